#include "pipeline/outputs/output_html.hpp"

#include <cctype>
#include <cmath>

#include "io/atomic_file.hpp"
#include "io/obj.hpp"
#include "pipeline/outputs/checker.hpp"
#include "pipeline/report/report.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr const char* kDataDir = "report_data";
constexpr const char* kPage = "report.html";

fs::path data_file(const std::string& frame_name) {
  return fs::path(kDataDir) / (frame_name + ".bin");
}

// The animation's frame rate: from the frames' times (glTF, MDD), else output.point_cache.fps.
double frame_rate(const std::vector<FrameSummary>& frames, double fallback) {
  const FrameSummary* first = nullptr;
  const FrameSummary* last = nullptr;
  for (const FrameSummary& f : frames) {
    if (!f.time) continue;
    if (!first) first = &f;
    last = &f;
  }
  if (first && last && last->frame > first->frame && *last->time > *first->time) {
    const double fps = (last->frame - first->frame) / (*last->time - *first->time);
    if (std::isfinite(fps) && fps > 0 && fps < 1000) return fps;
  }
  return fallback;
}

}  // namespace

HtmlReportOutput::HtmlReportOutput(const OutputContext& context)
    : config_(context.config), source_(context.source) {}

bool HtmlReportOutput::enabled(const SequenceJobOptions& config) { return config.output.html; }

const char* HtmlReportOutput::help() {
  return "  report.html, report_data/   a self-contained page of the run: plots, tables and a "
         "3D player\n"
         "                              of the frames before and after (\"html\")\n";
}

std::vector<fs::path> HtmlReportOutput::files(const std::vector<int>& frames) const {
  const fs::path& dir = config_.output.dir;
  std::vector<fs::path> out;
  for (int i : frames) out.push_back(dir / data_file(source_->name(i)));
  out.push_back(dir / kDataDir / "template.bin");
  out.push_back(dir / kPage);  // a shard's: written by `seqmassage merge`, as summary.csv
  return out;
}

std::vector<fs::path> HtmlReportOutput::folders() const {
  return {config_.output.dir / kDataDir};
}

std::string HtmlReportOutput::describe(const std::vector<int>& frames) const {
  std::string text = "  report_data/<name>.bin, template.bin (" + frames_text(int(frames.size())) +
                     ": the player's positions and shear)\n";
  if (config_.shard.sharded())
    text += "  report.html: written from every shard's data by seqmassage merge\n";
  else
    text += "  report.html (at most " + format_number(config_.output.html_max_mb) + " MB; " +
            (html_player_available() ? std::string("with the 3D player")
                                     : html_player_missing_reason()) +
            ")\n";
  return text;
}

json HtmlReportOutput::report() const { return {{"html", kPage}, {"html_data", "report_data/"}}; }

ResultNames HtmlReportOutput::results() const {
  if (config_.shard.sharded()) return {{"report_data/"}, {}};
  return {{"report_data/"}, {kPage}};
}

void HtmlReportOutput::start(const SequencePlan& plan) {
  std::shared_ptr<const ObjFile> obj;
  const CheckerOutputOptions& checker = config_.output.checker;
  if (checker.uv == CheckerUvSource::Auto) {
    if (plan.template_frame >= 0) {
      obj = source_->decode(plan.template_frame, source_->fetch(plan.template_frame)).obj;
    } else {
      std::string ext = config_.templ.mesh.extension().string();
      for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
      if (ext == ".obj") obj = std::make_shared<const ObjFile>(read_obj(config_.templ.mesh));
    }
  }
  const CornerUv uv = template_uv(plan.templ, obj.get(), checker);
  PlayerTemplate t;
  t.vertices = int(plan.templ.num_vertices());
  t.F = plan.templ.F;
  t.uv_source = uv.source;
  t.corner_uv.reserve(size_t(t.F.rows()) * 6);
  for (Eigen::Index i = 0; i < uv.faces.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 2; ++k) t.corner_uv.push_back(float(uv.uv(uv.faces(i, c), k)));
  template_ = std::move(t);
}

OutputFrame HtmlReportOutput::encode(const FrameOutcome& f) const {
  OutputFrame out;
  out.files.emplace_back(data_file(source_->name(f.index)),
                         encode_player_frame(f.input->mesh.V, *f.output, *f.shear_before,
                                             *f.shear_after));
  out.needs_shared = true;
  return out;
}

std::vector<std::pair<fs::path, std::string>> HtmlReportOutput::shared_files() const {
  if (!template_) return {};
  return {{fs::path(kDataDir) / "template.bin", encode_player_template(*template_)}};
}

OutputFinish HtmlReportOutput::finish(const FinishedFrames& done) const {
  if (config_.shard.sharded() || !done.summaries) return {};
  SequenceJobOptions job = config_;  // as report.json's config: the run controls reset
  job.shard = ShardOptions{};
  job.resume = false;
  SequencePageInput in;
  in.title = "seqmassage report: " + config_.output.dir.filename().string();
  in.summary_csv = format_summary_csv(*done.summaries, config_.output.timings);
  in.frames = done.summaries;
  if (done.warnings) in.warnings = *done.warnings;
  in.config = to_json(job);
  in.versions = version_info();
  in.fps = frame_rate(*done.summaries, config_.output.point_cache.fps);
  in.checker_cells = config_.output.checker.cells;
  const fs::path data = config_.output.dir / kDataDir;
  const std::vector<std::string>& names = done.names;
  const auto templ = std::make_shared<PlayerTemplate>();
  in.load_template = [data, templ] {
    const fs::path file = data / "template.bin";
    *templ = decode_player_template(read_file(file), file.string());
    return *templ;
  };
  in.load = [data, templ, &names](size_t k) {
    const fs::path file = data / (names[k] + ".bin");
    return decode_player_frame(read_file(file), templ->vertices, int(templ->F.rows()),
                               file.string());
  };
  if (html_player_available()) in.data_frames = done.frames;
  in.budget_bytes = size_t(config_.output.html_max_mb * 1024 * 1024);
  SequencePage page = make_sequence_page(in);
  write_file_atomic(config_.output.dir / kPage, page.html);
  return {std::move(page.warnings), {kPage}};
}

}  // namespace sm
