#include "pipeline/frame_extras.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/obj_textured.hpp"
#include "io/png.hpp"
#include "mesh/errors.hpp"
#include "pipeline/sequence_job.hpp"
#include "pipeline/shard.hpp"
#include "pipeline/shear_ply.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr const char* kMaterial = "checker";
constexpr const char* kMtl = "checker.mtl";
constexpr const char* kPng = "checker.png";

std::string stream_number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

int count_in(const FrameSelection& selection, const std::vector<int>& frames) {
  int n = 0;
  for (int i : frames) n += selection.contains(i);
  return n;
}

std::string frames_text(int n) {
  return std::to_string(n) + (n == 1 ? " frame" : " frames");
}

class Run : public ExtrasRun {
 public:
  Run(const SequenceJobOptions& config, std::shared_ptr<const FrameSource> source,
      const TriMesh& templ, std::string template_source, std::optional<CornerUv> uv)
      : config_(config),
        source_(std::move(source)),
        templ_(templ),
        template_source_(std::move(template_source)),
        uv_(std::move(uv)),
        header_(CsvWriter(iteration_columns()).str()) {}

  ExtraFrame encode(const FrameOutcome& o) const override {
    const OutputOptions& out = config_.output;
    ExtraFrame x;
    x.frame = o.index;
    x.file = source_->name(o.index);
    const fs::path name = x.file;
    const Positions& before = o.input->mesh.V;
    const Positions& after = *o.output;
    const std::string label = source_->label(o.index);

    if (out.colored.enabled && out.colored.frames.contains(o.index)) {
      const fs::path ply = fs::path(name).replace_extension(".ply");
      x.files.emplace_back(
          fs::path("colored") / "before" / ply,
          format_shear_ply(before, templ_.F, *o.shear_before, out.colored.max, out.colored.colors));
      x.files.emplace_back(
          fs::path("colored") / "after" / ply,
          format_shear_ply(after, templ_.F, *o.shear_after, out.colored.max, out.colored.colors));
    }
    if (uv_ && out.checker.frames.contains(o.index)) {
      const fs::path obj = fs::path(name).replace_extension(".obj");
      const std::string uv_text = "texture coordinates of the template, " + template_source_ +
                                  (uv_->source == "input" ? " (its own)" : " (charts)");
      x.files.emplace_back(
          fs::path("checker") / "before" / obj,
          format_textured_obj(before, templ_.F, uv_->uv, uv_->faces, kMtl, kMaterial,
                              "seqmassage checker: " + label + ", input\n" + uv_text));
      x.files.emplace_back(
          fs::path("checker") / "after" / obj,
          format_textured_obj(after, templ_.F, uv_->uv, uv_->faces, kMtl, kMaterial,
                              "seqmassage checker: " + label + ", corrected\n" + uv_text));
    }
    if (out.iterations.enabled && o.result &&
        (out.iterations.frames.contains(o.index) ||
         out.iterations.shear_frames.contains(o.index))) {
      const std::vector<std::optional<DistortionSummary>> none;
      const bool with_shear =
          out.iterations.shear_frames.contains(o.index) && o.result->ok && o.shear_per_iteration;
      x.iterations = iteration_rows(*o.result, summarize_distortion(*o.shear_before),
                                    summarize_distortion(*o.shear_after),
                                    with_shear ? *o.shear_per_iteration : none);
      CsvWriter rows(iteration_columns());
      append_iteration_rows(rows, x.frame, x.file, x.iterations);
      x.iterations_csv = rows.str().substr(header_.size());
    }
    return x;
  }

  void write(const ExtraFrame& x) override {
    const fs::path& dir = config_.output.dir;
    for (const auto& [path, bytes] : x.files) {
      if (!texture_written_ && *path.begin() == "checker") {
        const std::string png = encode_png(checker_texture(config_.output.checker.cells));
        const std::string mtl = format_texture_mtl(kMaterial, kPng);
        for (const char* side : {"before", "after"}) {
          write_file_atomic(dir / "checker" / side / kPng, png);
          write_file_atomic(dir / "checker" / side / kMtl, mtl);
        }
        texture_written_ = true;
      }
      write_file_atomic(dir / path, bytes);
    }
    rows_ += x.iterations_csv;
  }

  void keep(const std::string& iterations_csv) override { rows_ += iterations_csv; }

  json finish() override {
    const OutputOptions& out = config_.output;
    json r = json::object();
    if (out.colored.enabled)
      r["colored"] = {
          {"before", "colored/before/"},
          {"after", "colored/after/"},
          {"shear_red", out.colored.max},
          {"colors", out.colored.colors == ShearColorMode::Faces ? "faces" : "vertices"}};
    if (out.checker.enabled && uv_)
      r["checker"] = {{"before", "checker/before/"},
                      {"after", "checker/after/"},
                      {"uv", uv_->source},
                      {"uv_template", template_source_}};
    if (out.iterations.enabled) {
      const std::string name = iterations_file_name(config_.shard);
      write_file_atomic(out.dir / name, header_ + rows_);
      r["iterations"] = name;
    }
    return r;
  }

 private:
  SequenceJobOptions config_;
  std::shared_ptr<const FrameSource> source_;
  TriMesh templ_;
  std::string template_source_;
  std::optional<CornerUv> uv_;
  std::string header_;  // of iterations.csv
  std::string rows_;    // its rows, frame by frame
  bool texture_written_ = false;
};

}  // namespace

FrameExtras::FrameExtras(const SequenceJobOptions& config,
                         std::shared_ptr<const FrameSource> source)
    : config_(config), source_(std::move(source)) {}

bool FrameExtras::any() const {
  const OutputOptions& o = config_.output;
  return o.colored.enabled || o.checker.enabled || o.iterations.enabled;
}

bool FrameExtras::wants_shear_per_iteration(int index) const {
  const IterationLogOptions& o = config_.output.iterations;
  return o.enabled && o.shear_frames.contains(index);
}

std::vector<fs::path> FrameExtras::files(const std::vector<int>& frames) const {
  const OutputOptions& o = config_.output;
  std::vector<fs::path> out;
  for (const char* side : {"before", "after"}) {
    for (int i : frames) {
      const fs::path name = source_->name(i);
      if (o.colored.enabled && o.colored.frames.contains(i))
        out.push_back(o.dir / "colored" / side / fs::path(name).replace_extension(".ply"));
      if (o.checker.enabled && o.checker.frames.contains(i))
        out.push_back(o.dir / "checker" / side / fs::path(name).replace_extension(".obj"));
    }
    if (o.checker.enabled) {
      out.push_back(o.dir / "checker" / side / kMtl);
      out.push_back(o.dir / "checker" / side / kPng);
    }
  }
  if (o.iterations.enabled) out.push_back(o.dir / "iterations.csv");
  return out;
}

std::vector<fs::path> FrameExtras::folders() const {
  const OutputOptions& o = config_.output;
  std::vector<fs::path> out;
  for (const char* side : {"before", "after"}) {
    if (o.colored.enabled) out.push_back(o.dir / "colored" / side);
    if (o.checker.enabled) out.push_back(o.dir / "checker" / side);
  }
  return out;
}

std::string FrameExtras::describe(const std::vector<int>& frames) const {
  const OutputOptions& o = config_.output;
  std::string s;
  if (o.colored.enabled)
    s += "  colored/{before,after}/<name>.ply (" + frames_text(count_in(o.colored.frames, frames)) +
         ": shear 0 blue to " + stream_number(o.colored.max) + " and above red, " +
         (o.colored.colors == ShearColorMode::Faces ? "per face" : "per vertex") + ")\n";
  if (o.checker.enabled)
    s += "  checker/{before,after}/<name>.obj, checker.mtl, checker.png (" +
         frames_text(count_in(o.checker.frames, frames)) + ", " + std::to_string(o.checker.cells) +
         "x" + std::to_string(o.checker.cells) + " squares; texture coordinates: " +
         (o.checker.uv == CheckerUvSource::Auto ? "the template's own, else charts"
                                                : "charts by normal axis") +
         ")\n";
  if (o.iterations.enabled) {
    const int shear = count_in(o.iterations.shear_frames, frames);
    s += "  iterations.csv (the optimized frames among " +
         frames_text(count_in(o.iterations.frames, frames)) + "; shear after every iteration for " +
         frames_text(shear) + ")\n";
  }
  return s;
}

std::vector<std::string> FrameExtras::check(const std::vector<int>& frames) const {
  const OutputOptions& o = config_.output;
  std::vector<std::string> warnings;
  const auto unlisted = [&](const FrameSelection& selection, bool enabled, const std::string& key) {
    if (!enabled || selection.kind != FrameSelection::Kind::List) return;
    std::string missing;
    for (int i : selection.list)
      if (!std::binary_search(frames.begin(), frames.end(), i))
        missing += (missing.empty() ? "" : ", ") + std::to_string(i);
    if (!missing.empty())
      warnings.push_back(key + ": frame" + (missing.find(',') == std::string::npos ? " " : "s ") +
                         missing + " not processed by this run (see input.range and --frames)");
  };
  unlisted(o.colored.frames, o.colored.enabled, "output.colored.frames");
  unlisted(o.checker.frames, o.checker.enabled, "output.checker.frames");
  unlisted(o.iterations.frames, o.iterations.enabled, "output.iterations.frames");
  unlisted(o.iterations.shear_frames, o.iterations.enabled, "output.iterations.shear_frames");
  return warnings;
}

std::unique_ptr<ExtrasRun> FrameExtras::start(const SequencePlan& plan) const {
  std::optional<CornerUv> uv;
  if (config_.output.checker.enabled) {
    std::shared_ptr<const ObjFile> obj;
    if (config_.output.checker.uv == CheckerUvSource::Auto) {
      if (plan.template_frame >= 0) {
        obj = source_->decode(plan.template_frame, source_->fetch(plan.template_frame)).obj;
      } else {
        fs::path rest = config_.templ.mesh;
        std::string ext = rest.extension().string();
        for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (ext == ".obj") obj = std::make_shared<const ObjFile>(read_obj(rest));
      }
    }
    uv = template_uv(plan.templ, obj.get(), config_.output.checker);
  }
  return std::make_unique<Run>(config_, source_, plan.templ, plan.template_source, std::move(uv));
}

}  // namespace sm
