#pragma once
/// The job configuration: a JSON file whose objects map one-to-one onto a job's options
/// (pipeline/sequence/sequence_options.hpp, pipeline/mesh_jobs/mesh_job_options.hpp) through their tables, checked
/// completely before anything runs: types, ranges and unknown keys by the tables
/// (io/options_json.hpp), the rules across keys here. Messages name the key by its JSON path.
#include <filesystem>
#include <variant>

#include <nlohmann/json.hpp>

#include "io/json_text.hpp"
#include "io/options_json.hpp"
#include "pipeline/mesh_jobs/mesh_job_options.hpp"
#include "pipeline/sequence/sequence_options.hpp"
#include "pipeline/track/track_job_options.hpp"

namespace sm {

/// Any job's options.
using AnyJobOptions = std::variant<SequenceJobOptions, MeshJobOptions, TrackJobOptions>;

/// Maps a parsed config onto the sequence job's options; relative paths are made absolute
/// against `base_dir`. Besides the tables' checks: exactly one input kind ("frames", "synthetic",
/// "gltf", "pc2", "mdd"), the glTF keys only with "gltf" ("mesh" also with "pc2" or "mdd", where
/// it is required), a template "frame" or "mesh" (not both; no "mesh" with a synthetic input), a
/// tube that does not fold onto itself, output.format "gltf" (and output.gltf) only with a glTF
/// input, output.point_cache only with "pc2" or "mdd", no "on_failure": "skip" with "pc2". A
/// point cache's mesh becomes template.mesh unless "template" names a frame or a mesh.
SequenceJobOptions parse_config(const nlohmann::json& json, const std::filesystem::path& base_dir);

/// The same for a single-mesh job; the sequence job's "input" and "template" keys are refused
/// with a note, as are "input.reference" except for remesh and "template" except for crossparam.
MeshJobOptions parse_mesh_job_config(const nlohmann::json& json,
                                     const std::filesystem::path& base_dir);

/// The same for the track job: a template "frame" or "mesh" (not both); output.format "obj",
/// "pc2" or "mdd" (no glTF input to rebuild a GLB from); no output.on_failure "skip" (a lost
/// frame is written as its best attempt); massage.iterations, if given, equal to
/// track.refine_iterations (which it is set to).
TrackJobOptions parse_track_config(const nlohmann::json& json,
                                   const std::filesystem::path& base_dir);

/// The job kind named by "job" (required; ConfigError with the nearest kind for a typo).
JobKind parse_job_kind(const nlohmann::json& document);

/// Dispatches on "job": parse_config for "sequence", parse_track_config for "track",
/// parse_mesh_job_config for the others.
AnyJobOptions parse_any_config(const nlohmann::json& json, const std::filesystem::path& base_dir);

/// Reads and checks a config file; relative paths resolve against the file's folder. Throws
/// IoError if the file cannot be read, ConfigError for invalid JSON (parse_json_strict) and for
/// any invalid key or value. Messages do not repeat the file's name.
SequenceJobOptions load_config(const std::filesystem::path& path);
AnyJobOptions load_any_config(const std::filesystem::path& path);

}  // namespace sm
