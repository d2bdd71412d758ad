#pragma once
/// output.checker: the frames with a checkerboard texture on the template's texture coordinates,
/// checker/before|after/<frame>.obj, with checker.mtl and checker.png beside them (written once,
/// with the first checker frame): texture swimming shows as squares that slide over the surface.
#include <optional>

#include "pipeline/outputs/checker.hpp"
#include "pipeline/outputs/output_before_after.hpp"

namespace sm {

class CheckerObjOutput : public BeforeAfterOutput {
 public:
  explicit CheckerObjOutput(const OutputContext& context);
  static bool enabled(const SequenceJobOptions& config);
  static const char* help();

  std::string describe(const std::vector<int>& frames) const override;
  /// With the texture coordinates' source, known once the run has started.
  nlohmann::json report() const override;
  ResultNames results() const override;
  /// Reads the template's texture coordinates: the template frame as read (after the source is
  /// prepared), or the template mesh's file for an OBJ template.
  void start(const SequencePlan& plan) override;
  std::vector<std::pair<std::filesystem::path, std::string>> shared_files() const override;

 private:
  std::optional<std::pair<std::string, std::string>> encode_sides(
      const FrameOutcome& frame) const override;
  std::vector<std::string> side_files() const override;

  CheckerOutputOptions options_;
  std::filesystem::path template_mesh_;  // template.mesh, if any
  std::string template_source_;
  std::optional<CornerUv> uv_;  // from start()
};

}  // namespace sm
