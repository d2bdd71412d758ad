#pragma once
/// Where a sequence job's corrected frames go: one OBJ file per frame (frames/<frame name>), or
/// one GLB that plays the whole sequence (sequence.glb, glTF input only), assembled from one
/// positions file per frame (positions/<frame>.bin). Frames are encoded in parallel, then handed to
/// the sink's writer in frame order, each into its own file (atomically); the writer completes a
/// whole-sequence output when the run ends (or `seqmassage merge` does, for a sharded run).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/frame_source.hpp"
#include "pipeline/sequence_options.hpp"

namespace sm {

/// The state of one run's output. Each frame's file (FrameSink::output_file under output.dir) is
/// written by the job itself, atomically, as soon as the frame is done, from any thread; the
/// writer's methods are called in frame order, from one thread at a time, once per frame of the
/// run that has an output.
class FrameWriter {
 public:
  virtual ~FrameWriter() = default;
  /// Frame `index` has its file in place (written by this run, or kept from an earlier one when
  /// resuming): a whole-sequence output includes it.
  virtual void keep(int index) = 0;
  /// Completes the output from the frames written and kept (all of them, or those done before an
  /// interruption); returns warnings. Throws IoError when a file cannot be written.
  virtual std::vector<std::string> finish() = 0;
};

class FrameSink {
 public:
  virtual ~FrameSink() = default;
  /// The files a run of frames `frames` writes (for the overwrite check).
  virtual std::vector<std::filesystem::path> files(const std::vector<int>& frames) const = 0;
  /// The file that frame `index`'s encoded bytes go to, relative to output.dir
  /// ("frames/frame_0007.obj", "positions/frame_0007.bin").
  virtual std::filesystem::path output_file(int index) const = 0;
  /// Plan lines, each "  <file>: <what>\n".
  virtual std::string describe(const std::vector<int>& frames) const = 0;
  /// report.json "outputs" entries (relative to output.dir).
  virtual nlohmann::json report() const = 0;
  /// The bytes stored for a frame read as `input` whose output positions are `V` (the input's
  /// positions when `unchanged`). Thread-safe.
  virtual std::string encode(const SourceFrame& input, const Positions& V,
                             bool unchanged) const = 0;
  /// Starts a run's output (nothing is written yet).
  virtual std::unique_ptr<FrameWriter> start() const = 0;
};

/// The sink of config.output.format for frames from `source`: "obj" writes
/// frames/<source.name(i)> (an OBJ input's unchanged frame byte for byte, other frames with the
/// input's statements and new positions); "gltf" writes each frame's corrected welded positions
/// to positions/<frame>.bin (exact little-endian doubles, n×3 row-major: 24 bytes per vertex),
/// from which sequence.glb is assembled when the run ends (assemble_sequence_glb), so that memory
/// holds the frames in flight and the GLB being assembled, never all frames as well. A shard of a
/// sharded run (config.shard) writes the positions only; `seqmassage merge` assembles the GLB.
/// "pc2" and "mdd" write the same positions files, from which sequence.pc2 / sequence.mdd and
/// rest.obj are assembled (assemble_point_cache, pipeline/point_cache_output.hpp).
/// Throws ConfigError for "gltf" with a source that is not a glTF animation.
std::shared_ptr<const FrameSink> make_frame_sink(const SequenceJobOptions& config,
                                                 std::shared_ptr<const FrameSource> source);

/// positions/<frame name>.bin, relative to output.dir: a frame's corrected positions (exact
/// little-endian doubles, n×3 row-major) from which a whole-sequence output is assembled.
std::filesystem::path positions_file(const std::string& frame_name);

/// Frame `index`'s positions file under `output_dir`, read back (n vertices). Throws IoError when
/// it is missing or has the wrong size.
Positions read_frame_positions(const std::filesystem::path& output_dir, const FrameSource& source,
                               int index, Eigen::Index n);

/// Writes output.dir/sequence.glb (see write_gltf_sequence) of the frames `frames` (in order) of
/// `source`, a glTF animation, from their positions files. Returns warnings (none, or that no frame
/// was given, so nothing was written). Throws IoError when a positions file is missing or has
/// the wrong size, or the GLB cannot be written.
std::vector<std::string> assemble_sequence_glb(const SequenceJobOptions& config,
                                               const FrameSource& source,
                                               const std::vector<int>& frames);

}  // namespace sm
