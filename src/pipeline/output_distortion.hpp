#pragma once
/// output.per_triangle_csv: distortion/<frame>.csv, the shear (eq. 8) of every triangle before
/// and after.
#include <Eigen/Core>

#include "pipeline/frame_output.hpp"

namespace sm {

/// distortion/<frame>.csv: `triangle,shear_before,shear_after`, one row per triangle (0-based).
std::string format_distortion_csv(const Eigen::VectorXd& before, const Eigen::VectorXd& after);

class DistortionCsvOutput : public FrameOutput {
 public:
  explicit DistortionCsvOutput(const OutputContext& context);
  static bool enabled(const SequenceJobOptions& config);
  static const char* help();

  std::vector<std::filesystem::path> files(const std::vector<int>& frames) const override;
  std::vector<std::filesystem::path> folders() const override;
  std::string describe(const std::vector<int>& frames) const override;
  nlohmann::json report() const override;
  ResultNames results() const override;
  OutputFrame encode(const FrameOutcome& frame) const override;

 private:
  std::filesystem::path file(int index) const;  // relative to output.dir

  std::filesystem::path dir_;
  std::shared_ptr<const FrameSource> source_;
};

}  // namespace sm
