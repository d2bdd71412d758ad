#pragma once
/// The track job's options ("job": "track"): a folder of raw frames of any connectivity, the
/// template (a frame of the folder or a clean mesh), the tracker's options (track/track_options.hpp)
/// and the Mesh Massage refinement's, and the sequence job's "output" object, whose per-frame
/// outputs the tracked frames go through. Cross-field rules are the config's (config/config.cpp).
#include <filesystem>

#include <nlohmann/json_fwd.hpp>

#include "massage/massage.hpp"
#include "core/frame_selection.hpp"
#include "core/options_table.hpp"
#include "pipeline/sequence/job_kind.hpp"
#include "pipeline/sequence/sequence_options.hpp"
#include "pipeline/sequence/shard.hpp"
#include "track/track_options.hpp"

namespace sm {

/// "input" of the track job.
struct TrackInputOptions {
  std::filesystem::path frames;  ///< a folder of .obj, .ply and .off files, one per frame
  FrameRange range;
};

template <>
inline const Fields<TrackInputOptions>& fields_of<TrackInputOptions>() {
  using O = TrackInputOptions;
  static const Fields<O> fields = {
      field<&O::frames>("frames", any_value(),
                        "the raw frames: the folder's `.obj`, `.ply` and `.off` files in natural "
                        "order, each with its own vertices and triangles")
          .required("a folder of raw frames (.obj, .ply, .off)"),
      field<&O::range>("range", any_value(),
                       "which frames to track, like a Python slice `[start:stop:step]` of the "
                       "frames in natural order, tracked in that order; `--frames A:B[:STEP]` "
                       "replaces it"),
  };
  return fields;
}

/// "template" of the track job: a raw frame as captured, or a clean mesh posed like one.
struct TrackTemplateOptions {
  int frame = 0;               ///< index of the template frame in the full list
  std::filesystem::path mesh;  ///< a clean mesh instead (its own connectivity)
};

template <>
inline const Fields<TrackTemplateOptions>& fields_of<TrackTemplateOptions>() {
  using O = TrackTemplateOptions;
  static const Fields<O> fields = {
      field<&O::frame>("frame", at_least(0),
                       "the template: this raw frame as captured (its connectivity, texture "
                       "coordinates and materials), indexed in the full list of frames")
          .written_if([](const O& t) { return t.mesh.empty(); }),
      field<&O::mesh>("mesh", any_value(),
                      "instead of a frame: a clean mesh of the subject (`.obj` with its texture "
                      "coordinates and materials, `.ply`, `.off`), placed like the first tracked "
                      "frame; it is aligned to it rigidly first when it does not fit as placed"),
  };
  return fields;
}

inline constexpr EnumName<JobKind> kTrackJobNames[] = {{"track", JobKind::Track}};

struct TrackJobOptions {
  JobKind job = JobKind::Track;
  TrackInputOptions input;
  TrackTemplateOptions templ;
  OutputOptions output;
  TrackOptions track;
  /// The refinement toward each raw frame (iterations: track.refine_iterations).
  MassageOptions massage = refinement_massage_options();
  int threads = 0;         ///< worker threads, 0 = one per core
  ShardOptions shard;      ///< this process's block of the selected frames (cluster job arrays)
  /// The file the options were read from (empty from code): an input the outputs must not
  /// overwrite. Not a config key.
  std::filesystem::path config_file;
};

template <>
inline const Fields<TrackJobOptions>& fields_of<TrackJobOptions>() {
  using O = TrackJobOptions;
  static const Fields<O> fields = {
      field<&O::job>("job", choice(kTrackJobNames), "the kind of job")
          .required("the kind of job: \"track\""),
      field<&O::input>("input", any_value(), "the raw frames")
          .required("\"frames\": a folder of raw frames (.obj, .ply, .off)"),
      field<&O::templ>("template", any_value(),
                       "the mesh tracked through the frames, whose connectivity every output "
                       "frame has: a raw frame (`frame`) or a clean mesh (`mesh`), not both"),
      field<&O::output>("output", any_value(),
                        "what is written under `output.dir`: the sequence job's outputs, on the "
                        "template's connectivity (`\"format\"`: `\"obj\"`, `\"pc2\"`, "
                        "`\"mdd\"` or `\"gltf\"`); \"before\" in the checker, coloured and report outputs is "
                        "the registration, \"after\" the refined result")
          .required("an object with \"dir\", the output folder"),
      field<&O::track>("track", any_value(),
                       "the tracker: deformation graph, non-rigid ICP, tolerances of a `lost` "
                       "frame, recovery; lengths in mean edge lengths of the template"),
      field<&O::massage>("massage", any_value(),
                         "the Mesh Massage refinement toward each raw frame (T = the template, "
                         "N = the raw frame); its `iterations` are `track.refine_iterations`"),
      field<&O::threads>("threads", threads_range(),
                         "worker threads inside each frame (frames are tracked in order); 0 = "
                         "one per core. `--threads` overrides"),
      field<&O::shard>("shard", any_value(),
                       "the block of the selected frames this process tracks, for job arrays on "
                       "a cluster: tracked from the template registered directly onto the "
                       "block's first frame (or from the template frame, in its block); "
                       "`--shard I/N` replaces it, `seqmassage merge` combines the shards"),
  };
  return fields;
}

/// The options with every key (defaults included), paths absolute.
nlohmann::json to_json(const TrackJobOptions& options);

/// The sequence job's options that the per-frame outputs are built from: the same output
/// folder and output keys, the input folder and the template.
SequenceJobOptions output_job_options(const TrackJobOptions& options);

}  // namespace sm
