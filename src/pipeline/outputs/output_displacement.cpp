#include "pipeline/outputs/output_displacement.hpp"

#include "io/csv.hpp"

namespace sm {

std::string format_displacement_csv(const Positions& input, const Positions& output) {
  CsvWriter csv({"vertex", "dx", "dy", "dz"});
  for (Eigen::Index v = 0; v < input.rows(); ++v) {
    csv.cell(static_cast<int64_t>(v));
    for (int c = 0; c < 3; ++c) csv.cell(output(v, c) - input(v, c));
    csv.end_row();
  }
  return csv.str();
}

bool DisplacementCsvOutput::enabled(const SequenceJobOptions& config) {
  return config.output.displacement_csv;
}

const char* DisplacementCsvOutput::help() {
  return "  displacement/<frame>.csv    each vertex's move, output - input "
         "(\"displacement_csv\")\n";
}

std::string DisplacementCsvOutput::table(const FrameOutcome& f) const {
  return format_displacement_csv(f.input->mesh.V, *f.output);
}

}  // namespace sm
