#include "pipeline/output_displacement.hpp"

#include "io/csv.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

std::string format_displacement_csv(const Positions& input, const Positions& output) {
  CsvWriter csv({"vertex", "dx", "dy", "dz"});
  for (Eigen::Index v = 0; v < input.rows(); ++v) {
    csv.cell(static_cast<int64_t>(v));
    for (int c = 0; c < 3; ++c) csv.cell(output(v, c) - input(v, c));
    csv.end_row();
  }
  return csv.str();
}

DisplacementCsvOutput::DisplacementCsvOutput(const OutputContext& context)
    : dir_(context.config.output.dir), source_(context.source) {}

bool DisplacementCsvOutput::enabled(const SequenceJobOptions& config) {
  return config.output.displacement_csv;
}

const char* DisplacementCsvOutput::help() {
  return "  displacement/<frame>.csv    each vertex's move, output - input "
         "(\"displacement_csv\")\n";
}

fs::path DisplacementCsvOutput::file(int index) const {
  return fs::path("displacement") / fs::path(source_->name(index)).replace_extension(".csv");
}

std::vector<fs::path> DisplacementCsvOutput::files(const std::vector<int>& frames) const {
  std::vector<fs::path> out;
  for (int i : frames) out.push_back(dir_ / file(i));
  return out;
}

std::vector<fs::path> DisplacementCsvOutput::folders() const { return {dir_ / "displacement"}; }

std::string DisplacementCsvOutput::describe(const std::vector<int>& frames) const {
  return "  displacement/<name>.csv (" + std::to_string(frames.size()) + " files)\n";
}

json DisplacementCsvOutput::report() const { return {{"displacement", "displacement/"}}; }

ResultNames DisplacementCsvOutput::results() const { return {{"displacement/"}, {}}; }

OutputFrame DisplacementCsvOutput::encode(const FrameOutcome& f) const {
  OutputFrame out;
  out.files.emplace_back(file(f.index), format_displacement_csv(f.input->mesh.V, *f.output));
  return out;
}

}  // namespace sm
