#pragma once
/// The corrected frames, the sequence job's main output (output.format): one OBJ file per frame
/// (frames/<frame name>), or one GLB that plays the whole sequence (sequence.glb, glTF input
/// only), assembled when the run ends from one positions file per frame (positions/<frame>.bin).
#include "pipeline/outputs/frame_output.hpp"

namespace sm {

/// positions/<frame name>.bin, relative to output.dir: a frame's corrected positions (exact
/// little-endian doubles, n×3 row-major) that a whole-sequence output is assembled from.
std::filesystem::path positions_file(const std::string& frame_name);

/// The positions file of frame `frame_name` under `output_dir`, read back (n vertices). Throws
/// IoError when it is missing or has the wrong size.
Positions read_positions_file(const std::filesystem::path& output_dir,
                              const std::string& frame_name, Eigen::Index n);

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

/// "format": "gltf": each frame's corrected welded positions go to positions/<frame>.bin (exact
/// little-endian doubles, n×3 row-major: 24 bytes per vertex), from which finish() assembles
/// sequence.glb (write_gltf_sequence), reading them back one at a time: memory holds the frames
/// in flight and the GLB being assembled, never all frames as well. The positions files stay:
/// --resume and `seqmassage merge` rebuild the GLB from them. A shard writes the positions only.
/// Throws ConfigError when built without a glTF input.
class GlbFramesOutput : public FrameOutput {
 public:
  explicit GlbFramesOutput(const OutputContext& context);
  static bool enabled(const SequenceJobOptions& config);
  static const char* help();

  std::vector<std::filesystem::path> files(const std::vector<int>& frames) const override;
  std::vector<std::filesystem::path> folders() const override;
  std::string describe(const std::vector<int>& frames) const override;
  nlohmann::json report() const override;
  ResultNames results() const override;
  OutputFrame encode(const FrameOutcome& frame) const override;
  /// Writes output.dir/sequence.glb of `done`'s frames, in order; a warning and no file when
  /// there is none. Throws IoError when a positions file is missing or has the wrong size.
  OutputFinish finish(const FinishedFrames& done) const override;

 private:
  SequenceJobOptions config_;
  std::shared_ptr<const FrameSource> source_;
  std::shared_ptr<const GltfSequence> gltf_;
};

}  // namespace sm
