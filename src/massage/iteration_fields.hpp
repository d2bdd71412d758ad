#pragma once
/// The figures of IterationStats by name, described once: iterations.csv, the mesh jobs'
/// report.json and the Python module's per-iteration dict read this list, each taking the fields
/// it shows (`writers`), in this order.
#include <variant>
#include <vector>

#include "massage/massage_result.hpp"

namespace sm {

/// The writers of IterationStats (bits of IterationField::writers).
enum IterationWriter : unsigned {
  kIterationsCsv = 1u,  ///< iterations.csv's engine columns (after frame, file, iteration)
  kReportJson = 2u,     ///< report.json "massage.iterations" of the remesh/crossparam/smooth jobs
  kPythonDict = 4u,     ///< seqmassage.Result.iterations
};

/// One figure of an outer iteration.
struct IterationField {
  const char* name;
  std::variant<int IterationStats::*, double IterationStats::*> member;
  unsigned writers;  ///< IterationWriter bits
  /// iterations.csv's row 0 (the input, no iteration yet) shows 0 rather than an empty cell:
  /// the closest-point distances, 0 because the optimized mesh starts on the reference.
  bool zero_before = false;
};

/// Every figure of IterationStats, in the writers' order.
const std::vector<IterationField>& iteration_fields();

/// The names of the fields `writer` shows, in order.
std::vector<const char*> iteration_field_names(IterationWriter writer);

}  // namespace sm
