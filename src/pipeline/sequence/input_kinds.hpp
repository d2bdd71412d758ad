#pragma once
/// The kinds of sequence input, described once: "frames", "synthetic", "gltf", "pc2" and "mdd"
/// under "input". The config check (exactly one given), the key table's "missing" text,
/// `seqmassage --help` and the frame-source factory (make_frame_source) read this list; adding an
/// input kind is one line here, its source, and its options in InputOptions.
#include <memory>
#include <string>
#include <vector>

namespace sm {

class FrameSource;
struct GltfSequence;
struct InputOptions;
struct SequenceJobOptions;

/// One kind of input.
struct InputKind {
  const char* key;   ///< its key under "input"
  const char* what;  ///< what it is, for messages: "a folder of OBJ frames"
  const char* help;  ///< its line of `--help`, after the key
  /// The config's input is of this kind (its key was given).
  bool (*given)(const InputOptions& input);
  /// Its frame source; a glTF source hands out the loaded asset through `gltf` (if given).
  std::shared_ptr<const FrameSource> (*make)(const SequenceJobOptions& config,
                                             std::shared_ptr<const GltfSequence>* gltf);
};

/// Every input kind, in the order messages and `--help` list them.
const std::vector<InputKind>& input_kinds();

/// `one of "frames" (a folder of OBJ frames), ... or "mdd" (...)`: what "input" misses.
const std::string& input_kinds_text();

/// The inputs part of `seqmassage --help`: one line per kind.
std::string inputs_help();

}  // namespace sm
