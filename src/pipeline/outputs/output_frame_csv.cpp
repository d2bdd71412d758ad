#include "pipeline/outputs/output_frame_csv.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

FrameCsvOutput::FrameCsvOutput(const OutputContext& context, std::string folder)
    : dir_(context.config.output.dir), folder_(std::move(folder)), source_(context.source) {}

fs::path FrameCsvOutput::file(int index) const {
  return fs::path(folder_) / fs::path(source_->name(index)).replace_extension(".csv");
}

std::vector<fs::path> FrameCsvOutput::files(const std::vector<int>& frames) const {
  std::vector<fs::path> out;
  for (int i : frames) out.push_back(dir_ / file(i));
  return out;
}

std::vector<fs::path> FrameCsvOutput::folders() const { return {dir_ / folder_}; }

std::string FrameCsvOutput::describe(const std::vector<int>& frames) const {
  return "  " + folder_ + "/<name>.csv (" + std::to_string(frames.size()) + " files)\n";
}

json FrameCsvOutput::report() const { return {{folder_, folder_ + "/"}}; }

ResultNames FrameCsvOutput::results() const { return {{folder_ + "/"}, {}}; }

OutputFrame FrameCsvOutput::encode(const FrameOutcome& f) const {
  OutputFrame out;
  out.files.emplace_back(file(f.index), table(f));
  return out;
}

}  // namespace sm
