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

fs::path obj_name(const std::string& frame_name) {
  return fs::path(frame_name).replace_extension(".obj");
}

}  // namespace

CheckerObjOutput::CheckerObjOutput(const OutputContext& context)
    : dir_(context.config.output.dir),
      options_(context.config.output.checker),
      template_mesh_(context.config.templ.mesh),
      source_(context.source) {}

bool CheckerObjOutput::enabled(const SequenceJobOptions& config) {
  return config.output.checker.enabled;
}

const char* CheckerObjOutput::help() {
  return "  checker/{before,after}/<frame>.obj, checker.mtl, checker.png\n"
         "                              a checkerboard texture on the template's UVs "
         "(\"checker\")\n";
}

std::vector<fs::path> CheckerObjOutput::files(const std::vector<int>& frames) const {
  std::vector<fs::path> out;
  for (const char* side : {"before", "after"}) {
    for (int i : frames)
      if (options_.frames.contains(i)) out.push_back(dir_ / "checker" / side / obj_name(source_->name(i)));
    out.push_back(dir_ / "checker" / side / kMtl);
    out.push_back(dir_ / "checker" / side / kPng);
  }
  return out;
}

std::vector<fs::path> CheckerObjOutput::folders() const {
  return {dir_ / "checker" / "before", dir_ / "checker" / "after"};
}

std::string CheckerObjOutput::describe(const std::vector<int>& frames) const {
  return "  checker/{before,after}/<name>.obj, checker.mtl, checker.png (" +
         frames_text(count_in(options_.frames, frames)) + ", " + std::to_string(options_.cells) +
         "x" + std::to_string(options_.cells) + " squares; texture coordinates: " +
         (options_.uv == CheckerUvSource::Auto ? "the template's own, else charts"
                                               : "charts by normal axis") +
         ")\n";
}

std::vector<std::string> CheckerObjOutput::check(const std::vector<int>& selected) const {
  return unlisted_frames(options_.frames, selected, "output.checker.frames");
}

json CheckerObjOutput::report() const {
  if (!uv_) return json::object();  // not started
  return {{"checker",
           {{"before", "checker/before/"},
            {"after", "checker/after/"},
            {"uv", uv_->source},
            {"uv_template", template_source_}}}};
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

OutputFrame CheckerObjOutput::encode(const FrameOutcome& f) const {
  OutputFrame out;
  if (!uv_ || !options_.frames.contains(f.index)) return out;
  const fs::path obj = obj_name(source_->name(f.index));
  const std::string label = source_->label(f.index);
  const Triangles& F = f.input->mesh.F;  // the template's (checked when the frame was read)
  const std::string uv_text = "texture coordinates of the template, " + template_source_ +
                              (uv_->source == "input" ? " (its own)" : " (charts)");
  out.files.emplace_back(fs::path("checker") / "before" / obj,
                         format_textured_obj(f.input->mesh.V, F, uv_->uv, uv_->faces, kMtl,
                                             kMaterial,
                                             "seqmassage checker: " + label + ", input\n" + uv_text));
  out.files.emplace_back(fs::path("checker") / "after" / obj,
                         format_textured_obj(*f.output, F, uv_->uv, uv_->faces, kMtl, kMaterial,
                                             "seqmassage checker: " + label + ", corrected\n" +
                                                 uv_text));
  out.needs_shared = true;
  return out;
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
