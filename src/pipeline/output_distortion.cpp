#include "pipeline/output_distortion.hpp"

#include "io/csv.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

std::string format_distortion_csv(const Eigen::VectorXd& before, const Eigen::VectorXd& after) {
  CsvWriter csv({"triangle", "shear_before", "shear_after"});
  for (Eigen::Index t = 0; t < before.size(); ++t)
    csv.cell(static_cast<int64_t>(t)).cell(before[t]).cell(after[t]).end_row();
  return csv.str();
}

DistortionCsvOutput::DistortionCsvOutput(const OutputContext& context)
    : dir_(context.config.output.dir), source_(context.source) {}

bool DistortionCsvOutput::enabled(const SequenceJobOptions& config) {
  return config.output.per_triangle_csv;
}

const char* DistortionCsvOutput::help() {
  return "  distortion/<frame>.csv      shear per triangle before and after "
         "(\"per_triangle_csv\")\n";
}

fs::path DistortionCsvOutput::file(int index) const {
  return fs::path("distortion") / fs::path(source_->name(index)).replace_extension(".csv");
}

std::vector<fs::path> DistortionCsvOutput::files(const std::vector<int>& frames) const {
  std::vector<fs::path> out;
  for (int i : frames) out.push_back(dir_ / file(i));
  return out;
}

std::vector<fs::path> DistortionCsvOutput::folders() const {
  return {dir_ / "distortion"};
}

std::string DistortionCsvOutput::describe(const std::vector<int>& frames) const {
  return "  distortion/<name>.csv (" + std::to_string(frames.size()) + " files)\n";
}

json DistortionCsvOutput::report() const {
  return {{"distortion", "distortion/"}};
}

ResultNames DistortionCsvOutput::results() const {
  return {{"distortion/"}, {}};
}

OutputFrame DistortionCsvOutput::encode(const FrameOutcome& f) const {
  OutputFrame out;
  out.files.emplace_back(file(f.index), format_distortion_csv(*f.shear_before, *f.shear_after));
  return out;
}

}  // namespace sm
