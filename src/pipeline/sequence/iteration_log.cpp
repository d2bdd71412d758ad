#include "pipeline/sequence/iteration_log.hpp"

namespace sm {

std::vector<std::string> iteration_columns() {
  return {"frame",
          "file",
          "iteration",
          "mu",
          "energy",
          "max_dist_m_to_n",
          "rms_dist_m_to_n",
          "max_dist_n_to_m",
          "rms_dist_n_to_m",
          "max_move",
          "solver_iterations",
          "solver_residual",
          "shear_max",
          "shear_mean",
          "shear_p95"};
}

std::vector<IterationRow> iteration_rows(
    const MassageResult& result, const DistortionSummary& before, const DistortionSummary& after,
    const std::vector<std::optional<DistortionSummary>>& shear_per_iteration) {
  std::vector<IterationRow> rows;
  rows.push_back({0, std::nullopt, before});
  const size_t k = result.iterations.size();
  for (size_t i = 0; i < k; ++i) {
    IterationRow row{result.iterations[i].iteration, result.iterations[i], std::nullopt};
    if (i < shear_per_iteration.size()) row.shear = shear_per_iteration[i];
    if (i + 1 == k && result.ok) row.shear = after;
    rows.push_back(row);
  }
  return rows;
}

void append_iteration_rows(CsvWriter& csv, int frame, const std::string& file,
                           const std::vector<IterationRow>& rows) {
  for (const IterationRow& row : rows) {
    csv.cell(frame).cell(file).cell(row.iteration);
    if (row.stats) {
      const IterationStats& s = *row.stats;
      csv.cell(s.mu).cell(s.energy);
      csv.cell(s.max_dist_m_to_n).cell(s.rms_dist_m_to_n);
      csv.cell(s.max_dist_n_to_m).cell(s.rms_dist_n_to_m);
      csv.cell(s.max_move).cell(s.solver_iterations).cell(s.solver_residual);
    } else {
      csv.cell("").cell("");
      csv.cell(0.0).cell(0.0).cell(0.0).cell(0.0);
      csv.cell("").cell("").cell("");
    }
    if (row.shear)
      csv.cell(row.shear->max).cell(row.shear->mean).cell(row.shear->p95);
    else
      csv.cell("").cell("").cell("");
    csv.end_row();
  }
}

IterationObserver shear_observer(const TriMesh& templ,
                                 std::vector<std::optional<DistortionSummary>>& out) {
  return [&templ, &out](const IterationStats&, const Positions& V) {
    out.emplace_back(summarize_distortion(shear_distortion(templ.V, V, templ.F)));
  };
}

}  // namespace sm
