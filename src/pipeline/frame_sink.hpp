#pragma once
/// Where a sequence job's corrected frames go: one OBJ file per frame (frames/<frame name>), or
/// one GLB that plays the whole sequence (sequence.glb, glTF input only). Frames are encoded in
/// parallel, then handed to the sink's writer in frame order; the writer completes its output
/// when the run ends.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/config.hpp"
#include "pipeline/frame_source.hpp"

namespace sm {

/// The state of one run's output.
class FrameWriter {
 public:
  virtual ~FrameWriter() = default;
  /// Stores frame `index`'s encoded bytes. Called in frame order, from one thread at a time.
  virtual void write(int index, const std::string& bytes) = 0;
  /// Completes the output from the frames written (all of them, or those done before an
  /// interruption); returns warnings. Throws IoError when a file cannot be written.
  virtual std::vector<std::string> finish() = 0;
};

class FrameSink {
 public:
  virtual ~FrameSink() = default;
  /// The files a run of frames `frames` writes (for the overwrite check).
  virtual std::vector<std::filesystem::path> files(const std::vector<int>& frames) const = 0;
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
/// input's statements and new positions); "gltf" writes sequence.glb (see write_gltf_sequence)
/// from the corrected frames, which the run spools to a temporary file in frame order so that
/// memory does not hold them (only the GLB being assembled). Throws ConfigError for "gltf" with a
/// source that is not a glTF animation.
std::shared_ptr<const FrameSink> make_frame_sink(const JobConfig& config,
                                                 std::shared_ptr<const FrameSource> source);

}  // namespace sm
