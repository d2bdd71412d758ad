#pragma once
/// The plan and the result of a single-mesh job (mesh_job.hpp): the low structs the reports
/// (mesh_report.hpp, mesh_html.hpp) and the run texts read.
#include <optional>
#include <string>
#include <vector>

#include "io/obj.hpp"
#include "io/ply.hpp"
#include "massage/massage.hpp"
#include "geometry/measures.hpp"
#include "pipeline/mesh_jobs/mesh_job_options.hpp"

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

}  // namespace sm
