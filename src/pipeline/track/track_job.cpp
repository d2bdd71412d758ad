#include "pipeline/track/track_job.hpp"

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <map>
#include <sstream>

#include "geometry/shear.hpp"
#include "io/atomic_file.hpp"
#include "io/gltf/gltf_from_obj.hpp"
#include "io/csv.hpp"
#include "core/errors.hpp"
#include "core/timing.hpp"
#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/sequence/input_clash.hpp"
#include "pipeline/cluster/frame_record.hpp"
#include "pipeline/cluster/output_lock.hpp"
#include "pipeline/report/report.hpp"
#include "pipeline/sequence/shard.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {


// Refuses two selected frames whose outputs share a name, letter case aside (a.obj and a.ply
// both write frames/a.obj).
void check_output_names(const TrackPlan& plan) {
  std::map<std::string, int> seen;
  for (int i : plan.block) {
    std::string name = plan.outputs.source->name(i);
    for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
    const auto [at, fresh] = seen.emplace(name, i);
    if (!fresh)
      throw InputError("frames " + std::to_string(at->second) + " (" +
                       plan.files[size_t(at->second)].filename().string() + ") and " +
                       std::to_string(i) + " (" + plan.files[size_t(i)].filename().string() +
                       ") would both write " + plan.outputs.source->name(i) +
                       " (their names differ only in letter case or extension); rename one");
  }
}

void check_outputs(const TrackPlan& plan) {
  const TrackJobOptions& c = plan.config;
  std::vector<ReadFile> inputs = {{"the config", c.config_file}, {"template.mesh", c.templ.mesh}};
  for (const fs::path& file : plan.files) inputs.push_back({"the input", file});
  std::vector<fs::path> outputs;
  for (const auto& output : plan.outputs.outputs)
    for (fs::path& file : output->files(plan.block)) outputs.push_back(std::move(file));
  outputs.push_back(c.output.dir / summary_file_name(c.shard));
  outputs.push_back(c.output.dir / report_file_name(c.shard));
  refuse_overwriting_inputs(inputs, outputs);
}

std::string number(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

// "from_raw_mean 0.53 > lost_distance 0.2; folded 40 > ...": the figures beyond the tolerances.
std::string beyond_text(const FitFigures& f, const TrackOptions& o, int triangles) {
  std::string text;
  const auto add = [&](const char* figure, double value, const char* key, double limit) {
    if (value > limit)
      text += (text.empty() ? "" : "; ") + std::string(figure) + " " + number(value) + " > " +
              key + " " + number(limit);
  };
  add("to_raw_mean", f.to_raw_mean, "lost_distance", o.lost_distance);
  add("from_raw_mean", f.from_raw_mean, "lost_distance", o.lost_distance);
  add("to_raw_p99", f.to_raw_p99, "lost_distance_p99", o.lost_distance_p99);
  add("from_raw_p99", f.from_raw_p99, "lost_distance_p99", o.lost_distance_p99);
  add("folded fraction", triangles > 0 ? double(f.folded) / triangles : 0.0,
      "lost_folded_fraction", o.lost_folded_fraction);
  return text;
}

// A frame's row as the sequence job's outputs see it (report.html's tables): registration
// before, refined after; a lost frame is a failed one.
FrameSummary frame_summary(const TrackRow& row, const std::string& name, int vertices,
                           int triangles, const Eigen::VectorXd& before,
                           const Eigen::VectorXd& after) {
  FrameSummary s;
  s.frame = row.frame;
  s.file = name;
  s.vertices = vertices;
  s.triangles = triangles;
  s.shear_before = summarize_distortion(before);
  s.shear_after = summarize_distortion(after);
  s.iterations = row.iterations;
  s.seconds = row.seconds_register + row.seconds_refine;
  s.folded_triangles = row.fit.folded;
  if (row.status == TrackStatus::Lost) {
    s.status = FrameStatus::Failed;
    s.failure = "lost: " + row.beyond;
  }
  return s;
}

// sequence.glb's source ("format": "gltf"): the template as glTF, frame k at k / fps seconds.
std::function<std::shared_ptr<const GltfSequence>()> template_gltf(const TrackPlan& plan) {
  return [obj = plan.layout.obj, count = plan.files.size(), fps = plan.config.output.gltf.fps.value_or(GltfWriteOptions::kDefaultFps),
          name = plan.template_source] {
    std::vector<double> times;
    for (size_t k = 0; k < count; ++k) times.push_back(double(k) / fps);
    return std::make_shared<const GltfSequence>(gltf_sequence_from_obj(*obj, times, name));
  };
}

}  // namespace

TrackPlan plan_track_job(const TrackJobOptions& config) {
  TrackPlan plan;
  plan.config = config;
  const TrackJobOptions& c = plan.config;
  plan.threads = c.threads > 0 ? c.threads : std::max(1, tbb::info::default_concurrency());
  plan.files = list_raw_frames(c.input.frames);
  const int count = int(plan.files.size());
  plan.selected = select_frames(c.input.range, count);
  if (plan.selected.empty())
    throw ConfigError("input.range: selects no frame of the " + std::to_string(count));
  if (c.input.range.stop && *c.input.range.stop > count)
    plan.warnings.push_back("input.range.stop " + std::to_string(*c.input.range.stop) +
                            " is past the last frame; the folder has " + std::to_string(count));

  if (c.templ.mesh.empty()) {
    if (c.templ.frame >= count)
      throw ConfigError("template.frame: " + std::to_string(c.templ.frame) +
                        " is out of range (the folder has " + std::to_string(count) +
                        " frames, 0 to " + std::to_string(count - 1) + ")");
    plan.template_frame = c.templ.frame;
    plan.template_source = frame_label(plan.template_frame,
                                       plan.files[size_t(plan.template_frame)].filename().string(),
                                       std::nullopt);
    plan.layout = read_template_layout(plan.files[size_t(plan.template_frame)],
                                       "template, frame " + std::to_string(plan.template_frame));
  } else {
    plan.template_source = c.templ.mesh.filename().string();
    plan.layout = read_template_layout(c.templ.mesh, "template.mesh");
  }
  // Tracked from the template frame forward, then backward from it; a mesh: forward. A shard
  // whose block does not reach the template frame: forward from the block's first frame.
  plan.block = shard_frames(plan.selected, c.shard);
  plan.start_frame = plan.template_frame;
  if (c.shard.sharded() && !plan.block.empty() &&
      (plan.template_frame < plan.block.front() || plan.template_frame > plan.block.back()))
    plan.start_frame = plan.block.front();
  for (int i : plan.block)
    if (i >= plan.start_frame) plan.order.push_back(i);
  for (auto it = plan.block.rbegin(); it != plan.block.rend(); ++it)
    if (*it < plan.start_frame) plan.order.push_back(*it);

  const TriMesh& templ = plan.layout.obj->mesh;
  plan.weld = weld_by_position(templ.V, templ.F);
  if (plan.weld.mesh.num_triangles() == 0)
    throw InputError("template (" + plan.template_source + "): no triangle of non-zero extent");
  if (plan.weld.merged > 0)
    plan.warnings.push_back("template (" + plan.template_source + "): " +
                            std::to_string(plan.weld.merged) +
                            " vertices split along seams welded by position for tracking");
  {  // the options and the template, checked once (the run builds its own)
    tbb::task_arena arena(plan.threads);
    arena.execute([&] {
      with_option_path(
          "", [&] { (void)Tracker(plan.weld.mesh, c.track, output_job_options(c).massage); });
    });
  }

  SequencePlan& out = plan.outputs;
  out.config = output_job_options(c);
  out.source = std::make_shared<TrackLayoutSource>(c.input.frames, plan.files, plan.layout);
  out.outputs = make_frame_outputs({out.config, out.source, template_gltf(plan)});
  out.selected = plan.selected;
  out.run_frames = plan.block;
  out.template_frame = plan.template_frame;
  out.template_source = plan.template_source;
  out.templ = templ;
  out.threads = plan.threads;
  for (const auto& output : out.outputs)
    for (std::string& warning : output->check(plan.block))
      plan.warnings.push_back(std::move(warning));
  check_output_names(plan);
  check_outputs(plan);
  return plan;
}

std::string describe_track_plan(const TrackPlan& plan) {
  const TrackJobOptions& c = plan.config;
  std::ostringstream s;
  s << "job: track\n";
  s << "input: " << plan.outputs.source->describe() << "\n";
  s << "frames: " << plan.selected.size() << " selected (" << format_frame_range(c.input.range)
    << "): " << plan.files[size_t(plan.selected.front())].filename().string();
  if (plan.selected.size() > 1)
    s << " ... " << plan.files[size_t(plan.selected.back())].filename().string();
  s << "\n";
  if (c.shard.sharded()) {
    s << shard_label(c.shard) << ": " << plan.block.size() << " frames";
    if (!plan.block.empty())
      s << ", " << plan.files[size_t(plan.block.front())].filename().string() << " to "
        << plan.files[size_t(plan.block.back())].filename().string() << ", tracked from "
        << (plan.start_frame == plan.template_frame ? "the template frame"
                                                    : "the template registered onto the first");
    s << "\n";
  }
  s << "template: " << plan.template_source << ", " << plan.layout.obj->mesh.num_vertices()
    << " vertices (" << plan.weld.mesh.num_vertices() << " welded), "
    << plan.weld.mesh.num_triangles() << " triangles\n";
  s << "tracking: deformation graph (node spacing " << number(c.track.node_spacing)
    << " edges), " << c.track.stages << " stages of at most " << c.track.iterations
    << " ICP iterations, then " << c.track.refine_iterations
    << " Mesh Massage iterations toward each raw frame; lost beyond a mean distance of "
    << number(c.track.lost_distance) << " edges, a 99th percentile of "
    << number(c.track.lost_distance_p99) << ", or " << number(c.track.lost_folded_fraction)
    << " of the triangles folded\n";
  s << "threads: " << plan.threads << "\n";
  s << "output: " << c.output.dir.string() << "\n";
  for (const auto& output : plan.outputs.outputs) s << output->describe(plan.block);
  s << "  " << summary_file_name(c.shard) << ", " << report_file_name(c.shard) << "\n";
  for (const std::string& w : plan.warnings) s << "warning: " << w << "\n";
  return s.str();
}

namespace {

class TrackRun {
 public:
  TrackRun(const TrackPlan& plan, const TrackHooks& hooks)
      : plan_(plan), hooks_(hooks), shared_written_(plan.outputs.outputs.size(), false) {}

  TrackResult run() {
    t0_ = Clock::now();
    result_.warnings = plan_.warnings;
    start();
    tbb::task_arena arena(plan_.threads);
    arena.execute([&] { track_all(); });
    finish();
    return std::move(result_);
  }

 private:
  void start() {
    const fs::path& out = plan_.config.output.dir;
    remove_stale_temporaries(out);
    const ShardOptions& shard = plan_.config.shard;
    for (const std::string& name : {summary_file_name(shard), report_file_name(shard)})
      remove_output_file(out / name);
    for (const auto& output : plan_.outputs.outputs) {
      for (const fs::path& dir : output->folders()) remove_stale_temporaries(dir);
      output->start(plan_.outputs);
    }
  }

  void track_all() {
    const TrackJobOptions& c = plan_.config;
    Tracker tracker = with_option_path(
        "", [&] { return Tracker(plan_.weld.mesh, c.track, plan_.outputs.config.massage); });
    const int total = int(plan_.order.size());
    for (size_t k = 0; k < plan_.order.size(); ++k) {
      if (hooks_.cancel && hooks_.cancel->load()) {
        result_.interrupted = true;
        break;
      }
      const int index = plan_.order[k];
      if (k > 0 && index < plan_.start_frame && plan_.order[k - 1] >= plan_.start_frame)
        tracker.reset();  // the backward pass starts at the template again
      track_frame(tracker, index);
      if (hooks_.progress)
        hooks_.progress(rows_.at(index), int(k) + 1, total, seconds_since(t0_));
    }
  }

  void track_frame(Tracker& tracker, int index) {
    const TrackJobOptions& c = plan_.config;
    const TriMesh raw = read_raw_frame(plan_.files[size_t(index)], index);
    const GltfWeld welded = weld_by_position(raw.V, raw.F);
    if (welded.mesh.num_triangles() == 0)
      throw InputError("frame " + std::to_string(index) + " ('" +
                       plan_.files[size_t(index)].string() + "'): no triangle of non-zero extent");
    const TrackFrame t = tracker.track(welded.mesh);

    const TriMesh& templ = plan_.layout.obj->mesh;
    SourceFrame input;
    input.mesh = TriMesh{unweld_frame(plan_.weld.map, t.registered, templ.V), templ.F};
    input.obj = plan_.layout.obj;
    const Positions V = unweld_frame(plan_.weld.map, t.V, templ.V);
    const Eigen::VectorXd before = shear_distortion(templ.V, input.mesh.V, templ.F);
    const Eigen::VectorXd after = shear_distortion(templ.V, V, templ.F);
    const FrameOutcome outcome{index, &input, &V, false, &before, &after, nullptr, nullptr};

    TrackRow row;
    row.frame = index;
    row.file = plan_.files[size_t(index)].filename().string();
    row.raw_vertices = welded.mesh.num_vertices();
    row.raw_triangles = welded.mesh.num_triangles();
    row.status = t.status;
    row.recovery = t.recovery;
    row.fit = t.fit;
    row.registration_fit = t.registration_fit;
    row.iterations = t.iterations;
    if (c.output.timings) {
      row.seconds_register = t.seconds_register;
      row.seconds_refine = t.seconds_refine;
    }
    if (t.status == TrackStatus::Lost)
      row.beyond = beyond_text(t.fit, c.track, plan_.weld.mesh.num_triangles());
    const std::string name = plan_.outputs.source->name(index);
    summaries_[index] = frame_summary(row, name, templ.num_vertices(), templ.num_triangles(),
                                      before, after);
    rows_[index] = std::move(row);

    const auto& outputs = plan_.outputs.outputs;
    for (size_t o = 0; o < outputs.size(); ++o) {
      const OutputFrame part = outputs[o]->encode(outcome);
      if (part.needs_shared && !shared_written_[o]) {
        for (const auto& [file, bytes] : outputs[o]->shared_files())
          write_file_atomic(c.output.dir / file, bytes);
        shared_written_[o] = true;
      }
      for (const auto& [file, bytes] : part.files) write_file_atomic(c.output.dir / file, bytes);
      outputs[o]->add_record_rows(record_rows_[index], part);
    }
  }

  void finish() {
    const TrackJobOptions& c = plan_.config;
    FinishedFrames done;
    std::vector<FrameSummary> summaries;
    for (const auto& [index, row] : rows_) {  // frame order
      result_.frames.push_back(row);
      done.frames.push_back(index);
      done.names.push_back(plan_.outputs.source->name(index));
      append_record_rows(done.record_rows, record_rows_[index]);
      summaries.push_back(summaries_.at(index));
      if (row.status == TrackStatus::Lost) {
        ++result_.lost;
        result_.warnings.push_back(
            frame_label(index, row.file, std::nullopt) +
            " lost (written as its best attempt): " + row.beyond);
      }
      result_.recovered += row.status == TrackStatus::Recovered;
    }
    done.summaries = &summaries;
    done.warnings = &result_.warnings;
    for (const auto& output : plan_.outputs.outputs)
      for (std::string& warning : output->finish(done).warnings)
        result_.warnings.push_back(std::move(warning));
    result_.seconds = seconds_since(t0_);
    json report = make_track_report(plan_, result_);
    if (c.shard.sharded()) report["shard"] = shard_section();
    write_file_atomic(c.output.dir / summary_file_name(c.shard),
                      format_track_summary_csv(result_.frames));
    write_file_atomic(c.output.dir / report_file_name(c.shard), report.dump(2) + "\n");
  }

  // What merge needs of a shard: its block, whether it completed it, and every frame's rows.
  json shard_section() const {
    json frames = json::array(), rows = json::array();
    for (int i : plan_.block)
      frames.push_back({{"frame", i}, {"file", plan_.outputs.source->name(i)}});
    for (const auto& [index, row] : rows_) {
      json entry = to_json(row);
      entry["summary"] = to_json(summaries_.at(index));
      entry["record_rows"] = record_rows_.count(index) ? json(record_rows_.at(index)) : json::object();
      rows.push_back(std::move(entry));
    }
    const ShardOptions& shard = plan_.config.shard;
    return {{"index", shard.index},
            {"count", shard.count},
            {"frames", frames},
            {"complete", !result_.interrupted && rows_.size() == plan_.block.size()},
            {"rows", rows}};
  }

  const TrackPlan& plan_;
  const TrackHooks& hooks_;
  Clock::time_point t0_;
  TrackResult result_;
  std::map<int, TrackRow> rows_;
  std::map<int, FrameSummary> summaries_;
  std::map<int, RecordRows> record_rows_;
  std::vector<bool> shared_written_;
};

}  // namespace

TrackResult run_track_job(const TrackPlan& plan, const TrackHooks& hooks) {
  const OutputLock lock = lock_output_folder(plan.config.output.dir);
  return TrackRun(plan, hooks).run();
}

std::string format_track_summary_csv(const std::vector<TrackRow>& rows) {
  CsvWriter csv({"frame", "file", "status", "recovery", "to_raw_mean", "to_raw_p99", "to_raw_max",
                 "from_raw_mean", "from_raw_p99", "from_raw_max", "folded", "shear_mean",
                 "shear_max", "registration_to_raw_mean", "registration_from_raw_mean",
                 "registration_from_raw_p99", "registration_folded", "raw_vertices",
                 "raw_triangles", "iterations", "seconds_register", "seconds_refine", "beyond"});
  for (const TrackRow& r : rows) {
    csv.cell(r.frame).cell(r.file).cell(name_of(r.status, kTrackStatusNames)).cell(r.recovery);
    csv.cell(r.fit.to_raw_mean).cell(r.fit.to_raw_p99).cell(r.fit.to_raw_max);
    csv.cell(r.fit.from_raw_mean).cell(r.fit.from_raw_p99).cell(r.fit.from_raw_max);
    csv.cell(r.fit.folded).cell(r.fit.shear_mean).cell(r.fit.shear_max);
    csv.cell(r.registration_fit.to_raw_mean).cell(r.registration_fit.from_raw_mean);
    csv.cell(r.registration_fit.from_raw_p99).cell(r.registration_fit.folded);
    csv.cell(r.raw_vertices).cell(r.raw_triangles).cell(r.iterations);
    csv.cell(r.seconds_register).cell(r.seconds_refine).cell(r.beyond);
    csv.end_row();
  }
  return csv.str();
}

namespace {

json fit_json(const FitFigures& f) {
  return {{"to_raw_mean", f.to_raw_mean},     {"to_raw_p99", f.to_raw_p99},
          {"to_raw_max", f.to_raw_max},       {"from_raw_mean", f.from_raw_mean},
          {"from_raw_p99", f.from_raw_p99},   {"from_raw_max", f.from_raw_max},
          {"folded", f.folded},               {"shear_mean", f.shear_mean},
          {"shear_max", f.shear_max}};
}

FitFigures fit_from_json(const json& j) {
  FitFigures f;
  f.to_raw_mean = j.at("to_raw_mean").get<double>();
  f.to_raw_p99 = j.at("to_raw_p99").get<double>();
  f.to_raw_max = j.at("to_raw_max").get<double>();
  f.from_raw_mean = j.at("from_raw_mean").get<double>();
  f.from_raw_p99 = j.at("from_raw_p99").get<double>();
  f.from_raw_max = j.at("from_raw_max").get<double>();
  f.folded = j.at("folded").get<int>();
  f.shear_mean = j.at("shear_mean").get<double>();
  f.shear_max = j.at("shear_max").get<double>();
  return f;
}

}  // namespace

json to_json(const TrackRow& r) {
  return {{"frame", r.frame},
          {"file", r.file},
          {"status", std::string(name_of(r.status, kTrackStatusNames))},
          {"recovery", r.recovery},
          {"beyond", r.beyond},
          {"fit", fit_json(r.fit)},
          {"registration_fit", fit_json(r.registration_fit)},
          {"raw_vertices", r.raw_vertices},
          {"raw_triangles", r.raw_triangles},
          {"iterations", r.iterations},
          {"seconds_register", r.seconds_register},
          {"seconds_refine", r.seconds_refine}};
}

TrackRow track_row_from_json(const json& j) {
  try {
    TrackRow r;
    r.frame = j.at("frame").get<int>();
    r.file = j.at("file").get<std::string>();
    const std::string status = j.at("status").get<std::string>();
    bool known = false;
    for (const auto& [name, value] : kTrackStatusNames)
      if (status == name) r.status = value, known = true;
    if (!known) throw InputError("status: unknown value '" + status + "'");
    r.recovery = j.at("recovery").get<std::string>();
    r.beyond = j.at("beyond").get<std::string>();
    r.fit = fit_from_json(j.at("fit"));
    r.registration_fit = fit_from_json(j.at("registration_fit"));
    r.raw_vertices = j.at("raw_vertices").get<int>();
    r.raw_triangles = j.at("raw_triangles").get<int>();
    r.iterations = j.at("iterations").get<int>();
    r.seconds_register = j.at("seconds_register").get<double>();
    r.seconds_refine = j.at("seconds_refine").get<double>();
    return r;
  } catch (const json::exception& e) {
    throw InputError(std::string("a frame's row: ") + e.what());
  }
}

json make_track_report(const TrackPlan& plan, const TrackResult& result) {
  const TrackJobOptions& c = plan.config;
  json r;
  r["job"] = "track";
  r["versions"] = version_info();
  r["config"] = to_json(c);
  r["input"] = plan.outputs.source->report();
  r["template"] = {{"source", plan.template_source},
                   {"frame", plan.template_frame >= 0 ? json(plan.template_frame) : json(nullptr)},
                   {"vertices", plan.layout.obj->mesh.num_vertices()},
                   {"welded_vertices", plan.weld.mesh.num_vertices()},
                   {"triangles", plan.weld.mesh.num_triangles()},
                   {"mean_edge", mean_edge_length(plan.weld.mesh)}};
  r["units"] = "distances in mean edge lengths of the template";
  r["tolerances"] = {{"lost_distance", c.track.lost_distance},
                     {"lost_distance_p99", c.track.lost_distance_p99},
                     {"lost_folded_fraction", c.track.lost_folded_fraction}};
  json frames = json::array(), lost = json::array();
  double to_raw = 0, from_raw = 0;
  for (const TrackRow& row : result.frames) {
    frames.push_back({{"frame", row.frame},
                      {"file", row.file},
                      {"status", std::string(name_of(row.status, kTrackStatusNames))},
                      {"recovery", row.recovery},
                      {"to_raw_mean", row.fit.to_raw_mean},
                      {"from_raw_mean", row.fit.from_raw_mean},
                      {"from_raw_p99", row.fit.from_raw_p99},
                      {"folded", row.fit.folded}});
    if (row.status == TrackStatus::Lost)
      lost.push_back({{"frame", row.frame}, {"file", row.file}, {"beyond", row.beyond}});
    to_raw += row.fit.to_raw_mean;
    from_raw += row.fit.from_raw_mean;
  }
  const double n = std::max<size_t>(result.frames.size(), 1);
  r["summary"] = {{"frames", result.frames.size()},
                  {"lost", result.lost},
                  {"recovered", result.recovered},
                  {"interrupted", result.interrupted},
                  {"to_raw_mean", to_raw / n},
                  {"from_raw_mean", from_raw / n}};
  r["lost"] = lost;
  r["frames"] = frames;
  json outputs = json::object();
  for (const auto& output : plan.outputs.outputs) outputs.update(output->report());
  outputs["summary"] = "summary.csv";
  r["outputs"] = outputs;
  r["warnings"] = result.warnings;
  if (c.output.timings) r["run"] = {{"seconds", result.seconds}, {"threads", plan.threads}};
  return r;
}

}  // namespace sm
