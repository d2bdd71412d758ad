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

}  // namespace

ColoredPlyOutput::ColoredPlyOutput(const OutputContext& context)
    : BeforeAfterOutput(context, "colored", ".ply", context.config.output.colored.frames),
      options_(context.config.output.colored) {}

bool ColoredPlyOutput::enabled(const SequenceJobOptions& config) {
  return config.output.colored.enabled;
}

const char* ColoredPlyOutput::help() {
  return "  colored/{before,after}/<frame>.ply\n"
         "                              the shear (eq. 8) as colours, blue to red "
         "(\"colored\")\n";
}

std::string ColoredPlyOutput::describe(const std::vector<int>& frames) const {
  return "  colored/{before,after}/<name>.ply (" + frames_text(count_in(options_.frames, frames)) +
         ": shear 0 blue to " + stream_number(options_.max) + " and above red, " +
         (options_.colors == ShearColorMode::Faces ? "per face" : "per vertex") + ")\n";
}

json ColoredPlyOutput::report() const {
  json colored = folders_report();
  colored["shear_red"] = options_.max;
  colored["colors"] = options_.colors == ShearColorMode::Faces ? "faces" : "vertices";
  return {{"colored", colored}};
}

ResultNames ColoredPlyOutput::results() const {
  return {{"colored/ (PLY)"}, {}};
}

std::optional<std::pair<std::string, std::string>> ColoredPlyOutput::encode_sides(
    const FrameOutcome& f) const {
  const Triangles& F = f.input->mesh.F;  // the template's (checked when the frame was read)
  return std::make_pair(
      format_shear_ply(f.input->mesh.V, F, *f.shear_before, options_.max, options_.colors),
      format_shear_ply(*f.output, F, *f.shear_after, options_.max, options_.colors));
}

}  // namespace sm
