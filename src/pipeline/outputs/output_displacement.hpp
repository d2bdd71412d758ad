#pragma once
/// output.displacement_csv: displacement/<frame>.csv, how far the massage moved every vertex
/// (output − input, n rows), so the correction can be carried onto data that shares the frame's
/// vertices (a higher-resolution bake, per-vertex attributes, another cache of the same take).
#include "pipeline/outputs/output_frame_csv.hpp"

namespace sm {

/// displacement/<frame>.csv: `vertex,dx,dy,dz`, one row per vertex (0-based), output − input.
std::string format_displacement_csv(const Positions& input, const Positions& output);

class DisplacementCsvOutput : public FrameCsvOutput {
 public:
  explicit DisplacementCsvOutput(const OutputContext& context)
      : FrameCsvOutput(context, "displacement") {}
  static bool enabled(const SequenceJobOptions& config);
  static const char* help();

 protected:
  std::string table(const FrameOutcome& frame) const override;
};

}  // namespace sm
