#include "pipeline/outputs/output_before_after.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {
constexpr const char* kSides[] = {"before", "after"};
}  // namespace

BeforeAfterOutput::BeforeAfterOutput(const OutputContext& context, std::string folder,
                                     std::string extension, const FrameSelection& frames)
    : dir_(context.config.output.dir),
      folder_(std::move(folder)),
      extension_(std::move(extension)),
      frames_(frames),
      source_(context.source) {}

std::vector<fs::path> BeforeAfterOutput::files(const std::vector<int>& frames) const {
  std::vector<fs::path> out;
  for (const char* side : kSides) {
    for (int i : frames)
      if (frames_.contains(i))
        out.push_back(dir_ / folder_ / side / fs::path(source_->name(i)).replace_extension(extension_));
    for (const std::string& file : side_files()) out.push_back(dir_ / folder_ / side / file);
  }
  return out;
}

std::vector<fs::path> BeforeAfterOutput::folders() const {
  return {dir_ / folder_ / kSides[0], dir_ / folder_ / kSides[1]};
}

std::vector<std::string> BeforeAfterOutput::check(const std::vector<int>& selected) const {
  return unlisted_frames(frames_, selected, "output." + folder_ + ".frames");
}

json BeforeAfterOutput::folders_report() const {
  return {{"before", folder_ + "/before/"}, {"after", folder_ + "/after/"}};
}

OutputFrame BeforeAfterOutput::encode(const FrameOutcome& f) const {
  OutputFrame out;
  if (!frames_.contains(f.index)) return out;
  std::optional<std::pair<std::string, std::string>> sides = encode_sides(f);
  if (!sides) return out;
  const fs::path name = fs::path(source_->name(f.index)).replace_extension(extension_);
  out.files.emplace_back(fs::path(folder_) / kSides[0] / name, std::move(sides->first));
  out.files.emplace_back(fs::path(folder_) / kSides[1] / name, std::move(sides->second));
  out.needs_shared = !side_files().empty();
  return out;
}

}  // namespace sm
