#pragma once
/// The options of the single-mesh jobs ("job": "remesh", "crossparam" or "smooth"), each with its
/// table (fields_of). Which keys a job takes (a reference for remesh only, a template for
/// crossparam only) is the config's rule (config/config.hpp).
#include <filesystem>

#include <nlohmann/json_fwd.hpp>

#include "massage/massage.hpp"
#include "massage/massage_keys.hpp"
#include "core/options_table.hpp"
#include "pipeline/sequence/job_kind.hpp"
#include "geometry/measure_keys.hpp"
#include "geometry/measures.hpp"

namespace sm {

struct MeshInputOptions {
  std::filesystem::path mesh;       ///< M, the mesh to optimize (.obj, .off or .ply)
  std::filesystem::path reference;  ///< remesh only (required there): N, the source surface
};

template <>
inline const Fields<MeshInputOptions>& fields_of<MeshInputOptions>() {
  using O = MeshInputOptions;
  static const Fields<O> fields = {
      field<&O::mesh>("mesh", any_value(),
                      "M, the mesh to optimize (`.obj`, `.off` or `.ply`; polygons are "
                      "fan-triangulated for the optimizer, an OBJ output keeps them)")
          .required("the mesh file to optimize (.obj, .off or .ply)"),
      field<&O::reference>("reference", any_value(),
                           "remesh only (required there): N, the source surface the remesh "
                           "approximates (`.obj`, `.off` or `.ply`, any connectivity)"),
  };
  return fields;
}

/// "template" of the crossparam job (required there, refused by the others).
struct MeshTemplateOptions {
  std::filesystem::path mesh;  ///< T, a mesh with the input's connectivity
};

template <>
inline const Fields<MeshTemplateOptions>& fields_of<MeshTemplateOptions>() {
  static const Fields<MeshTemplateOptions> fields = {
      field<&MeshTemplateOptions::mesh>("mesh", any_value(),
                                        "T, the source mesh whose triangle shapes are copied: the "
                                        "same vertex count and the same triangles in the same "
                                        "order as M")
          .required("the source mesh, with the input's connectivity"),
  };
  return fields;
}

enum class MeshOutputFormat {
  Same,  ///< the input's format (an OBJ keeps its texture coordinates, groups, polygons)
  Obj,
  Off,
  Ply,  ///< binary little-endian
};
inline constexpr EnumName<MeshOutputFormat> kMeshOutputFormatNames[] = {
    {"same", MeshOutputFormat::Same},
    {"obj", MeshOutputFormat::Obj},
    {"off", MeshOutputFormat::Off},
    {"ply", MeshOutputFormat::Ply}};

struct MeshOutputOptions {
  std::filesystem::path dir;
  MeshOutputFormat format = MeshOutputFormat::Same;
  bool per_triangle_csv = false;  ///< triangles.csv, quality per triangle
  bool timings = true;            ///< false leaves run times out (reproducible bytes)
  bool html = true;               ///< report.html (mesh_html.hpp)
  double html_max_mb = 50.0;      ///< its size budget, in MiB
};

template <>
inline const Fields<MeshOutputOptions>& fields_of<MeshOutputOptions>() {
  using O = MeshOutputOptions;
  static const Fields<O> fields = {
      field<&O::dir>("dir", any_value(),
                     "where `<input file name>`, `measures.csv` and `report.json` are written; "
                     "refused if it would overwrite an input")
          .required("the folder the results are written to"),
      field<&O::format>("format", choice(kMeshOutputFormatNames),
                        "the result's format: `\"same\"` as the input (an OBJ keeps its texture "
                        "coordinates, groups, materials and polygons), or OBJ, OFF, binary "
                        "little-endian PLY"),
      field<&O::per_triangle_csv>("per_triangle_csv", any_value(),
                                  "also write `triangles.csv`: `triangle,radius_ratio_before,"
                                  "radius_ratio_after,shear_before,shear_after`"),
      field<&O::timings>("timings", any_value(),
                         "run times in `report.json`; `false` leaves them out (its `run` and "
                         "every iteration's `seconds`), so that a run reproduces every output "
                         "byte"),
      field<&O::html>("html", any_value(),
                      "`report.html`: one self-contained page of the run (the mesh before and "
                      "after in a 3D viewer coloured by shear, or radius ratio for `remesh`; the "
                      "measures, warnings, config); see [outputs](outputs.md#reporthtml)"),
      field<&O::html_max_mb>("html_max_mb", left_open(0, 1e6),
                             "`report.html`'s size budget in MiB; a mesh that does not fit is "
                             "left out of the viewer")
          .written_if([](const O& o) { return o.html; }),
  };
  return fields;
}

inline constexpr EnumName<JobKind> kMeshJobNames[] = {
    {"remesh", JobKind::Remesh}, {"crossparam", JobKind::Crossparam}, {"smooth", JobKind::Smooth}};

struct MeshJobOptions {
  JobKind job = JobKind::Smooth;
  MeshInputOptions input;
  MeshTemplateOptions templ;
  MeshOutputOptions output;
  MassageOptions massage;  ///< defaults by job: default_massage_options
  MeasureOptions measures;
  int threads = 0;  ///< worker threads, 0 = one per core
  /// The file the options were read from (load_config; empty from code): an input the outputs
  /// must not overwrite. Not a config key.
  std::filesystem::path config_file;
};

template <>
inline const Fields<MeshJobOptions>& fields_of<MeshJobOptions>() {
  using O = MeshJobOptions;
  static const Fields<O> fields = {
      field<&O::job>("job", choice(kMeshJobNames),
                     "remesh (§3.3), cross-parameterization (§3.2) or feature-preserving "
                     "smoothing (§4)")
          .required("the kind of job: \"remesh\", \"crossparam\" or \"smooth\""),
      field<&O::input>("input", any_value(), "the mesh (and for remesh its reference)"),
      field<&O::templ>("template", any_value(), "crossparam only (required there)"),
      field<&O::output>("output", any_value(), "what is written under `output.dir`")
          .required("an object with \"dir\", the output folder"),
      field<&O::massage>("massage", any_value(), "the optimizer, the same for every job"),
      field<&O::measures>("measures", any_value(), "how the report measures the meshes"),
      field<&O::threads>("threads", threads_range(),
                         "worker threads; 0 = one per core. `--threads` overrides"),
  };
  return fields;
}

/// The defaults of "massage" for a single-mesh job: MassageOptions' own for remesh and
/// crossparam; for smooth, uniform weights, the zero shape target, 60 iterations, edge samples
/// and μ = 0.7.
MassageOptions default_massage_options(JobKind job);

/// The options with every key, paths absolute: reads back to the same options.
nlohmann::json to_json(const MeshJobOptions& options);

}  // namespace sm
