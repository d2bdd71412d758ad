#include "pipeline/outputs/output_checker.hpp"

#include <cctype>

#include "io/obj_textured.hpp"
#include "io/png.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr const char* kMaterial = "checker";
constexpr const char* kMtl = "checker.mtl";
constexpr const char* kPng = "checker.png";

}  // namespace

CheckerObjOutput::CheckerObjOutput(const OutputContext& context)
    : BeforeAfterOutput(context, "checker", ".obj", context.config.output.checker.frames),
      options_(context.config.output.checker),
      template_mesh_(context.config.templ.mesh) {}

bool CheckerObjOutput::enabled(const SequenceJobOptions& config) {
  return config.output.checker.enabled;
}

const char* CheckerObjOutput::help() {
  return "  checker/{before,after}/<frame>.obj, checker.mtl, checker.png\n"
         "                              a checkerboard texture on the template's UVs "
         "(\"checker\")\n";
}

std::vector<std::string> CheckerObjOutput::side_files() const {
  return {kMtl, kPng};
}

std::string CheckerObjOutput::describe(const std::vector<int>& frames) const {
  return "  checker/{before,after}/<name>.obj, checker.mtl, checker.png (" +
         frames_text(count_in(options_.frames, frames)) + ", " + std::to_string(options_.cells) +
         "x" + std::to_string(options_.cells) + " squares; texture coordinates: " +
         (options_.uv == CheckerUvSource::Auto ? "the template's own, else charts"
                                               : "charts by normal axis") +
         ")\n";
}

json CheckerObjOutput::report() const {
  if (!uv_) return json::object();  // not started
  json checker = folders_report();
  checker["uv"] = uv_->source;
  checker["uv_template"] = template_source_;
  return {{"checker", checker}};
}

ResultNames CheckerObjOutput::results() const {
  return {{"checker/ (OBJ, MTL, PNG)"}, {}};
}

void CheckerObjOutput::start(const SequencePlan& plan) {
  std::shared_ptr<const ObjFile> obj;
  if (options_.uv == CheckerUvSource::Auto) {
    if (plan.template_frame >= 0) {
      obj = source_->decode(plan.template_frame, source_->fetch(plan.template_frame)).obj;
    } else {
      std::string ext = template_mesh_.extension().string();
      for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
      if (ext == ".obj") obj = std::make_shared<const ObjFile>(read_obj(template_mesh_));
    }
  }
  uv_ = template_uv(plan.templ, obj.get(), options_);
  template_source_ = plan.template_source;
}

std::optional<std::pair<std::string, std::string>> CheckerObjOutput::encode_sides(
    const FrameOutcome& f) const {
  if (!uv_) return std::nullopt;  // not started
  const std::string label = source_->label(f.index);
  const Triangles& F = f.input->mesh.F;  // the template's (checked when the frame was read)
  const std::string uv_text = "texture coordinates of the template, " + template_source_ +
                              (uv_->source == "input" ? " (its own)" : " (charts)");
  return std::make_pair(
      format_textured_obj(f.input->mesh.V, F, uv_->uv, uv_->faces, kMtl, kMaterial,
                          "seqmassage checker: " + label + ", input\n" + uv_text),
      format_textured_obj(*f.output, F, uv_->uv, uv_->faces, kMtl, kMaterial,
                          "seqmassage checker: " + label + ", corrected\n" + uv_text));
}

std::vector<std::pair<fs::path, std::string>> CheckerObjOutput::shared_files() const {
  const std::string png = encode_png(checker_texture(options_.cells));
  const std::string mtl = format_texture_mtl(kMaterial, kPng);
  std::vector<std::pair<fs::path, std::string>> out;
  for (const char* side : {"before", "after"}) {
    out.emplace_back(fs::path("checker") / side / kPng, png);
    out.emplace_back(fs::path("checker") / side / kMtl, mtl);
  }
  return out;
}

}  // namespace sm
