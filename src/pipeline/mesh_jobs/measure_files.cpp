#include "pipeline/mesh_jobs/measure_files.hpp"

#include <tbb/task_arena.h>

#include <optional>

#include "io/atomic_file.hpp"
#include "io/mesh_file.hpp"
#include "core/errors.hpp"
#include "pipeline/mesh_jobs/mesh_report.hpp"

namespace sm {
namespace fs = std::filesystem;

namespace {

bool same_connectivity(const TriMesh& a, const TriMesh& b) {
  return a.num_vertices() == b.num_vertices() && a.num_triangles() == b.num_triangles() &&
         a.F == b.F;
}

std::string counts(const TriMesh& m) {
  return std::to_string(m.num_vertices()) + " vertices, " + std::to_string(m.num_triangles()) +
         " triangles";
}

}  // namespace

MeasureFilesResult measure_files(const MeasureFilesRequest& r) {
  std::error_code ec;
  for (const auto& [out, option] : {std::pair{&r.csv, "--csv"}, std::pair{&r.json, "--json"}})
    for (const fs::path* in : {&r.mesh, &r.reference, &r.templ})
      if (!out->empty() && !in->empty() && fs::exists(*in, ec) && fs::equivalent(*out, *in, ec))
        throw ConfigError(std::string(option) + ": " + out->string() + " is an input file");

  const TriMesh mesh = read_mesh(r.mesh);
  validate_mesh(mesh, r.mesh.string().c_str());
  const TriMesh reference = read_mesh(r.reference);
  std::optional<TriMesh> templ;
  std::string template_note;
  if (!r.templ.empty()) {
    templ = read_mesh(r.templ);
    if (!same_connectivity(*templ, mesh))
      throw InputError(r.templ.string() + ": --template needs the connectivity of " +
                       r.mesh.string() + " (" + counts(mesh) + " in the same order); it has " +
                       counts(*templ));
    template_note = r.templ.string();
  } else if (same_connectivity(reference, mesh)) {
    templ = reference;
    template_note = "N (it has M's connectivity)";
  }

  MeasureFilesResult result;
  tbb::task_arena arena(r.threads > 0 ? r.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    const MeasureReference ref(reference, r.options, r.reference.string().c_str());
    result.reference_quality = ref.radius_ratio();
    result.measures = with_option_path(
        "measures", [&] { return measure_mesh(mesh, ref, templ ? &templ->V : nullptr); });
  });

  const std::string shown_reference = r.reference.string() + " (" + counts(reference) + ")";
  result.table =
      format_measures_table({{"measure", r.mesh.string(), shown_reference, &result.measures}},
                            &result.reference_quality, template_note);
  result.csv = format_measures_csv(
      {{"measure", r.mesh.string(), r.reference.string(), &result.measures}}, r.options);
  result.json = {
      {"mesh", r.mesh.string()},
      {"reference", r.reference.string()},
      {"template", templ ? nlohmann::json(r.templ.empty() ? r.reference.string() : r.templ.string())
                         : nlohmann::json(nullptr)},
      {"reference_radius_ratio",
       {{"min", result.reference_quality.min}, {"mean", result.reference_quality.mean}}},
      {"measures", measures_json(result.measures)}};
  if (!r.csv.empty()) write_file_atomic(r.csv, result.csv);
  if (!r.json.empty()) write_file_atomic(r.json, result.json.dump(2) + "\n");
  return result;
}

}  // namespace sm
