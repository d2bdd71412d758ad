#pragma once
/// output.colored: the shear (eq. 8) as coloured PLY meshes, colored/before|after/<frame>.ply,
/// blue (0) to red (output.colored.max and above), per face or per vertex.
#include "pipeline/outputs/frame_output.hpp"

namespace sm {

class ColoredPlyOutput : public FrameOutput {
 public:
  explicit ColoredPlyOutput(const OutputContext& context);
  static bool enabled(const SequenceJobOptions& config);
  static const char* help();

  std::vector<std::filesystem::path> files(const std::vector<int>& frames) const override;
  std::vector<std::filesystem::path> folders() const override;
  std::string describe(const std::vector<int>& frames) const override;
  std::vector<std::string> check(const std::vector<int>& selected) const override;
  nlohmann::json report() const override;
  ResultNames results() const override;
  OutputFrame encode(const FrameOutcome& frame) const override;

 private:
  std::filesystem::path dir_;
  ColoredOutputOptions options_;
  std::shared_ptr<const FrameSource> source_;
};

}  // namespace sm
