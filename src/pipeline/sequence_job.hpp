#pragma once
/// The sequence job (paper §3.1): every frame of a mesh sequence is massaged towards the triangle
/// shapes of a template frame while it stays on its own surface, streamed through a bounded TBB
/// pipeline (read in order → decode, optimize, measure and encode in parallel → write in order)
/// from a FrameSource (OBJ folder, synthetic, glTF, point cache) to the per-frame outputs
/// (frame_output.hpp).
#include <atomic>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/frame_summary.hpp"
#include "pipeline/sequence_options.hpp"
#include "pipeline/sequence_plan.hpp"

namespace sm {

/// Result of a run, the frames in order.
struct SequenceResult {
  std::vector<FrameSummary> frames;
  std::vector<std::string> warnings;
  int failed = 0;
  int resumed = 0;  ///< frames taken from their records (resume), not processed again
  /// Why frames were processed again when resuming, with how many: "no record", "the config
  /// changed", "the input changed", "an output is missing or changed", ...
  std::map<std::string, int> redone;
  bool interrupted = false;  ///< stopped by RunHooks::cancel before every frame was done
  double seconds = 0.0;      ///< wall time of the whole run
  /// Of it, the outputs' whole-run files (FrameOutput::finish: report.html, iterations.csv, ...).
  double seconds_finish = 0.0;
};

struct RunHooks {
  /// Called after each frame is written, in frame order, from one thread at a time.
  std::function<void(const FrameSummary& frame, int done, int total, double elapsed_seconds)>
      progress;
  /// When it becomes true, no further frame is started; frames in flight are finished and
  /// written, then summary.csv and report.json record the interruption.
  const std::atomic<bool>* cancel = nullptr;
  /// Called with warnings about the run that are not the job's (not in report.json): a lock file
  /// taken over from a run that ended without removing it.
  std::function<void(const std::string& warning)> notice;
};

/// Checks the config and every input before anything runs: lists the frames (or loads and welds
/// the glTF), selects the run's frames (input.range, then config.shard), reads every one of them
/// (in parallel, in a bounded way) and compares its vertex count and faces with the template's,
/// builds the template's Massager, and refuses an output folder that would overwrite an input.
/// Throws ConfigError, InputError (naming the frame and the counts, or the glTF file and element)
/// or IoError. Writes nothing.
SequencePlan plan_sequence_job(const SequenceJobOptions& config);

/// What a run of `plan` would do, several lines of text (for --dry-run).
std::string describe_plan(const SequencePlan& plan);

/// Runs the job: takes the output folder's lock (lock_output_folder: IoError if another run
/// holds it), writes the synthetic input (if any), then per frame frames/<name>.obj (or
/// positions/<name>.bin, assembled into sequence.glb, or sequence.pc2 / .mdd and rest.obj, at the
/// end), distortion/<name>.csv (if asked)
/// and its record records/<name>.json, then summary.csv and report.json (named by shard for a
/// shard) under config.output.dir, each file atomically. With config.resume, a frame whose record
/// is current (same config hash, template hash and input hash; outputs present with their size
/// and SHA-256) is not processed again: its row comes from the record. A frame's numerical failure
/// (optimizer failure, non-finite positions, more folded triangles than checks allow) is recorded
/// in the result, not thrown. Same plan, same output bytes (apart from timings), whatever the
/// number of threads, interruptions and resumes.
SequenceResult run_sequence_job(const SequencePlan& plan, const RunHooks& hooks = {});

}  // namespace sm
