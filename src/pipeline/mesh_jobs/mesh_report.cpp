#include "pipeline/mesh_jobs/mesh_report.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <type_traits>
#include <variant>

#include "io/csv.hpp"
#include "massage/iteration_fields.hpp"
#include "pipeline/report/report.hpp"
#include "pipeline/report/report_json.hpp"

namespace sm {
using json = nlohmann::json;

namespace {

std::string bin_name(double edge) {
  return "shear_hist_" + format_number(edge);
}

std::string sci(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4e", x);
  return b;
}

std::string fix(double x, int digits = 4) {
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", digits, x);
  return b;
}

std::string pad(const std::string& s, size_t width) {
  return s.size() >= width ? s + " " : s + std::string(width - s.size(), ' ');
}

constexpr size_t kLabel = 28;
constexpr size_t kCell = 13;

std::string trimmed(std::string text) {
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

// Sections of a heading with column titles, then one line per row (or the heading and the values
// on one line when there is a single row).
class Table {
 public:
  Table(std::ostringstream& out, const std::vector<MeasureRow>& rows) : out_(out), rows_(rows) {}

  template <class CellsOf>
  void section(const std::string& heading, const std::vector<std::string>& titles,
               CellsOf cells_of) {
    if (!titles.empty()) {
      std::string text = pad("", kLabel);
      for (const std::string& t : titles) text += pad(t, kCell);
      out_ << trimmed(text) << "\n";
    }
    if (rows_.size() == 1) {
      line(heading, cells_of(rows_[0]));
      return;
    }
    out_ << heading << "\n";
    for (const MeasureRow& r : rows_) line("  " + r.stage, cells_of(r));
  }

  void line(const std::string& label, const std::vector<std::string>& cells) {
    std::string text = pad(label, kLabel);
    for (const std::string& c : cells) text += pad(c, kCell);
    out_ << trimmed(text) << "\n";
  }

 private:
  std::ostringstream& out_;
  const std::vector<MeasureRow>& rows_;
};

std::vector<std::string> distance_cells(const DistanceStats& d) {
  return {sci(d.max), sci(d.mean), sci(d.rms), sci(d.max_rel), sci(d.mean_rel), sci(d.rms_rel)};
}

}  // namespace

std::vector<std::string> measure_columns(const MeasureOptions& options) {
  std::vector<std::string> c = {"stage", "mesh", "reference", "vertices", "triangles"};
  for (const char* d : {"mesh_to_ref", "ref_to_mesh"})
    for (const char* s : {"max", "mean", "rms", "max_rel", "mean_rel", "rms_rel", "samples"})
      c.push_back(std::string("dist_") + d + "_" + s);
  for (const char* s :
       {"hausdorff", "hausdorff_rel", "diagonal", "radius_ratio_min", "radius_ratio_mean",
        "shear_max", "shear_mean", "shear_p95", "shear_degenerate"})
    c.push_back(s);
  for (size_t i = 0; i + 1 < options.shear_bins.size(); ++i)
    c.push_back(bin_name(options.shear_bins[i]));
  for (const char* s : {"feature_edges", "feature_dist_max", "feature_dist_mean",
                        "feature_dist_max_rel", "feature_dist_mean_rel", "dihedral_change_max",
                        "dihedral_change_mean", "features_flattened"})
    c.push_back(s);
  return c;
}

std::string format_measures_csv(const std::vector<MeasureRow>& rows,
                                const MeasureOptions& options) {
  CsvWriter csv(measure_columns(options));
  const size_t bins = options.shear_bins.size() - 1;
  for (const MeasureRow& row : rows) {
    const MeshMeasures& m = *row.measures;
    csv.cell(row.stage).cell(row.mesh).cell(row.reference).cell(m.vertices).cell(m.triangles);
    for (const DistanceStats* d : {&m.to_reference, &m.from_reference})
      csv.cell(d->max)
          .cell(d->mean)
          .cell(d->rms)
          .cell(d->max_rel)
          .cell(d->mean_rel)
          .cell(d->rms_rel)
          .cell(static_cast<int64_t>(d->samples));
    csv.cell(m.hausdorff).cell(m.hausdorff_rel).cell(m.diagonal);
    csv.cell(m.radius_ratio.min).cell(m.radius_ratio.mean);
    if (m.shear) {
      const ShearMeasures& s = *m.shear;
      csv.cell(s.summary.max).cell(s.summary.mean).cell(s.summary.p95).cell(s.summary.infinite);
      for (size_t i = 0; i < bins; ++i) csv.cell(i < s.counts.size() ? s.counts[i] : 0);
    } else {
      for (size_t i = 0; i < 4 + bins; ++i) csv.cell("");
    }
    const FeatureMeasures& f = m.features;
    csv.cell(f.edges)
        .cell(f.distance.max)
        .cell(f.distance.mean)
        .cell(f.distance.max_rel)
        .cell(f.distance.mean_rel);
    if (f.dihedral_change_max)
      csv.cell(*f.dihedral_change_max).cell(*f.dihedral_change_mean).cell(*f.flattened);
    else
      csv.cell("").cell("").cell("");
    csv.end_row();
  }
  return csv.str();
}

std::string format_measures_table(const std::vector<MeasureRow>& rows,
                                  const QualitySummary* reference_quality,
                                  const std::string& template_name) {
  std::ostringstream out;
  if (rows.empty()) return "";
  Table table(out, rows);
  const MeasureRow& first = rows.front();
  out << "M = " << first.mesh << " (" << first.measures->vertices << " vertices, "
      << first.measures->triangles << " triangles)\n";
  out << "N = " << first.reference << "\n";
  if (!template_name.empty()) out << "T = " << template_name << "\n";
  out << "distances are sampled Metro-style on vertices, edges and inside triangles; diag = "
         "diagonal of the bounding box of M and N, "
      << sci(first.measures->diagonal) << "\n";
  const std::vector<std::string> dist_titles = {"max",      "mean",      "RMS",
                                                "max/diag", "mean/diag", "RMS/diag"};
  table.section("M -> N", dist_titles,
                [](const MeasureRow& r) { return distance_cells(r.measures->to_reference); });
  table.section("N -> M", {},
                [](const MeasureRow& r) { return distance_cells(r.measures->from_reference); });
  const double h0 = first.measures->hausdorff;
  table.section("Hausdorff distance", {}, [&](const MeasureRow& r) {
    std::vector<std::string> cells = {sci(r.measures->hausdorff), "", "",
                                      sci(r.measures->hausdorff_rel)};
    if (&r != &first && h0 > 0.0)
      cells.push_back("(" + fix(100.0 * (r.measures->hausdorff / h0 - 1.0), 1) + "% vs " +
                      first.stage + ")");
    return cells;
  });

  table.section("radius ratio 2r/R of M", {"min", "mean"}, [](const MeasureRow& r) {
    return std::vector<std::string>{fix(r.measures->radius_ratio.min),
                                    fix(r.measures->radius_ratio.mean)};
  });
  if (reference_quality)
    table.line("radius ratio 2r/R of N",
               {fix(reference_quality->min), fix(reference_quality->mean)});

  if (first.measures->shear) {
    table.section("shear against T (eq. 8)", {"max", "mean", "p95", "degenerate"},
                  [](const MeasureRow& r) {
                    if (!r.measures->shear) return std::vector<std::string>{};
                    const DistortionSummary& s = r.measures->shear->summary;
                    return std::vector<std::string>{sci(s.max), sci(s.mean), sci(s.p95),
                                                    std::to_string(s.infinite)};
                  });
    const std::vector<double>& bins = first.measures->shear->bins;
    std::vector<std::string> titles;
    for (size_t i = 0; i + 1 < bins.size(); ++i)
      titles.push_back("<" + (std::isfinite(bins[i + 1]) ? format_number(bins[i + 1]) : "inf"));
    table.section("shear histogram (triangles)", titles, [](const MeasureRow& r) {
      std::vector<std::string> cells;
      if (r.measures->shear)
        for (int c : r.measures->shear->counts) cells.push_back(std::to_string(c));
      return cells;
    });
  }

  const FeatureMeasures& f0 = first.measures->features;
  out << "feature edges of N (dihedral angle above " << format_number(f0.threshold_degrees)
      << " degrees): " << f0.edges << "\n";
  if (f0.edges > 0) {
    table.section(
        "  their distance to M", {"max", "mean", "max/diag", "mean/diag"}, [](const MeasureRow& r) {
          const DistanceStats& d = r.measures->features.distance;
          return std::vector<std::string>{sci(d.max), sci(d.mean), sci(d.max_rel), sci(d.mean_rel)};
        });
    if (f0.dihedral_change_max)
      table.section("  dihedral change (degrees)", {"max", "mean", "flattened"},
                    [](const MeasureRow& r) {
                      const FeatureMeasures& f = r.measures->features;
                      if (!f.dihedral_change_max) return std::vector<std::string>{};
                      return std::vector<std::string>{fix(*f.dihedral_change_max, 2),
                                                      fix(*f.dihedral_change_mean, 2),
                                                      std::to_string(*f.flattened)};
                    });
  }
  return out.str();
}

std::string format_mesh_job_table(const MeshJobPlan& plan, const MeshJobResult& result) {
  std::vector<MeasureRow> rows = {{"before", plan.mesh_name, plan.reference_name, &result.before}};
  if (result.after) rows.push_back({"after", plan.mesh_name, plan.reference_name, &*result.after});
  if (plan.config.job != JobKind::Remesh)
    return format_measures_table(rows, nullptr, plan.template_name);
  const QualitySummary reference_quality = summarize_quality(radius_ratio(plan.reference));
  return format_measures_table(rows, &reference_quality, plan.template_name);
}

std::vector<std::string> mesh_job_output_names(const MeshJobPlan& plan,
                                               const MeshJobResult& result) {
  std::vector<std::string> names;
  if (result.ok()) names.push_back(plan.output_mesh.filename().string());
  names.push_back("measures.csv");
  names.push_back("report.json");
  if (plan.config.output.per_triangle_csv) names.push_back("triangles.csv");
  if (plan.config.output.html) names.push_back("report.html");
  return names;
}

json measures_json(const MeshMeasures& m) {
  json j = {
      {"vertices", m.vertices},
      {"triangles", m.triangles},
      {"dist_mesh_to_ref", distance_json(m.to_reference)},
      {"dist_ref_to_mesh", distance_json(m.from_reference)},
      {"hausdorff", json_number(m.hausdorff)},
      {"hausdorff_rel", json_number(m.hausdorff_rel)},
      {"diagonal", json_number(m.diagonal)},
      {"radius_ratio",
       {{"min", json_number(m.radius_ratio.min)}, {"mean", json_number(m.radius_ratio.mean)}}}};
  if (m.shear) {
    json bins = json::array();
    for (double e : m.shear->bins) bins.push_back(json_number(e));
    j["shear"] = {{"max", json_number(m.shear->summary.max)},
                  {"mean", json_number(m.shear->summary.mean)},
                  {"p95", json_number(m.shear->summary.p95)},
                  {"degenerate", m.shear->summary.infinite},
                  {"histogram", {{"bins", bins}, {"counts", m.shear->counts}}}};
  } else {
    j["shear"] = nullptr;
  }
  const FeatureMeasures& f = m.features;
  j["features"] = {{"edges", f.edges},
                   {"threshold_degrees", json_number(f.threshold_degrees)},
                   {"distance", distance_json(f.distance)}};
  if (f.dihedral_change_max) {
    j["features"]["dihedral_change_max"] = json_number(*f.dihedral_change_max);
    j["features"]["dihedral_change_mean"] = json_number(*f.dihedral_change_mean);
    j["features"]["flattened"] = *f.flattened;
  }
  return j;
}

std::string format_triangles_csv(const TriangleMeasures& before, const TriangleMeasures* after) {
  CsvWriter csv(
      {"triangle", "radius_ratio_before", "radius_ratio_after", "shear_before", "shear_after"});
  const bool shear = before.shear.size() > 0;
  for (Eigen::Index t = 0; t < before.radius_ratio.size(); ++t) {
    csv.cell(static_cast<int64_t>(t)).cell(before.radius_ratio[t]);
    if (after)
      csv.cell(after->radius_ratio[t]);
    else
      csv.cell("");
    if (shear)
      csv.cell(before.shear[t]);
    else
      csv.cell("");
    if (shear && after)
      csv.cell(after->shear[t]);
    else
      csv.cell("");
    csv.end_row();
  }
  return csv.str();
}

json make_mesh_report(const MeshJobPlan& plan, const MeshJobResult& result) {
  const MeshJobOptions& c = plan.config;
  json r;
  r["versions"] = version_info();
  r["config"] = to_json(c);
  auto counts = [](const TriMesh& m) {
    return json{{"vertices", m.num_vertices()}, {"triangles", m.num_triangles()}};
  };
  json inputs;
  inputs["mesh"] = counts(plan.mesh);
  inputs["mesh"]["file"] = c.input.mesh.string();
  inputs["reference"] = counts(plan.reference);
  inputs["reference"]["file"] =
      c.job == JobKind::Remesh ? json(c.input.reference.string()) : json("the mesh as loaded");
  const QualitySummary reference_quality = summarize_quality(radius_ratio(plan.reference));
  inputs["reference"]["radius_ratio"] = {{"min", json_number(reference_quality.min)},
                                         {"mean", json_number(reference_quality.mean)}};
  inputs["template"] = counts(plan.templ);
  inputs["template"]["file"] =
      c.job == JobKind::Crossparam ? json(c.templ.mesh.string()) : json("the mesh itself");
  inputs["template"]["weight_fallback_vertices"] = plan.massager->weights().fallback_vertices;
  inputs["pinned_vertices"] = plan.pinned_vertices;
  r["inputs"] = inputs;

  const MassageResult& m = result.massage;
  json iterations = json::array();
  for (const IterationStats& it : m.iterations) {
    json row = json::object();
    for (const IterationField& field : iteration_fields())
      if (field.writers & kReportJson)
        std::visit(
            [&](auto member) {
              if constexpr (std::is_same_v<decltype(member), int IterationStats::*>)
                row[field.name] = it.*member;
              else
                row[field.name] = json_number(it.*member);
            },
            field.member);
    if (c.output.timings)
      row["seconds"] = json_number(it.seconds_closest + it.seconds_assemble + it.seconds_solve);
    iterations.push_back(row);
  }
  r["massage"] = {{"ok", m.ok},
                  {"failure", m.ok ? json(nullptr) : json(m.failure)},
                  {"iterations_run", m.iterations.size()},
                  {"stopped_early", m.stopped_early},
                  {"folded_triangles", m.folded_triangles},
                  {"iterations", iterations}};

  r["measures"] = {{"before", measures_json(result.before)},
                   {"after", result.after ? measures_json(*result.after) : json(nullptr)}};
  if (result.after && result.before.hausdorff > 0.0)
    r["measures"]["hausdorff_change"] =
        json_number(result.after->hausdorff / result.before.hausdorff - 1.0);
  r["warnings"] = result.warnings;
  r["outputs"] = {
      {"dir", c.output.dir.string()},
      {"mesh", result.massage.ok ? json(plan.output_mesh.filename().string()) : json(nullptr)},
      {"measures", "measures.csv"},
      {"triangles", c.output.per_triangle_csv ? json("triangles.csv") : json(nullptr)},
      {"html", c.output.html ? json("report.html") : json(nullptr)}};
  if (c.output.timings)
    r["run"] = {{"threads", plan.threads},
                {"seconds", result.seconds},
                {"seconds_massage", result.seconds_massage}};
  return r;
}

}  // namespace sm
