#include "pipeline/sequence/iteration_log.hpp"

#include <variant>

#include "massage/iteration_fields.hpp"

namespace sm {

std::vector<std::string> iteration_columns() {
  std::vector<std::string> columns = {"frame", "file", "iteration"};
  for (const char* name : iteration_field_names(kIterationsCsv)) columns.push_back(name);
  for (const char* name : {"shear_max", "shear_mean", "shear_p95"}) columns.push_back(name);
  return columns;
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
    for (const IterationField& field : iteration_fields()) {
      if (!(field.writers & kIterationsCsv)) continue;
      if (row.stats)
        std::visit([&](auto member) { csv.cell((*row.stats).*member); }, field.member);
      else if (field.zero_before)
        csv.cell(0.0);
      else
        csv.cell("");
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
