#pragma once
/// The job configuration: a JSON file mapped one-to-one onto the options structs below (key names
/// in quotes), checked completely before anything runs.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "io/gltf_load.hpp"
#include "io/gltf_write.hpp"
#include "massage/massage.hpp"

namespace sm {

enum class JobKind {
  Sequence,  ///< "sequence": correct the texture swimming of a mesh sequence (paper §3.1)
};

/// "input.synthetic": a generated drifted sequence, a tube bending over time whose vertices slide
/// tangentially by a smooth time-varying field (frame 0 straight and undrifted).
struct SyntheticConfig {
  std::string shape = "bending_tube";  ///< "shape": "bending_tube"
  int frames = 24;                     ///< "frames": number of frames, >= 2
  int segments = 32;                   ///< "segments": vertices around the tube, >= 3
  int rings = 48;                      ///< "rings": segments along the tube, >= 1
  double radius = 0.5;                 ///< "radius": tube radius, > 0
  double length = 4.0;                 ///< "length": tube length, > 0
  double bend = 90.0;  ///< "bend": bend angle of the last frame in degrees, [0, 300]
  double drift = 0.6;  ///< "drift": slide amplitude in edge lengths, [0, 2]
  int seed = 1;        ///< "seed": seed of the drift field, >= 0
};

/// "input.range": which frames to process, as a Python slice [start, stop) by step of the frames
/// in natural order (the template frame is indexed in the full list).
struct FrameRange {
  int start = 0;            ///< "start": >= 0
  std::optional<int> stop;  ///< "stop": one past the last frame, >= start; null = to the end
  int step = 1;             ///< "step": >= 1
};

struct InputConfig {
  /// "frames": folder of OBJ files, one per frame, in natural order. Exactly one of "frames",
  /// "synthetic" and "gltf" is given.
  std::filesystem::path frames;
  /// "synthetic": generate the frames into <output.dir>/input and the clean frames (the ground
  /// truth) into <output.dir>/ground_truth, then process them like a folder.
  std::optional<SyntheticConfig> synthetic;
  /// "gltf": a glTF 2.0 animation (.gltf or .glb) sampled to frames, with the keys beside it:
  /// "mesh" (name or index; default: the first skinned, else morphed, else instantiated mesh),
  /// "animation" (name or index; default 0) and "fps" (> 0; default: the keyframe times).
  std::optional<GltfInputOptions> gltf;
  FrameRange range;  ///< "range"
};

struct TemplateConfig {
  int frame = 0;               ///< "frame": index of the template frame in the full list, >= 0
  std::filesystem::path mesh;  ///< "mesh": a rest mesh with the frames' connectivity, instead
  bool optimize = false;       ///< "optimize": optimize the template frame too ("frame" only)
};

enum class OutputFormat {
  Obj,   ///< "obj": frames/<frame name>.obj
  Gltf,  ///< "gltf": sequence.glb, one morph target per frame (glTF input only)
};

struct OutputConfig {
  std::filesystem::path dir;                ///< "dir": output folder (required)
  OutputFormat format = OutputFormat::Obj;  ///< "format": "obj" or "gltf"
  GltfWriteOptions gltf;                    ///< "gltf": {"frames_per_mesh", "normals"}
  bool per_triangle_csv = false;            ///< "per_triangle_csv": write distortion/<frame>.csv
  /// "timings": run times in summary.csv and report.json; false writes 0 seconds, so that a run
  /// reproduces every output byte.
  bool timings = true;
};

struct JobConfig {
  JobKind job = JobKind::Sequence;  ///< "job" (required)
  InputConfig input;                ///< "input" (required)
  TemplateConfig templ;             ///< "template"
  OutputConfig output;              ///< "output" (required)
  MassageOptions massage;           ///< "massage": every key of MassageOptions
  int threads = 0;                  ///< "threads": worker threads, 0 = one per core
  int frames_in_flight = 0;         ///< "frames_in_flight": frames held at once, 0 = 2 × threads
};

/// Reads and checks a config file; relative paths resolve against the file's folder. Throws
/// IoError if the file cannot be read, ConfigError for invalid JSON (see parse_json_strict) and
/// for any invalid key or value (see parse_config). Messages do not repeat the file's name.
JobConfig load_config(const std::filesystem::path& path);

/// Parses JSON text strictly: no comments, no duplicate keys, no trailing content. Throws
/// ConfigError "line L, column C: <reason>" (or "<path>: duplicate key ...") on the first problem.
nlohmann::json parse_json_strict(std::string_view text);

/// Maps a parsed config onto JobConfig. Every message names the key by its JSON path, e.g.
/// `massage.iterations: expected an integer >= 1, got "ten"`, and suggests the nearest key for an
/// unknown one. Relative paths are made absolute against `base_dir`.
JobConfig parse_config(const nlohmann::json& json, const std::filesystem::path& base_dir);

/// The resolved config with every key (defaults included), paths absolute: parse_config of it
/// gives the same config back.
nlohmann::json to_json(const JobConfig& config);

/// Parses "A:B[:STEP]" (B may be empty: to the end) into a range. Throws ConfigError naming
/// `what` (e.g. "--frames").
FrameRange parse_frame_range(std::string_view text, std::string_view what);

/// The range as "A:B:STEP" ("A::STEP" without a stop).
std::string format_frame_range(const FrameRange& range);

/// Levenshtein distance between two strings (for "did you mean" suggestions).
int edit_distance(std::string_view a, std::string_view b);

}  // namespace sm
