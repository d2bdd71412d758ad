#pragma once
/// output.displacement_csv: displacement/<frame>.csv, how far the massage moved every vertex
/// (output − input, n rows), so the correction can be carried onto data that shares the frame's
/// vertices (a higher-resolution bake, per-vertex attributes, another cache of the same take).
#include "pipeline/frame_output.hpp"

namespace sm {

/// displacement/<frame>.csv: `vertex,dx,dy,dz`, one row per vertex (0-based), output − input.
std::string format_displacement_csv(const Positions& input, const Positions& output);

class DisplacementCsvOutput : public FrameOutput {
 public:
  explicit DisplacementCsvOutput(const OutputContext& context);
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
