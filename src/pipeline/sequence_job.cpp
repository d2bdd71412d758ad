#include "pipeline/sequence_job.hpp"

#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <exception>
#include <mutex>
#include <set>
#include <sstream>

#include "geometry/bvh.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/mesh_file.hpp"
#include "io/sha256.hpp"
#include "massage/reference.hpp"
#include "mesh/errors.hpp"
#include "mesh/mesh_check.hpp"
#include "mesh/timing.hpp"
#include "pipeline/fold_check.hpp"
#include "pipeline/frame_output.hpp"
#include "pipeline/frame_record.hpp"
#include "pipeline/report.hpp"
#include "pipeline/run_text.hpp"
#include "pipeline/shard.hpp"

namespace sm {
namespace fs = std::filesystem;

namespace {

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
  std::vector<std::string> problems(plan.run_frames.size());
  arena.execute([&] {
    tbb::parallel_for(size_t{0}, plan.run_frames.size(), [&](size_t k) {
      const int index = plan.run_frames[k];
      if (index == plan.template_frame) return;
      problems[k] =
          connectivity_mismatch(plan, index, source.decode(index, source.fetch(index)).mesh);
    });
  });
  for (const std::string& problem : problems)
    if (!problem.empty()) throw InputError(problem);
}

// Refuses an output file that is one of the inputs.
void check_outputs(const SequencePlan& plan) {
  const SequenceJobOptions& c = plan.config;
  std::set<fs::path> inputs;
  auto canonical = [](const fs::path& p) {
    std::error_code ec;  // a path that cannot be resolved is compared as written
    const fs::path resolved = fs::weakly_canonical(p, ec);
    return (ec ? fs::absolute(p) : resolved).lexically_normal();
  };
  std::vector<int> read = plan.run_frames;
  if (plan.template_frame >= 0) read.push_back(plan.template_frame);
  for (const fs::path& file : plan.source->files(read)) inputs.insert(canonical(file));
  if (!c.templ.mesh.empty()) inputs.insert(canonical(c.templ.mesh));
  std::vector<fs::path> outputs;
  for (const auto& output : plan.outputs)
    for (fs::path& file : output->files(plan.run_frames)) outputs.push_back(std::move(file));
  outputs.push_back(c.output.dir / summary_file_name(c.shard));
  outputs.push_back(c.output.dir / report_file_name(c.shard));
  for (int index : plan.run_frames)
    outputs.push_back(record_file(c.output.dir, plan.source->name(index)));
  for (const fs::path& out : outputs)
    if (inputs.count(canonical(out)))
      throw ConfigError("output.dir: writing " + out.string() +
                        " would overwrite an input file; choose another output folder");
}

// One frame in flight through the pipeline.
struct Work {
  int index = 0;
  std::string bytes;  // what the source fetched (the input file as read, if any)
  std::vector<OutputFrame> outputs;  // each output's part, as plan.outputs
  bool needs_shared = false;  // an output's shared files must be in place before the record
  FrameSummary summary;
  bool has_output = true;  // false: failed, and output.on_failure is "skip"
  FrameRecord record;      // the record to write, or the one resumed from
  bool resumed = false;    // the record is current: nothing to compute or write
  std::string redo;        // resuming: why the frame is processed again
};

// Why the frame is processed again although resuming ("" if its record is current).
std::string resume_problem(const SequencePlan& plan, int index, const std::string& input_hash,
                           FrameRecord& record) {
  std::string problem;
  std::optional<FrameRecord> found =
      read_frame_record(record_file(plan.config.output.dir, plan.source->name(index)), &problem);
  if (!found) return problem.rfind("unreadable", 0) == 0 ? "an unreadable record" : problem;
  if (found->config_hash != plan.config_hash) return "the config changed";
  if (found->template_hash != plan.template_hash) return "the template changed";
  if (found->input_hash != input_hash) return "the input changed";
  if (found->summary.frame != index || found->summary.file != plan.source->name(index))
    return "the record is another frame's";
  if (!check_recorded_outputs(*found, plan.config.output.dir, true).empty())
    return "an output is missing or changed";
  record = std::move(*found);
  return "";
}

RecordedOutput recorded(const fs::path& path, const std::string& bytes) {
  return {path.generic_string(), bytes.size(), sha256_hex(bytes)};
}

// Non-finite positions, then folds: the reason the optimized positions `V` of a frame read as
// `input` fail the checks, or "".
std::string check_output(const SequencePlan& plan, const TriMesh& input, const Positions& V,
                         FrameSummary& s) {
  if (std::string bad = non_finite_positions(V); !bad.empty())
    return "non-finite positions: output " + bad;
  const FoldCount folds =
      count_folded_triangles(plan.templ.F, plan.massager->topology(), input.V, V);
  s.folded_triangles = folds.folded;
  const FrameCheckOptions& checks = plan.config.checks;
  const int m = static_cast<int>(plan.templ.F.rows());
  std::string over;
  if (checks.max_folded_triangles && folds.folded > *checks.max_folded_triangles)
    over = "checks.max_folded_triangles = " + std::to_string(*checks.max_folded_triangles);
  else if (checks.max_folded_fraction && folds.folded > *checks.max_folded_fraction * m)
    over = "checks.max_folded_fraction = " + format_number(*checks.max_folded_fraction) + " of " +
           std::to_string(m) + " triangles";
  if (!over.empty())
    return "folded triangles: " + std::to_string(folds.folded) +
           " output triangles are folded over (normal opposed to the input frame's), more than " +
           over;
  return "";
}

void write_record(const SequencePlan& plan, const Work& w) {
  write_file_atomic(record_file(plan.config.output.dir, plan.source->name(w.index)),
                    to_json(w.record).dump(1) + "\n");
}

bool wants_shear_per_iteration(const SequencePlan& plan, int index) {
  for (const auto& output : plan.outputs)
    if (output->wants_shear_per_iteration(index)) return true;
  return false;
}

void process_frame(const SequencePlan& plan, Work& w) {
  const auto t0 = Clock::now();
  const SequenceJobOptions& c = plan.config;
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
  std::vector<std::optional<DistortionSummary>> shear_per_iteration;  // iterations.csv
  if (w.index == plan.template_frame && !c.templ.optimize) {
    s.status = FrameStatus::Template;
    unchanged = true;
  } else if (std::string bad = non_finite_positions(file.mesh.V); !bad.empty()) {
    s.status = FrameStatus::Failed;  // only a source that does not check its frames gets here
    s.failure = "non-finite positions: input " + bad;
    unchanged = true;
  } else {
    const std::string name = frame_label(plan, w.index);
    reference.emplace(file.mesh, c.massage.samples, name.c_str(), plan.massager->shared_topology(),
                      &plan.massager->template_bvh());
    result = wants_shear_per_iteration(plan, w.index)
                 ? plan.massager->run(file.mesh.V, *reference,
                                      shear_observer(plan.templ, shear_per_iteration))
                 : plan.massager->run(file.mesh.V, *reference);
    s.iterations = static_cast<int>(result.iterations.size());
    if (!result.ok) {
      s.status = FrameStatus::Failed;
      s.failure = "optimizer failed: " + result.failure;
      unchanged = true;
    } else if (std::string bad = check_output(plan, file.mesh, result.V, s); !bad.empty()) {
      s.status = FrameStatus::Failed;
      s.failure = std::move(bad);
      unchanged = true;
    } else {
      s.status = FrameStatus::Optimized;
      V = result.V;
      const FrameDistances d =
          plan.distance_meter->measure(file.mesh, reference->bvh(), reference->planes(), V);
      s.out_to_in = d.moved_to_original;
      s.in_to_out = d.original_to_moved;
    }
  }
  w.has_output = !(s.status == FrameStatus::Failed && c.output.on_failure == OnFailure::Skip);
  const Eigen::VectorXd after = unchanged ? before : shear_distortion(plan.templ.V, V, F);
  s.shear_before = summarize_distortion(before);
  s.shear_after = summarize_distortion(after);
  const FrameOutcome outcome{w.index,  &file,  &V, unchanged, &before, &after,
                             reference ? &result : nullptr, &shear_per_iteration};
  for (const auto& output : plan.outputs) w.outputs.push_back(output->encode(outcome));

  if (const std::optional<Positions>& clean = file.ground_truth) {
    const double unit = mean_edge_length(plan.templ);
    const Eigen::VectorXd e_in = (file.mesh.V - *clean).rowwise().norm() / unit;
    const Eigen::VectorXd e_out = (V - *clean).rowwise().norm() / unit;
    s.ground_truth = GroundTruthError{e_in.mean(), e_in.maxCoeff(), e_out.mean(), e_out.maxCoeff()};
  }
  s.seconds = c.output.timings ? seconds_since(t0) : 0.0;  // 0: records reproduce byte for byte

  FrameRecord& r = w.record;
  r.config_hash = plan.config_hash;
  r.template_hash = plan.template_hash;
  r.outputs.clear();
  r.iterations_csv.clear();
  for (const OutputFrame& part : w.outputs) {
    if (w.has_output)
      for (const auto& [path, bytes] : part.files) r.outputs.push_back(recorded(path, bytes));
    w.needs_shared = w.needs_shared || (w.has_output && part.needs_shared);
    r.iterations_csv += part.record_rows;
  }
  r.summary = s;
}

// A frame's files, written in the parallel stage: no other frame writes them, so the frames'
// writes (and their fsyncs) overlap the others' work instead of queueing in the serial stage. The
// order within the frame is kept: the old record is removed first, then the outputs are written
// (or, for a frame without output, removed), then the record, which comes back last. A frame
// whose files need an output's shared files (the checker texture, written in frame order with the
// first frame that needs it) has its record written in the serial stage, after them
// (write_record). Frees the encoded bytes.
void write_frame_files(const SequencePlan& plan, Work& w) {
  const fs::path& out = plan.config.output.dir;
  std::error_code ec;
  fs::remove(record_file(out, plan.source->name(w.index)), ec);
  for (OutputFrame& part : w.outputs) {
    for (const auto& [file, bytes] : part.files) {
      if (w.has_output)
        write_file_atomic(out / file, bytes);
      else
        fs::remove(out / file, ec);
    }
    part.files.clear();
    part.files.shrink_to_fit();
  }
  if (!w.needs_shared) write_record(plan, w);
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

SequencePlan plan_sequence_job(const SequenceJobOptions& config) {
  SequencePlan plan;
  plan.config = config;
  const SequenceJobOptions& c = plan.config;
  plan.threads = c.threads > 0 ? c.threads : std::max(1, tbb::info::default_concurrency());
  plan.frames_in_flight = c.frames_in_flight > 0 ? c.frames_in_flight : 2 * plan.threads;

  std::shared_ptr<const GltfSequence> gltf;
  plan.source = make_frame_source(c, &gltf);
  plan.outputs = make_frame_outputs({c, plan.source, [gltf] { return gltf; }});
  const int count = plan.source->size();
  plan.selected = select_frames(c.input.range, count);
  plan.run_frames = shard_frames(plan.selected, c.shard);
  for (const auto& output : plan.outputs)
    for (std::string& warning : output->check(plan.selected))
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
  plan.distance_meter = std::make_shared<const DistanceMeter>(
      plan.templ.F, plan.templ.num_vertices(), plan.massager->shared_topology(), c.measures);
  plan.config_hash = frame_config_hash(c);
  plan.template_hash = template_hash(plan.templ);

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
  const SequenceJobOptions& c = plan.config;
  std::ostringstream s;
  s << "job: sequence\n";
  s << "input: " << plan.source->describe() << "\n";
  s << "frames: " << plan.selected.size() << " selected (" << format_frame_range(c.input.range)
    << "): " << plan.source->name(plan.selected.front());
  if (plan.selected.size() > 1) s << " ... " << plan.source->name(plan.selected.back());
  s << "\n";
  if (c.shard.sharded()) {
    s << shard_label(c.shard) << ": " << plan.run_frames.size() << " frames";
    if (!plan.run_frames.empty()) {
      s << ": " << plan.source->name(plan.run_frames.front());
      if (plan.run_frames.size() > 1) s << " ... " << plan.source->name(plan.run_frames.back());
    }
    s << "\n";
  }
  if (c.resume) {
    int current = 0;  // records of this config and template (inputs and outputs checked at run)
    for (int index : plan.run_frames) {
      const auto r = read_frame_record(record_file(c.output.dir, plan.source->name(index)));
      current += r && r->config_hash == plan.config_hash && r->template_hash == plan.template_hash;
    }
    s << "resume: " << current << " of " << plan.run_frames.size()
      << " frames have a record of this config and template (skipped if their input and "
         "outputs are unchanged)\n";
  }
  s << "template: " << plan.template_source << ", " << plan.templ.num_vertices() << " vertices, "
    << plan.templ.num_triangles() << " triangles";
  if (plan.template_frame >= 0)
    s << (c.templ.optimize ? "; optimized like the others" : "; written unchanged");
  s << "\n";
  s << "massage: " << massage_text(c.massage) << "\n";
  if (c.measures.adaptive)
    s << "distances (summary.csv): adaptive, at the vertices and centroids, then"
      << (c.measures.sample_edges ? " along the edges" : "")
      << (c.measures.sample_edges && c.measures.sample_faces ? " and" : "")
      << (c.measures.sample_faces ? " inside" : "") << " the triangles above "
      << format_number(c.measures.refine_above) << " of the maximum, samples every "
      << format_number(c.measures.spacing) << " mean edge lengths\n";
  else
    s << "distances (summary.csv): samples every " << format_number(c.measures.spacing)
      << " mean edge lengths, at the vertices"
      << (c.measures.sample_edges ? ", along the edges" : "")
      << (c.measures.sample_faces ? ", inside the triangles" : "") << "\n";
  s << "threads: " << plan.threads << ", frames in flight: " << plan.frames_in_flight << "\n";
  s << "output: " << c.output.dir.string() << "\n";
  for (const auto& output : plan.outputs) s << output->describe(plan.run_frames);
  s << "  records/<name>.json (" << plan.run_frames.size() << " files)\n";
  s << "  " << summary_file_name(c.shard) << ", " << report_file_name(c.shard) << "\n";
  for (const std::string& w : plan.warnings) s << "warning: " << w << "\n";
  return s.str();
}

SequenceResult run_sequence_job(const SequencePlan& plan, const RunHooks& hooks) {
  const auto t0 = Clock::now();
  const SequenceJobOptions& c = plan.config;
  const fs::path& out = c.output.dir;
  SequenceResult result;
  result.warnings = plan.warnings;
  for (const char* dir : {".", "records", "input", "ground_truth"})
    remove_stale_temporaries(out / dir);
  // The summary and report of an earlier run would no longer describe the files: they are written
  // again when this run ends (or stops at an interruption), and are absent until then.
  for (const std::string& name : {summary_file_name(c.shard), report_file_name(c.shard)}) {
    std::error_code ec;
    fs::remove(out / name, ec);
  }
  plan.source->prepare();
  for (const auto& output : plan.outputs) {
    for (const fs::path& dir : output->folders()) remove_stale_temporaries(dir);
    output->start(plan);
  }
  FinishedFrames done;                                    // what the outputs finish from
  std::vector<bool> shared_written(plan.outputs.size());  // their shared files, this run
  const auto keep = [&](const Work& w) {
    if (w.has_output) {
      done.frames.push_back(w.index);
      done.names.push_back(w.summary.file);
    }
    done.record_rows += w.record.iterations_csv;
  };

  const size_t total = plan.run_frames.size();
  size_t next = 0;
  // The first exception of a stage stops the input and is rethrown once the frames in flight have
  // drained (those that finish after it are not written; one finishing at the same moment may
  // have written its complete files): thrown through parallel_pipeline, it would leak them (oneTBB
  // does not destroy the tokens of a cancelled pipeline).
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
              w->index = plan.run_frames[next++];
              return guarded([&](std::shared_ptr<Work> w) {
                w->bytes = plan.source->fetch(w->index);
                return w;
              })(std::move(w));
            }) &
            tbb::make_filter<std::shared_ptr<Work>, std::shared_ptr<Work>>(
                tbb::filter_mode::parallel, guarded([&](std::shared_ptr<Work> w) {
                  const std::string input_hash = plan.source->input_hash(w->index, w->bytes);
                  if (c.resume) {
                    w->redo = resume_problem(plan, w->index, input_hash, w->record);
                    if (w->redo.empty()) {
                      w->resumed = true;
                      w->summary = w->record.summary;
                      w->summary.resumed = true;
                      w->has_output = !(w->summary.status == FrameStatus::Failed &&
                                        c.output.on_failure == OnFailure::Skip);
                      return w;
                    }
                  }
                  w->record.input_hash = input_hash;
                  process_frame(plan, *w);
                  if (!failed) write_frame_files(plan, *w);  // else dropped, like the others
                  return w;
                })) &
            tbb::make_filter<std::shared_ptr<Work>, void>(
                tbb::filter_mode::serial_in_order, guarded([&](std::shared_ptr<Work> w) {
                  if (w->resumed) {
                    ++result.resumed;
                  } else {
                    // The frame's own files are written (write_frame_files); the shared files
                    // they need go here, in frame order, then its record if they held it back.
                    if (c.resume) ++result.redone[w->redo];
                    if (w->needs_shared) {
                      for (size_t k = 0; k < plan.outputs.size(); ++k) {
                        if (!w->outputs[k].needs_shared || shared_written[k]) continue;
                        for (const auto& [file, bytes] : plan.outputs[k]->shared_files())
                          write_file_atomic(out / file, bytes);
                        shared_written[k] = true;
                      }
                      write_record(plan, *w);
                    }
                  }
                  keep(*w);
                  const FrameSummary& s = w->summary;
                  append_frame_warnings(s, c.output.on_failure, result.warnings);
                  if (s.status == FrameStatus::Failed) ++result.failed;
                  result.frames.push_back(std::move(w->summary));
                  if (hooks.progress)
                    hooks.progress(result.frames.back(), static_cast<int>(result.frames.size()),
                                   static_cast<int>(total), seconds_since(t0));
                  return w;
                })));
  });
  if (error) std::rethrow_exception(error);
  for (const auto& output : plan.outputs)
    for (std::string& warning : output->finish(done).warnings)
      result.warnings.push_back(std::move(warning));
  result.seconds = seconds_since(t0);
  write_file_atomic(out / summary_file_name(c.shard),
                    format_summary_csv(result.frames, c.output.timings));
  write_file_atomic(out / report_file_name(c.shard), make_report(plan, result).dump(2) + "\n");
  return result;
}

}  // namespace sm
