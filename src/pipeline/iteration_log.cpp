#include "pipeline/iteration_log.hpp"

#include <cstring>

namespace sm {
namespace {

bool same(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Whether two runs agree at an iteration: every figure that depends on the positions.
bool same_iteration(const IterationStats& a, const IterationStats& b) {
  return a.iteration == b.iteration && same(a.mu, b.mu) && same(a.energy, b.energy) &&
         same(a.max_dist_m_to_n, b.max_dist_m_to_n) && same(a.rms_dist_m_to_n, b.rms_dist_m_to_n) &&
         same(a.max_dist_n_to_m, b.max_dist_n_to_m) && same(a.rms_dist_n_to_m, b.rms_dist_n_to_m) &&
         same(a.max_move, b.max_move);
}

}  // namespace

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

std::vector<std::optional<DistortionSummary>> shear_per_iteration(
    const TriMesh& templ, const MassageOptions& options, const Positions& start,
    const Reference& reference, const MassageResult& full, std::string& warning) {
  const int k = static_cast<int>(full.iterations.size());
  std::vector<std::optional<DistortionSummary>> out(size_t(std::max(0, k - 1)));
  std::vector<int> differ, failed;
  for (int j = 1; j < k; ++j) {
    MassageOptions limited = options;
    limited.iterations = j;
    const Massager massager(templ, limited, "template");
    const MassageResult run = massager.run(start, reference);
    if (!run.ok) {
      failed.push_back(j);
      continue;
    }
    if (run.iterations.empty() || !same_iteration(run.iterations.back(), full.iterations[j - 1])) {
      differ.push_back(j);
      continue;
    }
    out[size_t(j - 1)] = summarize_distortion(shear_distortion(templ.V, run.V, templ.F));
  }
  const auto list = [](const std::vector<int>& its) {
    std::string text;
    for (int j : its) text += (text.empty() ? "" : ", ") + std::to_string(j);
    return text;
  };
  warning.clear();
  if (!differ.empty())
    warning = "shear per iteration: the re-run limited to iterations " + list(differ) +
              " differs from the full run there (the optimizer's first iterations depend on the "
              "iteration count); their shear is left empty";
  if (!failed.empty())
    warning += std::string(warning.empty() ? "" : "; ") +
               "shear per iteration: the re-run limited to iterations " + list(failed) +
               " failed; their shear is left empty";
  return out;
}

}  // namespace sm
