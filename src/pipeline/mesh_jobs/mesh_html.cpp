#include "pipeline/mesh_jobs/mesh_html.hpp"

#include "geometry/quality.hpp"
#include "geometry/shear.hpp"
#include "pipeline/outputs/checker.hpp"
#include "pipeline/report/html_sequence.hpp"

namespace sm {

std::string mesh_html_page(const MeshJobPlan& plan, const MeshJobResult& result,
                           const std::string& measures_csv, const nlohmann::json& report) {
  const MeshJobOptions& c = plan.config;
  const bool remesh = c.job == JobKind::Remesh;
  const TriMesh output{result.V, plan.mesh.F};
  // The colours' measure per triangle: radius ratio (remesh: T is M itself, its shear is 0
  // before) or the shear against T.
  const auto measure = [&](const TriMesh& m) -> Eigen::VectorXd {
    return remesh ? radius_ratio(m) : shear_distortion(plan.templ.V, m.V, m.F);
  };
  const Eigen::VectorXd before = measure(plan.mesh), after = measure(output);
  const std::vector<FrameSummary> none;
  SequencePageInput in;
  in.kind = "mesh";
  in.title = "seqmassage " + job_name(c.job) + ": " + plan.mesh_name;
  in.summary_csv = measures_csv;
  in.frames = &none;
  in.warnings = result.warnings;
  in.config = report.value("config", nlohmann::json::object());
  in.versions = report.value("versions", nlohmann::json::object());
  in.colour = remesh ? "radius ratio" : "shear";
  in.colour_scale = remesh ? 1.0 : summarize_distortion(before).p95;
  in.checker_cells = CheckerOutputOptions{}.cells;
  in.load_template = [&] {
    const CornerUv uv = template_uv(plan.mesh, plan.obj ? &*plan.obj : nullptr, {});
    PlayerTemplate t;
    t.vertices = int(plan.mesh.num_vertices());
    t.F = plan.mesh.F;
    t.uv_source = uv.source;
    for (Eigen::Index i = 0; i < uv.faces.rows(); ++i)
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 2; ++j) t.corner_uv.push_back(float(uv.uv(uv.faces(i, k), j)));
    return t;
  };
  in.data_frames = {0};
  const std::string frame = encode_player_frame(plan.mesh.V, result.V, before, after);
  in.load = [&](size_t) { return decode_player_frame(frame, int(plan.mesh.num_vertices()),
                                                     int(plan.mesh.num_triangles()), "mesh"); };
  if (!html_player_available()) in.data_frames.clear();
  in.budget_bytes = size_t(c.output.html_max_mb * 1024 * 1024);
  return make_sequence_page(in).html;
}

}  // namespace sm
