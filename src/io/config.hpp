#pragma once
/// The job configuration: a JSON file mapped one-to-one onto the options structs below (key names
/// in quotes), checked completely before anything runs.
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/distance.hpp"
#include "io/gltf_load.hpp"
#include "io/gltf_write.hpp"
#include "io/output_options.hpp"
#include "massage/massage.hpp"

namespace sm {

enum class JobKind {
  Sequence,    ///< "sequence": correct the texture swimming of a mesh sequence (paper §3.1)
  Remesh,      ///< "remesh": bring a remesh closer to its source surface (paper §3.3)
  Crossparam,  ///< "crossparam": copy a source mesh's triangle shapes onto a target (paper §3.2)
  Smooth,      ///< "smooth": feature-preserving smoothing, uniform weights (paper §4)
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

/// What a frame that fails its numerical checks gets as output ("output.on_failure").
enum class OnFailure {
  CopyInput,  ///< "copy_input": its input, unchanged (an OBJ frame byte for byte)
  Skip,       ///< "skip": nothing (no frame file, no distortion table; left out of sequence.glb)
};

struct OutputConfig {
  std::filesystem::path dir;                ///< "dir": output folder (required)
  OutputFormat format = OutputFormat::Obj;  ///< "format": "obj" or "gltf"
  GltfWriteOptions gltf;                    ///< "gltf": {"frames_per_mesh", "normals"}
  bool per_triangle_csv = false;            ///< "per_triangle_csv": write distortion/<frame>.csv
  /// "timings": run times in summary.csv and report.json; false writes 0 seconds, so that a run
  /// reproduces every output byte.
  bool timings = true;
  OnFailure on_failure = OnFailure::CopyInput;  ///< "on_failure": "copy_input" or "skip"
  ColoredOutputOptions colored;    ///< "colored": shear as coloured PLY meshes, before and after
  CheckerOutputOptions checker;    ///< "checker": frames with a checkerboard texture (OBJ+MTL+PNG)
  IterationLogOptions iterations;  ///< "iterations": iterations.csv
};

/// "checks": when an optimized frame fails, besides a failed solve and non-finite positions
/// (which always fail it). A folded triangle is an output triangle whose normal opposes the same
/// triangle's normal in the input frame; a frame fails when its folded triangles exceed either
/// limit. Real captures give a few per frame at most (README, "Failed frames").
struct FrameChecks {
  /// "max_folded_triangles": the most folded triangles a frame may have, >= 0; null: no limit.
  std::optional<int> max_folded_triangles;
  /// "max_folded_fraction": the most folded triangles a frame may have, as a fraction of its
  /// triangles, in [0, 1]; null: no limit.
  std::optional<double> max_folded_fraction = 0.005;
};

/// "shard": the part of the selected frames this process runs, for job arrays on a cluster: the
/// selected frames are cut into `count` contiguous blocks of (nearly) equal size, and shard `index`
/// runs block `index`. Its summary and report are named by shard (summary.shard-I-of-N.csv,
/// report.shard-I-of-N.json); `seqmassage merge` combines the shards.
struct ShardConfig {
  /// "index": 0-based, < count (a Slurm array task id, a Kubernetes completion index)
  int index = 0;
  int count = 1;  ///< "count": number of shards, >= 1; 1 = not sharded
  bool sharded() const { return count > 1; }
};

/// "measures" of the sequence job: how the distances of summary.csv (dist_out_to_in_*,
/// dist_in_to_out_*: each output frame against its input frame, both ways) are sampled. The keys
/// map onto DistanceOptions one-to-one: "spacing" (> 0, in mean edge lengths of the sampled
/// frame), "sample_edges", "sample_faces", "adaptive", "refine_above" (in [0, 1]). The job's
/// defaults differ from DistanceOptions' (which the mesh jobs keep) by measurement (README,
/// "Performance"): adaptive sampling at spacing 0.125 costs a third to a quarter of the uniform
/// sampling at 0.25 on the crane, samba and horse and finds the maximum of the uniform sampling
/// at 0.125; its RMS is the area integral.
/// corresponding_triangles is not a key: the job sets it (an output frame has its input's
/// triangles); it only speeds the search and changes no result.
DistanceOptions default_sequence_measures();

struct JobConfig {
  JobKind job = JobKind::Sequence;  ///< "job" (required)
  InputConfig input;                ///< "input" (required)
  TemplateConfig templ;             ///< "template"
  OutputConfig output;              ///< "output" (required)
  MassageOptions massage;           ///< "massage": every key of MassageOptions
  int threads = 0;                  ///< "threads": worker threads, 0 = one per core
  int frames_in_flight = 0;         ///< "frames_in_flight": frames held at once, 0 = 2 × threads
  FrameChecks checks;               ///< "checks"
  ShardConfig shard;                ///< "shard"
  /// "resume": skip the frames whose record (records/<frame>.json) shows that their outputs are
  /// complete and were made from the same config, template and input.
  bool resume = false;
  /// "measures": the sampling of summary.csv's distances
  DistanceOptions measures = default_sequence_measures();
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

/// Parses "I/N" (0 <= I < N) into a shard. Throws ConfigError naming `what` (e.g. "--shard").
ShardConfig parse_shard(std::string_view text, std::string_view what);

/// "I/N".
std::string format_shard(const ShardConfig& shard);

/// The range as "A:B:STEP" ("A::STEP" without a stop).
std::string format_frame_range(const FrameRange& range);

/// Levenshtein distance between two strings (for "did you mean" suggestions).
int edit_distance(std::string_view a, std::string_view b);

// ---------------------------------------------------------------------------------------------
// The single-mesh jobs: "remesh", "crossparam" and "smooth" (one mesh in, one mesh out).

/// "input" of a single-mesh job.
struct MeshJobInput {
  std::filesystem::path mesh;       ///< "mesh": M, the mesh to optimize (.obj, .off or .ply)
  std::filesystem::path reference;  ///< "reference": remesh only (required): N, the source surface
};

/// "output.format" of a single-mesh job.
enum class MeshOutputFormat {
  Same,  ///< "same": the input's format (an OBJ keeps its texture coordinates, groups, polygons)
  Obj,   ///< "obj"
  Off,   ///< "off"
  Ply,   ///< "ply" (binary little-endian)
};

struct MeshJobOutput {
  std::filesystem::path dir;                         ///< "dir": output folder (required)
  MeshOutputFormat format = MeshOutputFormat::Same;  ///< "format"
  bool per_triangle_csv = false;  ///< "per_triangle_csv": triangles.csv, quality per triangle
  bool timings = true;            ///< "timings": false leaves run times out (reproducible bytes)
};

/// "measures": how the report measures the meshes (paper Tables 1–3).
struct MeasureOptions {
  /// "spacing": distance between the Metro-style samples on edges and inside triangles, as a
  /// fraction of the sampled mesh's mean edge length, > 0.
  double spacing = 0.25;
  /// "feature_angle": an edge of the reference whose two triangles' normals differ by more than
  /// this many degrees is a feature (sharp) edge, in (0, 180).
  double feature_angle = 30.0;
  /// "shear_bins": increasing bin edges of the shear histogram (eq. 8); a last edge "inf" counts
  /// the degenerate triangles too.
  std::vector<double> shear_bins = {0.0, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, INFINITY};
};

struct MeshJobConfig {
  JobKind job = JobKind::Smooth;  ///< "job": "remesh", "crossparam" or "smooth" (required)
  MeshJobInput input;             ///< "input" (required)
  /// "template": {"mesh": path}, crossparam only (required there): T, a mesh with the input's
  /// connectivity whose triangle shapes are copied.
  std::filesystem::path template_mesh;
  MeshJobOutput output;     ///< "output" (required)
  MassageOptions massage;   ///< "massage": every key of MassageOptions, defaults by job
  MeasureOptions measures;  ///< "measures"
  int threads = 0;          ///< "threads": worker threads, 0 = one per core
};

/// The defaults of "massage" for a single-mesh job: MassageOptions' own for remesh and
/// crossparam; for smooth, uniform weights, 60 iterations, edge samples and μ = 0.7 (see README).
MassageOptions default_massage_options(JobKind job);

/// Any job's configuration.
using AnyJobConfig = std::variant<JobConfig, MeshJobConfig>;

/// The job kind named by "job" (required; ConfigError with the nearest kind for a typo).
JobKind parse_job_kind(const nlohmann::json& document);

/// The JSON name of a job kind ("sequence", "remesh", "crossparam", "smooth").
std::string job_name(JobKind job);

/// Maps a parsed single-mesh job config onto MeshJobConfig, with the same strictness and messages
/// as parse_config (keys of the sequence job's "input" are refused with a note). Relative paths
/// are made absolute against `base_dir`.
MeshJobConfig parse_mesh_job_config(const nlohmann::json& json,
                                    const std::filesystem::path& base_dir);

/// The resolved config with every key: parse_mesh_job_config of it gives the same config back.
nlohmann::json to_json(const MeshJobConfig& config);

/// Dispatches on "job": parse_config for "sequence", parse_mesh_job_config for the others.
AnyJobConfig parse_any_config(const nlohmann::json& json, const std::filesystem::path& base_dir);

/// load_config for any job kind.
AnyJobConfig load_any_config(const std::filesystem::path& path);

}  // namespace sm
