#include "pipeline/run/sequence_job.hpp"

#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <exception>
#include <mutex>

#include "io/atomic_file.hpp"
#include "io/sha256.hpp"
#include "core/timing.hpp"
#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/run/frame_processor.hpp"
#include "pipeline/cluster/output_lock.hpp"
#include "pipeline/cluster/frame_record.hpp"
#include "pipeline/report/report.hpp"
#include "pipeline/run/sequence_report.hpp"
#include "pipeline/sequence/shard.hpp"

namespace sm {
namespace fs = std::filesystem;

namespace {

// One frame in flight through the pipeline.
struct Work {
  int index = 0;
  std::string bytes;                 // what the source fetched (the input file as read, if any)
  std::vector<OutputFrame> outputs;  // each output's part, as plan.outputs
  bool needs_shared = false;  // an output's shared files must be in place before the record
  FrameSummary summary;
  bool has_output = true;  // false: failed, and output.on_failure is "skip"
  FrameRecord record;      // the record to write, or the one resumed from
  bool resumed = false;    // the record is current: nothing to compute or write
  std::string redo;        // resuming: why the frame is processed again
};
using WorkPtr = std::shared_ptr<Work>;

bool has_output(const FrameSummary& s, OnFailure on_failure) {
  return !(s.status == FrameStatus::Failed && on_failure == OnFailure::Skip);
}

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

bool wants_shear_per_iteration(const SequencePlan& plan, int index) {
  for (const auto& output : plan.outputs)
    if (output->wants_shear_per_iteration(index)) return true;
  return false;
}

// The record of a processed frame: the hashes, every output file it has (path, size, SHA-256)
// and the outputs' record rows.
void fill_record(const SequencePlan& plan, Work& w) {
  FrameRecord& r = w.record;
  r.config_hash = plan.config_hash;
  r.template_hash = plan.template_hash;
  r.outputs.clear();
  r.record_rows.clear();
  for (size_t o = 0; o < w.outputs.size(); ++o) {
    const OutputFrame& part = w.outputs[o];
    if (w.has_output)
      for (const auto& [path, bytes] : part.files)
        r.outputs.push_back({path.generic_string(), bytes.size(), sha256_hex(bytes)});
    w.needs_shared = w.needs_shared || (w.has_output && part.needs_shared);
    plan.outputs[o]->add_record_rows(r.record_rows, part);
  }
  r.summary = w.summary;
}

// The frame through the processor's stages: optimize → check → measure → encode.
void process_frame(const SequencePlan& plan, Work& w) {
  const auto t0 = Clock::now();
  const FrameProcessor& processor = *plan.processor;
  const std::string label = plan.source->label(w.index);
  ProcessedFrame f =
      processor.start(w.index, plan.source->decode(w.index, std::move(w.bytes)), label);
  processor.optimize(f, label, wants_shear_per_iteration(plan, w.index));
  processor.check(f);
  processor.measure(f);
  w.outputs = processor.encode(f, plan.outputs);
  f.summary.file = plan.source->name(w.index);
  f.summary.time = plan.source->time(w.index);
  // 0 without timings: records reproduce byte for byte.
  f.summary.seconds = plan.config.output.timings ? seconds_since(t0) : 0.0;
  w.summary = std::move(f.summary);
  w.has_output = has_output(w.summary, plan.config.output.on_failure);
  fill_record(plan, w);
}

void write_record(const SequencePlan& plan, const Work& w) {
  write_file_atomic(record_file(plan.config.output.dir, plan.source->name(w.index)),
                    to_json(w.record).dump(1) + "\n");
}

// A frame's files, written in the parallel stage: no other frame writes them, so the frames'
// writes (and their fsyncs) overlap the others' work instead of queueing in the serial stage. The
// order within the frame is kept: the old record is removed first, then the outputs are written
// (or, for a frame without output, removed), then the record, which comes back last. A frame
// whose files need an output's shared files (the checker texture, written in frame order with the
// first frame that needs it) has its record written in the serial stage, after them. Frees the
// encoded bytes.
void write_frame_files(const SequencePlan& plan, Work& w) {
  const fs::path& out = plan.config.output.dir;
  remove_output_file(record_file(out, plan.source->name(w.index)));
  for (OutputFrame& part : w.outputs) {
    for (const auto& [file, bytes] : part.files) {
      if (w.has_output)
        write_file_atomic(out / file, bytes);
      else
        remove_output_file(out / file);
    }
    part.files.clear();
    part.files.shrink_to_fit();
  }
  if (!w.needs_shared) write_record(plan, w);
}

// One run of a plan: the pipeline's three stages (read in order → process and write each frame
// in parallel → complete in order) and what the run keeps between them.
class SequenceRun {
 public:
  SequenceRun(const SequencePlan& plan, const RunHooks& hooks)
      : plan_(plan), hooks_(hooks), shared_written_(plan.outputs.size()) {}

  SequenceResult run() {
    t0_ = Clock::now();
    result_.warnings = plan_.warnings;
    start();
    tbb::task_arena arena(plan_.threads);
    arena.execute([&] {
      tbb::parallel_pipeline(
          static_cast<size_t>(plan_.frames_in_flight),
          tbb::make_filter<void, WorkPtr>(tbb::filter_mode::serial_in_order,
                                          [&](tbb::flow_control& fc) { return read(fc); }) &
              tbb::make_filter<WorkPtr, WorkPtr>(
                  tbb::filter_mode::parallel,
                  [&](WorkPtr w) { return guarded(std::move(w), &SequenceRun::process); }) &
              tbb::make_filter<WorkPtr, void>(tbb::filter_mode::serial_in_order, [&](WorkPtr w) {
                guarded(std::move(w), &SequenceRun::complete);
              }));
    });
    if (error_) std::rethrow_exception(error_);
    finish();
    return std::move(result_);
  }

 private:
  // Removes what an earlier run left that would no longer describe the files: stale
  // temporaries, the summary and report (written again when this run ends, or stops); prepares
  // the source and starts the outputs.
  void start() {
    const fs::path& out = plan_.config.output.dir;
    for (const char* dir : {".", "records", "input", "ground_truth"})
      remove_stale_temporaries(out / dir);
    for (const std::string& name :
         {summary_file_name(plan_.config.shard), report_file_name(plan_.config.shard)})
      remove_output_file(out / name);
    plan_.source->prepare();
    for (const auto& output : plan_.outputs) {
      for (const fs::path& dir : output->folders()) remove_stale_temporaries(dir);
      output->start(plan_);
    }
  }

  // Stage 1 (serial, in order): the next frame's bytes, or the end of the input.
  WorkPtr read(tbb::flow_control& fc) {
    const size_t total = plan_.run_frames.size();
    if (next_ < total && hooks_.cancel && hooks_.cancel->load()) result_.interrupted = true;
    if (next_ >= total || result_.interrupted || failed_) {
      fc.stop();
      return nullptr;
    }
    auto w = std::make_shared<Work>();
    w->index = plan_.run_frames[next_++];
    return guarded(std::move(w), &SequenceRun::fetch);
  }

  WorkPtr fetch(WorkPtr w) {
    w->bytes = plan_.source->fetch(w->index);
    return w;
  }

  // Stage 2 (parallel): the frame resumed from its record, or processed and its files written.
  WorkPtr process(WorkPtr w) {
    const std::string input_hash = plan_.source->input_hash(w->index, w->bytes);
    if (plan_.config.resume) {
      w->redo = resume_problem(plan_, w->index, input_hash, w->record);
      if (w->redo.empty()) {
        w->resumed = true;
        w->summary = w->record.summary;
        w->summary.resumed = true;
        w->has_output = has_output(w->summary, plan_.config.output.on_failure);
        return w;
      }
    }
    w->record.input_hash = input_hash;
    process_frame(plan_, *w);
    if (!failed_) write_frame_files(plan_, *w);  // else dropped, like the others
    return w;
  }

  // Stage 3 (serial, in order): the shared files a frame needs and its record if they held it
  // back; the frame's row, warnings and progress.
  WorkPtr complete(WorkPtr w) {
    if (w->resumed) {
      ++result_.resumed;
    } else {
      if (plan_.config.resume) ++result_.redone[w->redo];
      if (w->needs_shared) {
        write_shared_files(*w);
        write_record(plan_, *w);
      }
    }
    if (w->has_output) {
      done_.frames.push_back(w->index);
      done_.names.push_back(w->summary.file);
    }
    append_record_rows(done_.record_rows, w->record.record_rows);
    const FrameSummary& s = w->summary;
    append_frame_warnings(s, plan_.config.output.on_failure, result_.warnings);
    if (s.status == FrameStatus::Failed) ++result_.failed;
    result_.frames.push_back(std::move(w->summary));
    if (hooks_.progress)
      hooks_.progress(result_.frames.back(), static_cast<int>(result_.frames.size()),
                      static_cast<int>(plan_.run_frames.size()), seconds_since(t0_));
    return w;
  }

  void write_shared_files(const Work& w) {
    for (size_t k = 0; k < plan_.outputs.size(); ++k) {
      if (!w.outputs[k].needs_shared || shared_written_[k]) continue;
      for (const auto& [file, bytes] : plan_.outputs[k]->shared_files())
        write_file_atomic(plan_.config.output.dir / file, bytes);
      shared_written_[k] = true;
    }
  }

  // The outputs' whole-run files, summary.csv and report.json.
  void finish() {
    const SequenceJobOptions& c = plan_.config;
    done_.summaries = &result_.frames;
    done_.warnings = &result_.warnings;
    const auto t_finish = Clock::now();
    for (const auto& output : plan_.outputs)
      for (std::string& warning : output->finish(done_).warnings)
        result_.warnings.push_back(std::move(warning));
    result_.seconds_finish = seconds_since(t_finish);
    result_.seconds = seconds_since(t0_);
    write_file_atomic(c.output.dir / summary_file_name(c.shard),
                      format_summary_csv(result_.frames, c.output.timings));
    write_file_atomic(c.output.dir / report_file_name(c.shard),
                      make_report(plan_, result_).dump(2) + "\n");
  }

  // Runs `stage` only while nothing failed, and records its exception: the first exception of a
  // stage stops the input and is rethrown once the frames in flight have drained (those that
  // finish after it are not written; one finishing at the same moment may have written its
  // complete files). Thrown through parallel_pipeline, it would leak them (oneTBB does not
  // destroy the tokens of a cancelled pipeline).
  WorkPtr guarded(WorkPtr w, WorkPtr (SequenceRun::*stage)(WorkPtr)) {
    if (!failed_) try {
        w = (this->*stage)(std::move(w));
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex_);
        if (!error_) error_ = std::current_exception();
        failed_ = true;
      }
    return w;
  }

  const SequencePlan& plan_;
  const RunHooks& hooks_;
  Clock::time_point t0_;
  SequenceResult result_;
  size_t next_ = 0;                  // the next of plan.run_frames to read
  FinishedFrames done_;              // what the outputs finish from
  std::vector<bool> shared_written_;  // the outputs' shared files, this run
  std::exception_ptr error_;
  std::mutex error_mutex_;
  std::atomic<bool> failed_{false};
};

}  // namespace

SequenceResult run_sequence_job(const SequencePlan& plan, const RunHooks& hooks) {
  // One writer per output folder and shard, for the whole run (released when this returns or
  // throws). Its warnings are not the run's: a resumed run writes what an uninterrupted one does.
  const OutputLock lock = lock_output_folder(plan.config.output.dir, plan.config.shard);
  if (hooks.notice)
    for (const std::string& w : lock.warnings()) hooks.notice(w);
  return SequenceRun(plan, hooks).run();
}

}  // namespace sm
