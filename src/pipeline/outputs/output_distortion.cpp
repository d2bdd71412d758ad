#include "pipeline/outputs/output_distortion.hpp"

#include "io/csv.hpp"

namespace sm {

std::string format_distortion_csv(const Eigen::VectorXd& before, const Eigen::VectorXd& after) {
  CsvWriter csv({"triangle", "shear_before", "shear_after"});
  for (Eigen::Index t = 0; t < before.size(); ++t)
    csv.cell(static_cast<int64_t>(t)).cell(before[t]).cell(after[t]).end_row();
  return csv.str();
}

bool DistortionCsvOutput::enabled(const SequenceJobOptions& config) {
  return config.output.per_triangle_csv;
}

const char* DistortionCsvOutput::help() {
  return "  distortion/<frame>.csv      shear per triangle before and after "
         "(\"per_triangle_csv\")\n";
}

std::string DistortionCsvOutput::table(const FrameOutcome& f) const {
  return format_distortion_csv(*f.shear_before, *f.shear_after);
}

}  // namespace sm
