#pragma once
/// output.colored: the shear (eq. 8) as coloured PLY meshes, colored/before|after/<frame>.ply,
/// blue (0) to red (output.colored.max and above), per face or per vertex.
#include "pipeline/outputs/output_before_after.hpp"

namespace sm {

class ColoredPlyOutput : public BeforeAfterOutput {
 public:
  explicit ColoredPlyOutput(const OutputContext& context);
  static bool enabled(const SequenceJobOptions& config);
  static const char* help();

  std::string describe(const std::vector<int>& frames) const override;
  nlohmann::json report() const override;
  ResultNames results() const override;

 private:
  std::optional<std::pair<std::string, std::string>> encode_sides(
      const FrameOutcome& frame) const override;

  ColoredOutputOptions options_;
};

}  // namespace sm
