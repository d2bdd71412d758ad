#pragma once
/// output.per_triangle_csv: distortion/<frame>.csv, the shear (eq. 8) of every triangle before
/// and after.
#include <Eigen/Core>

#include "pipeline/outputs/output_frame_csv.hpp"

namespace sm {

/// distortion/<frame>.csv: `triangle,shear_before,shear_after`, one row per triangle (0-based).
std::string format_distortion_csv(const Eigen::VectorXd& before, const Eigen::VectorXd& after);

class DistortionCsvOutput : public FrameCsvOutput {
 public:
  explicit DistortionCsvOutput(const OutputContext& context)
      : FrameCsvOutput(context, "distortion") {}
  static bool enabled(const SequenceJobOptions& config);
  static const char* help();

 protected:
  std::string table(const FrameOutcome& frame) const override;
};

}  // namespace sm
