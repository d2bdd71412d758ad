#pragma once
/// The corrected frames, the sequence job's main output (output.format): one OBJ file per frame
/// (frames/<frame name>), or one GLB that plays the whole sequence (sequence.glb, glTF input
/// only), assembled when the run ends from one positions file per frame (positions/<frame>.bin).
#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/outputs/output_staged.hpp"

namespace sm {

/// "format": "obj": frames/<source name>; an OBJ input's unchanged frame byte for byte, other
/// frames with the input's statements and new positions.
class ObjFramesOutput : public FrameOutput {
 public:
  explicit ObjFramesOutput(const OutputContext& context);
  static bool enabled(const SequenceJobOptions& config);
  static const char* help();

  std::vector<std::filesystem::path> files(const std::vector<int>& frames) const override;
  std::vector<std::filesystem::path> folders() const override;
  std::string describe(const std::vector<int>& frames) const override;
  nlohmann::json report() const override;
  ResultNames results() const override;
  OutputFrame encode(const FrameOutcome& frame) const override;

 private:
  std::filesystem::path dir_;
  std::shared_ptr<const FrameSource> source_;
};

/// "format": "gltf": the frames' positions staged (StagedPositionsOutput), from which finish()
/// assembles sequence.glb (write_gltf_sequence), a morph target per frame. Throws ConfigError
/// when built without a glTF input.
class GlbFramesOutput : public StagedPositionsOutput {
 public:
  explicit GlbFramesOutput(const OutputContext& context);
  static bool enabled(const SequenceJobOptions& config);
  static const char* help();

  nlohmann::json report() const override;

 private:
  std::vector<std::string> assembled_files() const override;
  std::string describe_assembled(const std::vector<int>& frames) const override;
  void assemble(const FinishedFrames& done, const PositionsReader& read) const override;

  std::shared_ptr<const GltfSequence> gltf_;
};

}  // namespace sm
