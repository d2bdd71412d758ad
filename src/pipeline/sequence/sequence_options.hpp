#pragma once
/// The sequence job's options ("job": "sequence"): the config's objects map one-to-one onto the
/// structs below and the other modules' options nested in them, each with its table
/// (fields_of). Cross-field rules (one input kind, a template frame or mesh, ...) are the
/// config's (config/config.hpp).
#include <filesystem>
#include <optional>

#include <nlohmann/json_fwd.hpp>

#include "geometry/distance.hpp"
#include "geometry/distance_keys.hpp"
#include "io/gltf/gltf_load.hpp"
#include "io/gltf/gltf_write.hpp"
#include "io/point_cache.hpp"
#include "massage/massage.hpp"
#include "massage/massage_keys.hpp"
#include "core/frame_selection.hpp"
#include "core/options_table.hpp"
#include "pipeline/sequence/fold_check.hpp"
#include "pipeline/sequence/output_options.hpp"
#include "pipeline/sequence/input_kinds.hpp"
#include "pipeline/sequence/iteration_log.hpp"
#include "pipeline/sequence/job_kind.hpp"
#include "pipeline/sequence/shard.hpp"
#include "pipeline/sequence/synthetic.hpp"

namespace sm {

/// A point cache input, {"pc2": file, "mesh": file} (or "mdd"): the cache gives every frame's
/// positions, the mesh their connectivity, texture coordinates and materials.
template <PointCacheFormat Format>
struct PointCacheInputOptions {
  static constexpr PointCacheFormat format = Format;
  std::filesystem::path file;  ///< the .pc2 or .mdd file
  std::filesystem::path mesh;  ///< .obj, .ply or .off with the cache's vertex count
};
using Pc2InputOptions = PointCacheInputOptions<PointCacheFormat::Pc2>;
using MddInputOptions = PointCacheInputOptions<PointCacheFormat::Mdd>;

/// The keys sit in the sequence job's "input"; "pc2" (or "mdd") comes first: it says the input is
/// a point cache.
template <PointCacheFormat Format>
const Fields<PointCacheInputOptions<Format>>& point_cache_input_fields(std::string_view key,
                                                                         std::string_view doc,
                                                                         std::string_view mesh) {
  using O = PointCacheInputOptions<Format>;
  static const Fields<O> fields = {field<&O::file>(key, any_value(), doc),
                                   field<&O::mesh>("mesh", any_value(), mesh)};
  return fields;
}
template <>
inline const Fields<Pc2InputOptions>& fields_of<Pc2InputOptions>() {
  return point_cache_input_fields<PointCacheFormat::Pc2>(
      "pc2",
      "a PC2 point cache (little-endian, `POINTCACHE2`): one frame per sample, on the "
      "connectivity of `input.mesh`; see [point caches](point-caches.md)",
      "with `input.pc2` (required there): the mesh (`.obj`, `.ply` or `.off`, the cache's vertex "
      "count) that gives the frames' triangles, texture coordinates and materials; the template "
      "unless `template` says otherwise");
}
template <>
inline const Fields<MddInputOptions>& fields_of<MddInputOptions>() {
  return point_cache_input_fields<PointCacheFormat::Mdd>(
      "mdd",
      "an MDD point cache (big-endian, with frame times): one frame per cache frame, on the "
      "connectivity of `input.mesh`",
      "with `input.mdd` (required there): the mesh, as for `input.pc2`");
}

/// The point cache of an input, whichever its format.
struct PointCacheInput {
  PointCacheFormat format = PointCacheFormat::Pc2;
  std::filesystem::path file, mesh;
};

/// "input": exactly one of "frames", "synthetic", "gltf", "pc2" and "mdd", and "range".
struct InputOptions {
  std::filesystem::path frames;  ///< a folder of OBJ files, one per frame, in natural order
  /// Generate the frames into <output.dir>/input and the clean frames (the ground truth) into
  /// <output.dir>/ground_truth, then process them like a folder.
  std::optional<SyntheticOptions> synthetic;
  std::optional<GltfInputOptions> gltf;  ///< keys "gltf", "mesh", "animation", "fps"
  std::optional<Pc2InputOptions> pc2;    ///< keys "pc2", "mesh"
  std::optional<MddInputOptions> mdd;    ///< keys "mdd", "mesh"
  FrameRange range;

  /// The point cache input ("pc2" or "mdd"), if that is the input.
  std::optional<PointCacheInput> point_cache() const {
    if (pc2) return PointCacheInput{pc2->format, pc2->file, pc2->mesh};
    if (mdd) return PointCacheInput{mdd->format, mdd->file, mdd->mesh};
    return std::nullopt;
  }
};

template <>
inline const Fields<InputOptions>& fields_of<InputOptions>() {
  using O = InputOptions;
  static const Fields<O> fields = {
      field<&O::frames>("frames", any_value(),
                        "the frames: the folder's `.obj` files in natural order (`frame_2` before "
                        "`frame_10`), all with frame 0's vertex count and faces"),
      field<&O::synthetic>("synthetic", any_value(),
                           "a generated drifted sequence: a tube bending over time whose vertices "
                           "slide tangentially by a smooth time-varying field (frame 0 straight "
                           "and undrifted), written to `<output.dir>/input` and its clean frames "
                           "(ground truth) to `<output.dir>/ground_truth`, then processed like a "
                           "folder; `{}` takes every default"),
      inline_field<&O::gltf>("a glTF animation"),
      inline_field<&O::pc2>("a PC2 point cache on a mesh"),
      inline_field<&O::mdd>("an MDD point cache on a mesh"),
      field<&O::range>("range", any_value(),
                       "which frames to process, like a Python slice `[start:stop:step]` of the "
                       "frames in natural order; `--frames A:B[:STEP]` replaces it"),
  };
  return fields;
}

struct TemplateOptions {
  int frame = 0;               ///< index of the template frame in the full list
  std::filesystem::path mesh;  ///< a rest mesh with the frames' connectivity, instead
  bool optimize = false;       ///< optimize the template frame too ("frame" only)
};

template <>
inline const Fields<TemplateOptions>& fields_of<TemplateOptions>() {
  using O = TemplateOptions;
  static const Fields<O> fields = {
      field<&O::frame>("frame", at_least(0),
                       "the template frame, indexed in the full list of frames (not in "
                       "`input.range`), below the number of frames")
          .written_if([](const O& t) { return t.mesh.empty(); }),
      field<&O::mesh>("mesh", any_value(),
                      "instead of a frame: a rest mesh (`.obj`, `.off` or `.ply`) with the frames' "
                      "vertex count and triangles; every selected frame is then optimized. Not "
                      "with `input.synthetic`"),
      field<&O::optimize>("optimize", any_value(),
                          "optimize the template frame too; `false` writes it unchanged (with "
                          "`template.frame` only)"),
  };
  return fields;
}

enum class OutputFormat {
  Obj,   ///< frames/<frame name>.obj
  Gltf,  ///< sequence.glb, one morph target per frame (glTF input only)
  Pc2,   ///< sequence.pc2 and rest.obj
  Mdd,   ///< sequence.mdd and rest.obj
};
inline constexpr EnumName<OutputFormat> kOutputFormatNames[] = {{"obj", OutputFormat::Obj},
                                                                {"gltf", OutputFormat::Gltf},
                                                                {"pc2", OutputFormat::Pc2},
                                                                {"mdd", OutputFormat::Mdd}};

/// The point cache format of an output format, if it is one.
inline std::optional<PointCacheFormat> point_cache_format(OutputFormat format) {
  if (format == OutputFormat::Pc2) return PointCacheFormat::Pc2;
  if (format == OutputFormat::Mdd) return PointCacheFormat::Mdd;
  return std::nullopt;
}

/// "output.point_cache": how a PC2 or MDD output states its frames' times.
struct PointCacheOutputOptions {
  /// Frames per second of an input without frame times (OBJ folder, synthetic, PC2): MDD frame
  /// times are frame numbers / fps.
  double fps = 24.0;
};

template <>
inline const Fields<PointCacheOutputOptions>& fields_of<PointCacheOutputOptions>() {
  using O = PointCacheOutputOptions;
  static const Fields<O> fields = {
      field<&O::fps>("fps", left_open(0, 1e6),
                     "MDD frame times (seconds) of an input without times (OBJ folder, "
                     "synthetic, PC2): the frame number (a PC2's start + index × sample rate, "
                     "else the index) / fps; glTF and MDD inputs keep their times"),
  };
  return fields;
}

/// What a frame that fails its numerical checks gets as output ("output.on_failure").
enum class OnFailure {
  CopyInput,  ///< its input, unchanged (an OBJ frame byte for byte)
  Skip,       ///< nothing (no frame file, no distortion table; left out of sequence.glb)
};
inline constexpr EnumName<OnFailure> kOnFailureNames[] = {{"copy_input", OnFailure::CopyInput},
                                                          {"skip", OnFailure::Skip}};

struct OutputOptions {
  std::filesystem::path dir;
  OutputFormat format = OutputFormat::Obj;
  GltfWriteOptions gltf;
  PointCacheOutputOptions point_cache;
  bool per_triangle_csv = false;
  bool displacement_csv = false;
  bool timings = true;  ///< false: 0 seconds, so that a run reproduces every output byte
  bool html = true;            ///< report.html (output_html.hpp)
  double html_max_mb = 50.0;   ///< report.html's size budget, in MiB
  OnFailure on_failure = OnFailure::CopyInput;
  ColoredOutputOptions colored;
  CheckerOutputOptions checker;
  IterationLogOptions iterations;
};

template <>
inline const Fields<OutputOptions>& fields_of<OutputOptions>() {
  using O = OutputOptions;
  static const Fields<O> fields = {
      field<&O::dir>("dir", any_value(),
                     "where everything is written; a folder whose outputs would overwrite an "
                     "input is refused")
          .required("the folder the results are written to"),
      field<&O::format>("format", choice(kOutputFormatNames),
                        "`\"obj\"`: `frames/<input name>.obj`; `\"gltf\"`: `sequence.glb`, one "
                        "morph target per frame (needs `input.gltf`, whose mesh, materials and "
                        "textures it keeps); `\"pc2\"`, `\"mdd\"`: `sequence.pc2` / "
                        "`sequence.mdd`, every frame's positions as float32, and `rest.obj`, the "
                        "template mesh the cache applies to"),
      field<&O::gltf>("gltf", any_value(), "the GLB's layout; only with `\"format\": \"gltf\"`")
          .written_if([](const O& o) { return o.format == OutputFormat::Gltf; }),
      field<&O::point_cache>("point_cache", any_value(),
                             "the cache's frame times; only with `\"format\": \"pc2\"` or "
                             "`\"mdd\"`")
          .written_if([](const O& o) { return point_cache_format(o.format).has_value(); }),
      field<&O::per_triangle_csv>("per_triangle_csv", any_value(),
                                  "also write `distortion/<frame name>.csv`: "
                                  "`triangle,shear_before,shear_after` (eq. 8)"),
      field<&O::displacement_csv>("displacement_csv", any_value(),
                                  "also write `displacement/<frame name>.csv`: `vertex,dx,dy,dz`, "
                                  "each vertex's output minus its input (the correction, to carry "
                                  "onto data that shares the frame's vertices)"),
      field<&O::timings>("timings", any_value(),
                         "run times in `summary.csv` and `report.json`; `false` writes 0 in "
                         "`summary.csv`'s `seconds` and leaves `report.json`'s `run` out, so "
                         "that a run reproduces every output byte"),
      field<&O::colored>("colored", any_value(),
                         "shear (eq. 8) as coloured PLY meshes, `colored/before/` and "
                         "`colored/after/` (the paper's Figure 4)"),
      field<&O::checker>("checker", any_value(),
                         "the frames with a checkerboard texture on the template's texture "
                         "coordinates (OBJ + MTL + PNG), `checker/before/` and `checker/after/` "
                         "(Figure 6)"),
      field<&O::iterations>("iterations", any_value(),
                            "`iterations.csv`: one row per frame and iteration (μ, energy, "
                            "distances, solver; Figure 8)"),
      field<&O::html>("html", any_value(),
                      "`report.html`: one self-contained page of the run (plots, tables, a 3D "
                      "player of the frames before and after) that opens from the folder in any "
                      "browser with no network; its data in `report_data/`. See "
                      "[outputs](outputs.md#reporthtml)"),
      field<&O::html_max_mb>("html_max_mb", left_open(0, 1e6),
                             "`report.html`'s size budget in MiB (2^20 bytes): when the "
                             "player's frames do not fit, it keeps evenly spaced frames (first "
                             "and last included) and says so")
          .written_if([](const O& o) { return o.html; }),
      field<&O::on_failure>("on_failure", choice(kOnFailureNames),
                            "the output of a failed frame: its input unchanged (an OBJ frame "
                            "byte for byte), or nothing"),
  };
  return fields;
}

/// The sampling of summary.csv's distances (dist_out_to_in_*, dist_in_to_out_*: each output
/// frame against its input frame, both ways): DistanceOptions' but adaptive at spacing 0.125,
/// which costs a third to a quarter of the uniform sampling at 0.25 on the crane, samba and horse
/// and finds the maximum of the uniform sampling at 0.125; its RMS is the area integral.
/// corresponding_triangles is set (an output frame has its input's triangles): it only speeds the
/// search.
DistanceOptions default_sequence_measures();

inline constexpr EnumName<JobKind> kSequenceJobNames[] = {{"sequence", JobKind::Sequence}};

struct SequenceJobOptions {
  JobKind job = JobKind::Sequence;
  InputOptions input;
  TemplateOptions templ;
  OutputOptions output;
  MassageOptions massage;
  int threads = 0;           ///< worker threads, 0 = one per core
  int frames_in_flight = 0;  ///< frames held at once, 0 = 2 × threads
  FrameCheckOptions checks;
  ShardOptions shard;
  bool resume = false;
  DistanceOptions measures = default_sequence_measures();
  /// The file the options were read from (load_config; empty from code): an input the outputs
  /// must not overwrite. Not a config key.
  std::filesystem::path config_file;
};

template <>
inline const Fields<SequenceJobOptions>& fields_of<SequenceJobOptions>() {
  using O = SequenceJobOptions;
  static const Fields<O> fields = {
      field<&O::job>("job", choice(kSequenceJobNames), "the kind of job")
          .required("the kind of job: \"sequence\""),
      field<&O::input>("input", any_value(),
                       "the frames: exactly one of `input.frames`, `input.synthetic`, "
                       "`input.gltf`, `input.pc2` and `input.mdd`")
          .required(input_kinds_text()),
      field<&O::templ>("template", any_value(),
                       "T, whose triangle shapes every frame takes: a frame of the input "
                       "(`frame`) or a rest mesh (`mesh`), not both"),
      field<&O::output>("output", any_value(), "what is written under `output.dir`")
          .required("an object with \"dir\", the output folder"),
      field<&O::massage>("massage", any_value(), "the optimizer, the same for every job"),
      field<&O::measures>("measures", any_value(),
                          "the sampling of the Metro-style distances in `summary.csv` (`dist_*` "
                          "columns): exact point-to-surface distances from samples at the "
                          "vertices, along the edges and inside the triangles"),
      field<&O::threads>("threads", threads_range(),
                         "worker threads; 0 = one per core. `--threads` overrides"),
      field<&O::frames_in_flight>("frames_in_flight", closed(0, 1000000),
                                  "frames held in memory at once by the pipeline (read → "
                                  "optimize → write); 0 = 2 × threads. Memory does not grow "
                                  "with the number of frames"),
      field<&O::checks>("checks", any_value(),
                        "when an optimized frame fails, besides a failed solve and non-finite "
                        "positions, which always fail it. A folded triangle is an output "
                        "triangle whose normal opposes the same triangle's normal in the input "
                        "frame"),
      field<&O::shard>("shard", any_value(),
                       "the part of the selected frames this process runs, for job arrays on a "
                       "cluster; `--shard I/N` replaces it"),
      field<&O::resume>("resume", any_value(),
                        "skip the frames whose record (`records/<frame>.json`) shows complete "
                        "outputs of the same config, template and input; `--resume` sets it"),
  };
  return fields;
}

/// The options with every key (defaults included), paths absolute: the resolved config, which
/// reads back to the same options.
nlohmann::json to_json(const SequenceJobOptions& options);

}  // namespace sm
