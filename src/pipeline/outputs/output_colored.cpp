#include "pipeline/outputs/output_colored.hpp"

#include <sstream>

#include "pipeline/outputs/shear_ply.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::string stream_number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

fs::path ply_name(const std::string& frame_name) {
  return fs::path(frame_name).replace_extension(".ply");
}

}  // namespace

ColoredPlyOutput::ColoredPlyOutput(const OutputContext& context)
    : dir_(context.config.output.dir),
      options_(context.config.output.colored),
      source_(context.source) {}

bool ColoredPlyOutput::enabled(const SequenceJobOptions& config) {
  return config.output.colored.enabled;
}

const char* ColoredPlyOutput::help() {
  return "  colored/{before,after}/<frame>.ply\n"
         "                              the shear (eq. 8) as colours, blue to red "
         "(\"colored\")\n";
}

std::vector<fs::path> ColoredPlyOutput::files(const std::vector<int>& frames) const {
  std::vector<fs::path> out;
  for (const char* side : {"before", "after"})
    for (int i : frames)
      if (options_.frames.contains(i)) out.push_back(dir_ / "colored" / side / ply_name(source_->name(i)));
  return out;
}

std::vector<fs::path> ColoredPlyOutput::folders() const {
  return {dir_ / "colored" / "before", dir_ / "colored" / "after"};
}

std::string ColoredPlyOutput::describe(const std::vector<int>& frames) const {
  return "  colored/{before,after}/<name>.ply (" + frames_text(count_in(options_.frames, frames)) +
         ": shear 0 blue to " + stream_number(options_.max) + " and above red, " +
         (options_.colors == ShearColorMode::Faces ? "per face" : "per vertex") + ")\n";
}

std::vector<std::string> ColoredPlyOutput::check(const std::vector<int>& selected) const {
  return unlisted_frames(options_.frames, selected, "output.colored.frames");
}

json ColoredPlyOutput::report() const {
  return {{"colored",
           {{"before", "colored/before/"},
            {"after", "colored/after/"},
            {"shear_red", options_.max},
            {"colors", options_.colors == ShearColorMode::Faces ? "faces" : "vertices"}}}};
}

ResultNames ColoredPlyOutput::results() const {
  return {{"colored/ (PLY)"}, {}};
}

OutputFrame ColoredPlyOutput::encode(const FrameOutcome& f) const {
  OutputFrame out;
  if (!options_.frames.contains(f.index)) return out;
  const fs::path ply = ply_name(source_->name(f.index));
  const Triangles& F = f.input->mesh.F;  // the template's (checked when the frame was read)
  out.files.emplace_back(fs::path("colored") / "before" / ply,
                         format_shear_ply(f.input->mesh.V, F, *f.shear_before, options_.max,
                                          options_.colors));
  out.files.emplace_back(
      fs::path("colored") / "after" / ply,
      format_shear_ply(*f.output, F, *f.shear_after, options_.max, options_.colors));
  return out;
}

}  // namespace sm
