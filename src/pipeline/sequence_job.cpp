#include "pipeline/sequence_job.hpp"

#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <set>
#include <sstream>

#include "geometry/bvh.hpp"
#include "io/atomic_file.hpp"
#include "io/mesh_file.hpp"
#include "massage/reference.hpp"
#include "mesh/errors.hpp"
#include "mesh/mesh_check.hpp"
#include "pipeline/frame_extras.hpp"
#include "pipeline/report.hpp"

namespace sm {
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string frame_label(const SequencePlan& plan, int index) {
  return plan.source->label(index);
}

// Why `frame` cannot be massaged with the template's connectivity, or "" if it can.
std::string connectivity_mismatch(const SequencePlan& plan, int index, const TriMesh& frame) {
  const TriMesh& t = plan.templ;
  const std::string who = frame_label(plan, index);
  const std::string like = ", but the template, " + plan.template_source + ", has ";
  if (frame.num_vertices() != t.num_vertices())
    return who + ": " + std::to_string(frame.num_vertices()) + " vertices" + like +
           std::to_string(t.num_vertices());
  if (frame.num_triangles() != t.num_triangles())
    return who + ": " + std::to_string(frame.num_triangles()) + " triangles" + like +
           std::to_string(t.num_triangles());
  for (int k = 0; k < t.num_triangles(); ++k) {
    if (frame.F.row(k) == t.F.row(k)) continue;
    auto corners = [](const Triangles& F, int k) {
      return std::to_string(F(k, 0) + 1) + " " + std::to_string(F(k, 1) + 1) + " " +
             std::to_string(F(k, 2) + 1);
    };
    return who + ": faces differ from the template's, " + plan.template_source + ": triangle " +
           std::to_string(k + 1) + " has vertices " + corners(frame.F, k) + ", the template's " +
           corners(t.F, k) + " (1-based)";
  }
  return "";
}

// Reads every selected frame (a few at a time) and throws for the first one, in frame order,
// whose connectivity differs from the template's.
void check_frames(const SequencePlan& plan, tbb::task_arena& arena) {
  const FrameSource& source = *plan.source;
  std::vector<std::string> problems(plan.selected.size());
  arena.execute([&] {
    tbb::parallel_for(size_t{0}, plan.selected.size(), [&](size_t k) {
      const int index = plan.selected[k];
      if (index == plan.template_frame) return;
      problems[k] =
          connectivity_mismatch(plan, index, source.decode(index, source.fetch(index)).mesh);
    });
  });
  for (const std::string& problem : problems)
    if (!problem.empty()) throw InputError(problem);
}

// distortion/<frame name>.csv
fs::path distortion_csv_name(const SequencePlan& plan, int index) {
  return fs::path(plan.source->name(index)).replace_extension(".csv");
}

// Refuses an output file that is one of the inputs.
void check_outputs(const SequencePlan& plan) {
  const JobConfig& c = plan.config;
  std::set<fs::path> inputs;
  auto canonical = [](const fs::path& p) {
    std::error_code ec;  // a path that cannot be resolved is compared as written
    const fs::path resolved = fs::weakly_canonical(p, ec);
    return (ec ? fs::absolute(p) : resolved).lexically_normal();
  };
  std::vector<int> read = plan.selected;
  if (plan.template_frame >= 0) read.push_back(plan.template_frame);
  for (const fs::path& file : plan.source->files(read)) inputs.insert(canonical(file));
  if (!c.templ.mesh.empty()) inputs.insert(canonical(c.templ.mesh));
  std::vector<fs::path> outputs = plan.sink->files(plan.selected);
  outputs.push_back(c.output.dir / "summary.csv");
  outputs.push_back(c.output.dir / "report.json");
  if (c.output.per_triangle_csv)
    for (int index : plan.selected)
      outputs.push_back(c.output.dir / "distortion" / distortion_csv_name(plan, index));
  for (fs::path& file : plan.extras->files(plan.selected)) outputs.push_back(std::move(file));
  for (const fs::path& out : outputs)
    if (inputs.count(canonical(out)))
      throw ConfigError("output.dir: writing " + out.string() +
                        " would overwrite an input file; choose another output folder");
}

std::vector<int> select_frames(const FrameRange& range, int count) {
  if (range.start >= count)
    throw ConfigError("input.range.start: " + std::to_string(range.start) +
                      " is beyond the last frame (the sequence has " + std::to_string(count) +
                      " frames, 0 to " + std::to_string(count - 1) + ")");
  const int stop = range.stop ? std::min(*range.stop, count) : count;
  std::vector<int> selected;
  for (int i = range.start; i < stop; i += range.step) selected.push_back(i);
  if (selected.empty())
    throw ConfigError("input.range: selects no frames (" + format_frame_range(range) + ")");
  return selected;
}

// One frame in flight through the pipeline.
struct Work {
  int index = 0;
  std::string bytes;  // what the source fetched (the input file as read, if any)
  std::string out;    // the output frame, encoded by the sink
  std::string csv;    // per-triangle distortion (if asked)
  ExtraFrame extras;  // colored, checker and iterations outputs (if asked)
  FrameSummary summary;
};

void process_frame(const SequencePlan& plan, const ExtrasRun& extras, Work& w) {
  const auto t0 = Clock::now();
  const JobConfig& c = plan.config;
  const SourceFrame file = plan.source->decode(w.index, std::move(w.bytes));
  if (std::string problem = connectivity_mismatch(plan, w.index, file.mesh); !problem.empty())
    throw InputError(problem);

  FrameSummary& s = w.summary;
  s.frame = w.index;
  s.file = plan.source->name(w.index);
  s.time = plan.source->time(w.index);
  s.warnings = file.warnings;
  s.vertices = file.mesh.num_vertices();
  s.triangles = file.mesh.num_triangles();
  const Triangles& F = plan.templ.F;
  const Eigen::VectorXd before = shear_distortion(plan.templ.V, file.mesh.V, F);

  Positions V = file.mesh.V;
  bool unchanged = false;
  std::optional<Reference> reference;
  MassageResult result;
  if (w.index == plan.template_frame && !c.templ.optimize) {
    s.status = FrameStatus::Template;
    unchanged = true;
  } else {
    const std::string name = frame_label(plan, w.index);
    reference.emplace(file.mesh, c.massage.samples, name.c_str(), plan.massager->shared_topology(),
                      &plan.massager->template_bvh());
    result = plan.massager->run(file.mesh.V, *reference);
    s.iterations = static_cast<int>(result.iterations.size());
    if (!result.ok) {
      s.status = FrameStatus::Failed;
      s.failure = result.failure;
      unchanged = true;
    } else {
      s.status = FrameStatus::Optimized;
      s.folded_triangles = result.folded_triangles;
      V = result.V;
      const TriMesh output{V, F};
      const Topology& topology = plan.massager->topology();
      s.out_to_in =
          one_sided_distance(output, reference->bvh(), {}, &reference->planes(), &topology);
      TriangleBvh output_bvh = reference->bvh();  // same triangles: refit, no rebuild
      output_bvh.refit(V);
      const TrianglePlanes output_planes(V, F, &topology);
      s.in_to_out = one_sided_distance(file.mesh, output_bvh, {}, &output_planes, &topology);
    }
  }
  w.out = plan.sink->encode(file, V, unchanged);
  const Eigen::VectorXd after = unchanged ? before : shear_distortion(plan.templ.V, V, F);
  s.shear_before = summarize_distortion(before);
  s.shear_after = summarize_distortion(after);
  if (c.output.per_triangle_csv) w.csv = format_distortion_csv(before, after);
  if (plan.extras->any())
    w.extras = extras.encode({w.index, &file, &V, &before, &after, reference ? &result : nullptr,
                              reference ? &*reference : nullptr});

  if (const std::optional<Positions> clean = plan.source->ground_truth(w.index)) {
    const double unit = mean_edge_length(plan.templ);
    const Eigen::VectorXd e_in = (file.mesh.V - *clean).rowwise().norm() / unit;
    const Eigen::VectorXd e_out = (V - *clean).rowwise().norm() / unit;
    s.ground_truth = GroundTruthError{e_in.mean(), e_in.maxCoeff(), e_out.mean(), e_out.maxCoeff()};
  }
  s.seconds = seconds_since(t0);
}

}  // namespace

const char* status_name(FrameStatus status) {
  switch (status) {
    case FrameStatus::Optimized:
      return "optimized";
    case FrameStatus::Template:
      return "template";
    case FrameStatus::Failed:
      return "failed";
  }
  return "";
}

SequencePlan plan_sequence_job(const JobConfig& config) {
  SequencePlan plan;
  plan.config = config;
  const JobConfig& c = plan.config;
  plan.threads = c.threads > 0 ? c.threads : std::max(1, tbb::info::default_concurrency());
  plan.frames_in_flight = c.frames_in_flight > 0 ? c.frames_in_flight : 2 * plan.threads;

  plan.source = make_frame_source(c);
  plan.sink = make_frame_sink(c, plan.source);
  plan.extras = std::make_shared<const FrameExtras>(c, plan.source);
  const int count = plan.source->size();
  plan.selected = select_frames(c.input.range, count);
  for (std::string& warning : plan.extras->check(plan.selected))
    plan.warnings.push_back(std::move(warning));

  if (c.templ.mesh.empty()) {
    if (c.templ.frame >= count)
      throw ConfigError("template.frame: " + std::to_string(c.templ.frame) +
                        " is out of range (the sequence has " + std::to_string(count) +
                        " frames, 0 to " + std::to_string(count - 1) + ")");
    plan.template_frame = c.templ.frame;
    plan.template_source = frame_label(plan, plan.template_frame);
    plan.templ = plan.source->template_frame(plan.template_frame);
  } else {
    plan.template_source = c.templ.mesh.filename().string();
    plan.templ = read_mesh(c.templ.mesh);
  }
  plan.massager =
      std::make_shared<const Massager>(plan.templ, c.massage, plan.template_source.c_str());

  const MeshReport report = check_mesh(plan.templ, plan.massager->topology());
  if (!report.ok_for_optimization())
    plan.warnings.push_back("template (" + plan.template_source + "): " + report.describe());
  if (const int fallback = plan.massager->weights().fallback_vertices; fallback > 0)
    plan.warnings.push_back("template (" + plan.template_source + "): " + std::to_string(fallback) +
                            " vertices with degenerate corners use uniform weights");
  if (c.input.range.stop && *c.input.range.stop > count)
    plan.warnings.push_back("input.range.stop " + std::to_string(*c.input.range.stop) +
                            " is past the last frame; the sequence has " + std::to_string(count));

  if (plan.source->needs_check()) {
    tbb::task_arena arena(plan.threads);
    check_frames(plan, arena);
  }
  check_outputs(plan);
  return plan;
}

std::string describe_plan(const SequencePlan& plan) {
  const JobConfig& c = plan.config;
  std::ostringstream s;
  s << "job: sequence\n";
  s << "input: " << plan.source->describe() << "\n";
  s << "frames: " << plan.selected.size() << " selected (" << format_frame_range(c.input.range)
    << "): " << plan.source->name(plan.selected.front());
  if (plan.selected.size() > 1) s << " ... " << plan.source->name(plan.selected.back());
  s << "\n";
  s << "template: " << plan.template_source << ", " << plan.templ.num_vertices() << " vertices, "
    << plan.templ.num_triangles() << " triangles";
  if (plan.template_frame >= 0)
    s << (c.templ.optimize ? "; optimized like the others" : "; written unchanged");
  s << "\n";
  const nlohmann::json m = to_json(c)["massage"];
  const std::string mu = m["mu"].is_string() ? m["mu"].get<std::string>() : m["mu"].dump();
  s << "massage: " << m["weights"].get<std::string>() << " weights, " << m["iterations"]
    << " iterations, mu " << mu << ", samples " << m["samples"].get<std::string>() << ", solver "
    << m["solver"].get<std::string>() << "\n";
  s << "threads: " << plan.threads << ", frames in flight: " << plan.frames_in_flight << "\n";
  s << "output: " << c.output.dir.string() << "\n";
  s << plan.sink->describe(plan.selected);
  if (c.output.per_triangle_csv)
    s << "  distortion/<name>.csv (" << plan.selected.size() << " files)\n";
  s << plan.extras->describe(plan.selected);
  s << "  summary.csv, report.json\n";
  for (const std::string& w : plan.warnings) s << "warning: " << w << "\n";
  return s.str();
}

SequenceResult run_sequence_job(const SequencePlan& plan, const RunHooks& hooks) {
  const auto t0 = Clock::now();
  const JobConfig& c = plan.config;
  const fs::path& out = c.output.dir;
  SequenceResult result;
  result.warnings = plan.warnings;
  plan.source->prepare();
  for (const fs::path& dir : {out, out / "frames", out / "distortion"})
    remove_stale_temporaries(dir);
  for (const fs::path& dir : plan.extras->folders()) remove_stale_temporaries(dir);
  const std::unique_ptr<FrameWriter> writer = plan.sink->start();
  const std::unique_ptr<ExtrasRun> extras = plan.extras->start(plan);

  const size_t total = plan.selected.size();
  size_t next = 0;
  // The first exception of a stage stops the input and is rethrown once the frames in flight have
  // drained, unwritten: thrown through parallel_pipeline, it would leak them (oneTBB does not
  // destroy the tokens of a cancelled pipeline).
  std::exception_ptr error;
  std::mutex error_mutex;
  std::atomic<bool> failed{false};
  const auto record_error = [&] {
    const std::lock_guard<std::mutex> lock(error_mutex);
    if (!error) error = std::current_exception();
    failed = true;
  };
  // A stage that runs only while nothing failed and records its exception (what the last stage
  // returns is dropped).
  const auto guarded = [&](auto stage) {
    return [&, stage](std::shared_ptr<Work> w) {
      if (!failed) try {
          w = stage(std::move(w));
        } catch (...) {
          record_error();
        }
      return w;
    };
  };
  tbb::task_arena arena(plan.threads);
  arena.execute([&] {
    tbb::parallel_pipeline(
        static_cast<size_t>(plan.frames_in_flight),
        tbb::make_filter<void, std::shared_ptr<Work>>(
            tbb::filter_mode::serial_in_order,
            [&](tbb::flow_control& fc) -> std::shared_ptr<Work> {
              if (next < total && hooks.cancel && hooks.cancel->load()) result.interrupted = true;
              if (next >= total || result.interrupted || failed) {
                fc.stop();
                return nullptr;
              }
              auto w = std::make_shared<Work>();
              w->index = plan.selected[next++];
              return guarded([&](std::shared_ptr<Work> w) {
                w->bytes = plan.source->fetch(w->index);
                return w;
              })(std::move(w));
            }) &
            tbb::make_filter<std::shared_ptr<Work>, std::shared_ptr<Work>>(
                tbb::filter_mode::parallel, guarded([&](std::shared_ptr<Work> w) {
                  process_frame(plan, *extras, *w);
                  return w;
                })) &
            tbb::make_filter<std::shared_ptr<Work>, void>(
                tbb::filter_mode::serial_in_order, guarded([&](std::shared_ptr<Work> w) {
                  writer->write(w->index, w->out);
                  if (c.output.per_triangle_csv)
                    write_file_atomic(out / "distortion" / distortion_csv_name(plan, w->index),
                                      w->csv);
                  extras->write(w->extras);
                  const FrameSummary& s = w->summary;
                  const std::string who = frame_label(plan, w->index);
                  if (!w->extras.warning.empty())
                    result.warnings.push_back(who + ": " + w->extras.warning);
                  for (const std::string& warning : s.warnings)
                    result.warnings.push_back(who + ": " + warning);
                  if (s.status == FrameStatus::Failed) {
                    ++result.failed;
                    result.warnings.push_back(who + " failed, written unchanged: " + s.failure);
                  }
                  if (s.folded_triangles > 0)
                    result.warnings.push_back(who + ": " + std::to_string(s.folded_triangles) +
                                              " triangles folded over the input surface");
                  result.frames.push_back(std::move(w->summary));
                  if (hooks.progress)
                    hooks.progress(result.frames.back(), static_cast<int>(result.frames.size()),
                                   static_cast<int>(total), seconds_since(t0));
                  return w;
                })));
  });
  if (error) std::rethrow_exception(error);
  for (std::string& warning : writer->finish()) result.warnings.push_back(std::move(warning));
  result.extra_outputs = extras->finish();
  result.seconds = seconds_since(t0);
  write_file_atomic(out / "summary.csv", format_summary_csv(result.frames, c.output.timings));
  write_file_atomic(out / "report.json", make_report(plan, result).dump(2) + "\n");
  return result;
}

}  // namespace sm
