#include "pipeline/mesh_jobs/mesh_job.hpp"

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <set>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/mesh_file.hpp"
#include "io/off.hpp"
#include "io/vertex_weights.hpp"
#include "massage/reference.hpp"
#include "core/errors.hpp"
#include "mesh/mesh_check.hpp"
#include "core/timing.hpp"
#include "pipeline/sequence/input_clash.hpp"
#include "pipeline/mesh_jobs/mesh_html.hpp"
#include "pipeline/mesh_jobs/mesh_report.hpp"
#include "pipeline/cluster/output_lock.hpp"
#include "pipeline/report/run_text.hpp"

namespace sm {
namespace fs = std::filesystem;

namespace {

std::string lower_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  for (char& c : ext)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return ext;
}

// Why `templ` cannot serve as the template of `mesh`, or "" if it can.
std::string connectivity_mismatch(const MeshJobPlan& plan) {
  const TriMesh &t = plan.templ, &m = plan.mesh;
  const std::string who = "template (" + plan.template_name + "): ";
  const std::string but = ", but the mesh (" + plan.mesh_name + ") has ";
  if (t.num_vertices() != m.num_vertices())
    return who + std::to_string(t.num_vertices()) + " vertices" + but +
           std::to_string(m.num_vertices()) + " (crossparam needs the same connectivity)";
  if (t.num_triangles() != m.num_triangles())
    return who + std::to_string(t.num_triangles()) + " triangles" + but +
           std::to_string(m.num_triangles()) + " (crossparam needs the same connectivity)";
  for (int k = 0; k < t.num_triangles(); ++k)
    if (t.F.row(k) != m.F.row(k))
      return who + "triangle " + std::to_string(k + 1) + " has vertices " +
             std::to_string(t.F(k, 0) + 1) + " " + std::to_string(t.F(k, 1) + 1) + " " +
             std::to_string(t.F(k, 2) + 1) + but + std::to_string(m.F(k, 0) + 1) + " " +
             std::to_string(m.F(k, 1) + 1) + " " + std::to_string(m.F(k, 2) + 1) +
             " there (1-based; crossparam needs the same connectivity)";
  return "";
}

// A warning when M and N are not roughly aligned: the closest-point correspondences of §2.2.1
// assume that the two surfaces are similar in shape and position.
std::string alignment_warning(const MeshJobPlan& plan) {
  const Positions &a = plan.mesh.V, &b = plan.reference.V;
  const double diagonal = bounding_box_diagonal(b);
  const double gap = std::max((a.colwise().minCoeff() - b.colwise().minCoeff()).norm(),
                              (a.colwise().maxCoeff() - b.colwise().maxCoeff()).norm());
  if (!(gap > 0.05 * diagonal)) return "";
  std::ostringstream s;
  s << "the bounding boxes of " << plan.mesh_name << " and " << plan.reference_name << " differ by "
    << gap / diagonal
    << " of the reference's diagonal; the closest-point correspondences assume that the "
       "meshes are aligned";
  return s.str();
}

void check_outputs(const MeshJobPlan& plan) {
  const MeshJobOptions& c = plan.config;
  std::vector<ReadFile> inputs = {{"the config", c.config_file},
                                  {"input.mesh", c.input.mesh},
                                  {"input.reference", c.input.reference},
                                  {"template.mesh", c.templ.mesh}};
  if (!c.massage.vertex_weights_file.empty())
    inputs.push_back({"massage.vertex_weights", weights_file_read(c.massage.vertex_weights_file)});
  std::vector<fs::path> outputs = {plan.output_mesh, c.output.dir / "measures.csv",
                                   c.output.dir / "report.json"};
  if (c.output.per_triangle_csv) outputs.push_back(c.output.dir / "triangles.csv");
  if (c.output.html) outputs.push_back(c.output.dir / "report.html");
  refuse_overwriting_inputs(inputs, outputs);
}

std::string output_text(const MeshJobPlan& plan, const Positions& V) {
  const std::string ext = lower_extension(plan.output_mesh);
  const TriMesh mesh{V, plan.mesh.F};
  if (ext == ".obj") return plan.obj ? format_obj(*plan.obj, V) : format_obj(mesh);
  if (ext == ".off") return format_off(mesh);
  const bool colours = plan.colors.vertex.size() == static_cast<size_t>(mesh.num_vertices()) ||
                       plan.colors.face.size() == static_cast<size_t>(mesh.num_triangles());
  return format_ply(mesh, colours ? &plan.colors : nullptr, /*binary=*/true);
}

}  // namespace

fs::path mesh_output_path(const MeshJobOptions& config) {
  fs::path name = config.input.mesh.filename();
  switch (config.output.format) {
    case MeshOutputFormat::Same:
      break;
    case MeshOutputFormat::Obj:
      if (lower_extension(name) != ".obj") name.replace_extension(".obj");
      break;
    case MeshOutputFormat::Off:
      if (lower_extension(name) != ".off") name.replace_extension(".off");
      break;
    case MeshOutputFormat::Ply:
      if (lower_extension(name) != ".ply") name.replace_extension(".ply");
      break;
  }
  return config.output.dir / name;
}

MeshJobPlan plan_mesh_job(const MeshJobOptions& config) {
  MeshJobPlan plan;
  plan.config = config;
  const MeshJobOptions& c = plan.config;
  plan.threads = c.threads > 0 ? c.threads : std::max(1, tbb::info::default_concurrency());

  plan.mesh_name = c.input.mesh.filename().string();
  const std::string ext = lower_extension(c.input.mesh);
  if (ext == ".obj") {
    plan.obj = read_obj(c.input.mesh);
    plan.mesh = plan.obj->mesh;
  } else if (ext == ".ply") {
    plan.mesh = read_ply(c.input.mesh, &plan.colors);
  } else {
    plan.mesh = read_mesh(c.input.mesh);  // .off, or InputError naming the extension
  }
  validate_mesh(plan.mesh, c.input.mesh.string().c_str());

  if (c.job == JobKind::Remesh) {
    plan.reference_name = c.input.reference.filename().string();
    if (plan.reference_name == plan.mesh_name) plan.reference_name = c.input.reference.string();
    plan.reference = read_mesh(c.input.reference);
    validate_mesh(plan.reference, c.input.reference.string().c_str());
    if (plan.reference.num_triangles() == 0)
      throw InputError(c.input.reference.string() + ": the reference mesh has no triangles");
  } else {
    plan.reference_name = plan.mesh_name + " as loaded";
    plan.reference = plan.mesh;
  }

  if (c.job == JobKind::Crossparam) {
    plan.template_name = c.templ.mesh.filename().string();
    if (plan.template_name == plan.mesh_name) plan.template_name = c.templ.mesh.string();
    plan.templ = read_mesh(c.templ.mesh);
    validate_mesh(plan.templ, c.templ.mesh.string().c_str());
    if (std::string problem = connectivity_mismatch(plan); !problem.empty())
      throw InputError(problem);
  } else {
    plan.template_name = plan.mesh_name;
    plan.templ = plan.mesh;
  }

  if (!c.massage.vertex_weights_file.empty())
    plan.config.massage.vertex_weights = read_vertex_weights(
        c.massage.vertex_weights_file, plan.templ.num_vertices(), plan.template_name);
  plan.massager = with_option_path("massage", [&] {
    return std::make_shared<const Massager>(plan.templ, c.massage, plan.template_name.c_str());
  });
  std::vector<unsigned char> pinned(plan.mesh.num_vertices(), 0);
  for (int v : c.massage.pinned) pinned[v] = 1;
  if (c.massage.pin_boundary)
    for (int v = 0; v < plan.mesh.num_vertices(); ++v)
      if (plan.massager->topology().is_boundary_vertex[v]) pinned[v] = 1;
  plan.pinned_vertices = static_cast<int>(std::count(pinned.begin(), pinned.end(), 1));

  const MeshReport report = check_mesh(plan.mesh, plan.massager->topology());
  if (!report.ok_for_optimization())
    plan.warnings.push_back(plan.mesh_name + ": " + report.describe());
  if (c.job == JobKind::Crossparam) {
    const MeshReport t = check_mesh(plan.templ, plan.massager->topology());
    if (t.degenerate_triangles > 0)
      plan.warnings.push_back("template (" + plan.template_name + "): " + t.describe());
  }
  if (const int fallback = plan.massager->weights().fallback_vertices; fallback > 0)
    plan.warnings.push_back(plan.template_name + ": " + std::to_string(fallback) +
                            " vertices with degenerate corners use uniform weights");
  if (c.massage.pin_boundary && plan.massager->topology().boundary_loops.empty())
    plan.warnings.push_back("massage.pin_boundary: " + plan.mesh_name +
                            " has no boundary, no vertex is pinned by it");
  if (c.job == JobKind::Remesh)
    if (std::string w = alignment_warning(plan); !w.empty()) plan.warnings.push_back(w);

  plan.output_mesh = mesh_output_path(c);
  check_outputs(plan);
  return plan;
}

std::string describe_mesh_plan(const MeshJobPlan& plan) {
  const MeshJobOptions& c = plan.config;
  std::ostringstream s;
  auto counts = [](const TriMesh& m) {
    return std::to_string(m.num_vertices()) + " vertices, " + std::to_string(m.num_triangles()) +
           " triangles";
  };
  s << "job: " << job_name(c.job) << "\n";
  s << "mesh (M): " << c.input.mesh.string() << ", " << counts(plan.mesh) << "\n";
  if (c.job == JobKind::Remesh)
    s << "reference (N): " << c.input.reference.string() << ", " << counts(plan.reference) << "\n";
  else
    s << "reference (N): the mesh as loaded\n";
  if (c.job == JobKind::Crossparam)
    s << "template (T): " << c.templ.mesh.string() << ", " << counts(plan.templ) << "\n";
  else
    s << "template (T): the mesh itself\n";
  s << "massage: " << massage_text(c.massage) << ", " << plan.pinned_vertices
    << " pinned vertices\n";
  s << "threads: " << plan.threads << "\n";
  s << "output: " << c.output.dir.string() << "\n";
  s << "  " << plan.output_mesh.filename().string() << ", measures.csv, report.json"
    << (c.output.per_triangle_csv ? ", triangles.csv" : "")
    << (c.output.html ? ", report.html" : "") << "\n";
  for (const std::string& w : plan.warnings) s << "warning: " << w << "\n";
  return s.str();
}

MeshJobResult run_mesh_job(const MeshJobPlan& plan) {
  const auto t0 = Clock::now();
  const MeshJobOptions& c = plan.config;
  const fs::path& out = c.output.dir;
  MeshJobResult result;
  result.warnings = plan.warnings;
  const OutputLock lock = lock_output_folder(out);  // one writer per output folder
  for (const std::string& w : lock.warnings()) result.warnings.push_back(w);
  remove_stale_temporaries(out);

  TriangleMeasures triangles_before, triangles_after;
  tbb::task_arena arena(plan.threads);
  arena.execute([&] {
    const MeasureReference measure_ref(plan.reference, c.measures, plan.reference_name.c_str());
    const Positions* shear_template = &plan.templ.V;
    const auto measure = [&](const TriMesh& mesh) {
      return with_option_path("measures",
                              [&] { return measure_mesh(mesh, measure_ref, shear_template); });
    };
    result.before = measure(plan.mesh);
    if (c.output.per_triangle_csv) triangles_before = measure_triangles(plan.mesh, shear_template);

    // N shares M's topology when it is M as loaded.
    const Reference reference(
        plan.reference, c.massage.samples, plan.reference_name.c_str(),
        c.job == JobKind::Remesh ? nullptr : plan.massager->shared_topology());
    const auto t_massage = Clock::now();
    result.massage = plan.massager->run(plan.mesh.V, reference);
    result.seconds_massage = seconds_since(t_massage);
    result.V = result.massage.V;
    if (!result.massage.ok) return;
    const TriMesh output{result.V, plan.mesh.F};
    result.after = measure(output);
    if (c.output.per_triangle_csv) triangles_after = measure_triangles(output, shear_template);
  });

  if (result.massage.ok) {
    if (result.massage.folded_triangles > 0)
      result.warnings.push_back(std::to_string(result.massage.folded_triangles) +
                                " triangles of the output are folded over the reference surface");
    write_file_atomic(plan.output_mesh, output_text(plan, result.V));
  } else {
    result.warnings.push_back("the optimizer failed, no mesh written: " + result.massage.failure);
  }
  if (c.output.per_triangle_csv)
    write_file_atomic(
        out / "triangles.csv",
        format_triangles_csv(triangles_before, result.massage.ok ? &triangles_after : nullptr));
  std::vector<MeasureRow> rows = {{"before", plan.mesh_name, plan.reference_name, &result.before}};
  if (result.after) rows.push_back({"after", plan.mesh_name, plan.reference_name, &*result.after});
  const std::string measures_csv = format_measures_csv(rows, c.measures);
  write_file_atomic(out / "measures.csv", measures_csv);
  result.seconds = seconds_since(t0);
  const nlohmann::json report = make_mesh_report(plan, result);
  write_file_atomic(out / "report.json", report.dump(2) + "\n");
  if (c.output.html)
    write_file_atomic(out / "report.html", mesh_html_page(plan, result, measures_csv, report));
  return result;
}

}  // namespace sm
