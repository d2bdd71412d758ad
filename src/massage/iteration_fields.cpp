#include "massage/iteration_fields.hpp"

namespace sm {

const std::vector<IterationField>& iteration_fields() {
  using S = IterationStats;
  constexpr unsigned all = kIterationsCsv | kReportJson | kPythonDict;
  constexpr unsigned csv_python = kIterationsCsv | kPythonDict;
  constexpr unsigned report_python = kReportJson | kPythonDict;
  // iteration is iterations.csv's row key, which it writes itself (row 0 has no IterationStats).
  static const std::vector<IterationField> fields = {
      {"iteration", &S::iteration, report_python},
      {"mu", &S::mu, all},
      {"energy", &S::energy, all},
      {"max_dist_m_to_n", &S::max_dist_m_to_n, all, true},
      {"rms_dist_m_to_n", &S::rms_dist_m_to_n, all, true},
      {"max_dist_n_to_m", &S::max_dist_n_to_m, all, true},
      {"rms_dist_n_to_m", &S::rms_dist_n_to_m, all, true},
      {"max_move", &S::max_move, all},
      {"solver_iterations", &S::solver_iterations, all},
      {"solver_residual", &S::solver_residual, csv_python},
      {"exact_queries", &S::exact_queries, report_python},
      // Timings: report.json sums them as "seconds" (with output.timings).
      {"seconds_closest", &S::seconds_closest, kPythonDict},
      {"seconds_assemble", &S::seconds_assemble, kPythonDict},
      {"seconds_solve", &S::seconds_solve, kPythonDict},
  };
  return fields;
}

std::vector<const char*> iteration_field_names(IterationWriter writer) {
  std::vector<const char*> names;
  for (const IterationField& f : iteration_fields())
    if (f.writers & writer) names.push_back(f.name);
  return names;
}

}  // namespace sm
