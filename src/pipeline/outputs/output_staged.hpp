#pragma once
/// Outputs assembled from staged positions: each frame's corrected positions go to
/// positions/<frame>.bin (exact little-endian doubles, n×3 row-major: 24 bytes per vertex), and
/// finish() assembles the whole-sequence files from them, reading them back one at a time in
/// frame order: memory holds the frames in flight and the file being assembled, never all frames
/// as well. The positions files stay: --resume and `seqmassage merge` rebuild the assembled files
/// from them. A shard writes the positions only. sequence.glb and the point caches derive from it.
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "pipeline/outputs/frame_output.hpp"

namespace sm {

/// positions/<frame name>.bin, relative to output.dir: a frame's corrected positions (exact
/// little-endian doubles, n×3 row-major) that a whole-sequence output is assembled from.
std::filesystem::path positions_file(const std::string& frame_name);

/// The positions file of frame `frame_name` under `output_dir`, read back (n vertices). Throws
/// IoError when it is missing or has the wrong size.
Positions read_positions_file(const std::filesystem::path& output_dir,
                              const std::string& frame_name, Eigen::Index n);

/// The base of the outputs assembled from positions/<frame>.bin: it owns the per-frame files,
/// the plan's lines for them, the shard rule and the ordered read-back; a derived output says
/// what it assembles (assembled_files, describe_assembled, assemble).
class StagedPositionsOutput : public FrameOutput {
 public:
  std::vector<std::filesystem::path> files(const std::vector<int>& frames) const final;
  std::vector<std::filesystem::path> folders() const final;
  std::string describe(const std::vector<int>& frames) const final;
  ResultNames results() const final;
  OutputFrame encode(const FrameOutcome& frame) const final;
  /// Nothing in a shard (`seqmassage merge` assembles); a warning and no file when no frame is
  /// done; else assemble(). Throws IoError when a positions file is missing or has the wrong
  /// size or a file cannot be written.
  OutputFinish finish(const FinishedFrames& done) const final;

 protected:
  explicit StagedPositionsOutput(const OutputContext& context);

  /// Frame k of `done` (k = 0, 1, ... in order): its positions, read back (n vertices).
  using PositionsReader = std::function<Positions(int k, Eigen::Index n)>;

  /// The files assembled from the positions, relative to output.dir, in the results line's order.
  virtual std::vector<std::string> assembled_files() const = 0;
  /// The dry run's line(s) for them, each "  <file> (<what>)\n", for a whole (unsharded) run.
  virtual std::string describe_assembled(const std::vector<int>& frames) const = 0;
  /// Writes assembled_files() from `done`'s frames (at least one), each read once, in order.
  virtual void assemble(const FinishedFrames& done, const PositionsReader& read) const = 0;

  /// The frames' source; built from the config on first use where the output has none (merge).
  const FrameSource& source() const;

  SequenceJobOptions config_;

 private:
  mutable std::shared_ptr<const FrameSource> source_;
  mutable std::once_flag source_once_;
};

}  // namespace sm
