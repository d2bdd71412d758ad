#pragma once
/// The single-mesh jobs, with the paper's roles (M the mesh optimized, T the shape template, N the
/// reference surface):
///
///   "remesh"      §3.3  M = a remesh, T = M itself, N = its source surface (any connectivity)
///   "crossparam"  §3.2  M = a target mesh, T = a source mesh with M's connectivity, N = M as
///   loaded "smooth"      §4    M = the mesh, uniform (or mean value) weights of M, N = M as loaded
///
/// A job is planned (every input read and checked, nothing written), then run: one Massager run,
/// the paper's measures before and after, and the outputs <output.dir>/<input file name>,
/// measures.csv, report.json (and triangles.csv on request), each written atomically.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/obj.hpp"
#include "io/ply.hpp"
#include "massage/massage.hpp"
#include "pipeline/measures.hpp"
#include "pipeline/mesh_job_options.hpp"

namespace sm {

/// Everything a run needs, checked: built by plan_mesh_job without writing anything.
struct MeshJobPlan {
  MeshJobOptions config;
  TriMesh mesh;                ///< M as loaded
  std::optional<ObjFile> obj;  ///< the OBJ file as read, to write back (OBJ input only)
  PlyColors colors;            ///< colours of a PLY input, kept in a PLY output
  TriMesh reference;           ///< N: the source (remesh) or M as loaded
  TriMesh templ;               ///< T: the template (crossparam) or M as loaded
  std::string mesh_name;       ///< file names, for messages and reports
  std::string reference_name;
  std::string template_name;
  std::shared_ptr<const Massager> massager;  ///< built once from T
  std::filesystem::path output_mesh;         ///< <output.dir>/<input name>, format's extension
  int pinned_vertices = 0;                   ///< listed and (with pin_boundary) boundary vertices
  int threads = 1;                           ///< resolved worker threads
  std::vector<std::string> warnings;
};

/// Result of a run.
struct MeshJobResult {
  MeshMeasures before;                ///< M as loaded against N (shear against T)
  std::optional<MeshMeasures> after;  ///< the output against N; empty if the optimizer failed
  Positions V;                        ///< the output positions (M's on failure)
  MassageResult massage;              ///< per-iteration statistics, failure reason
  std::vector<std::string> warnings;
  double seconds = 0.0;          ///< wall time of the whole run
  double seconds_massage = 0.0;  ///< of the optimizer alone
  bool ok() const { return massage.ok; }
};

/// Reads the mesh (and the reference or template), checks them (connectivity of the template,
/// mesh validity, options such as pinned indices) and builds the Massager; refuses an output that
/// would overwrite an input. Throws ConfigError, InputError (naming the file) or IoError.
MeshJobPlan plan_mesh_job(const MeshJobOptions& config);

/// What a run of `plan` would do, several lines of text (for --dry-run).
std::string describe_mesh_plan(const MeshJobPlan& plan);

/// Runs the job and writes its outputs, holding the output folder's lock (lock_output_folder:
/// IoError if another run holds it). A numerical failure of the optimizer is recorded in the
/// result (no mesh is written then; measures.csv holds the "before" row and report.json the
/// reason), not thrown. Same plan, same output bytes (apart from timings) for any thread count.
MeshJobResult run_mesh_job(const MeshJobPlan& plan);

/// The output mesh's path for `config`: <output.dir>/<input file name>, with the extension of
/// output.format unless it is "same".
std::filesystem::path mesh_output_path(const MeshJobOptions& config);

}  // namespace sm
