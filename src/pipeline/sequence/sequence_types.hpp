#pragma once
/// The plan, result and hooks of a sequence job: the low structs. plan_sequence_job
/// (sequence_plan.hpp) builds a plan without writing anything, run_sequence_job
/// (sequence_job.hpp) runs it; the outputs, the frame processor, the reports and the run texts
/// read these structs only, and name the outputs and the processor by forward declaration.
#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"
#include "pipeline/sequence/frame_source.hpp"
#include "pipeline/sequence/frame_summary.hpp"
#include "pipeline/sequence/sequence_options.hpp"

namespace sm {

/// The text the frames' records keep for the outputs' finish(), per output: its record key
/// (FrameOutput::kRecordKey) → the rows, in frame order.
using RecordRows = std::map<std::string, std::string>;

class FrameOutput;
class FrameProcessor;

struct SequencePlan {
  SequenceJobOptions config;
  std::shared_ptr<const FrameSource> source;  ///< every input frame, in order
  /// The per-frame outputs the config enables, in registry order (make_frame_outputs). Their
  /// encode and plan methods are const; start() is called once per run, before any frame.
  std::vector<std::shared_ptr<FrameOutput>> outputs;
  std::vector<int> selected;    ///< indices of the job's selected frames, in order
  std::vector<int> run_frames;  ///< the frames this run processes: `selected`, or its shard of them
  int template_frame = -1;      ///< index of the template frame, -1 for a mesh
  std::string template_source;  ///< e.g. "frame 0 (frame_0000.obj)"
  TriMesh templ;                ///< the original template: weights and shear
  /// Every frame's stages (optimize, check, measure, encode): the template's Massager, the
  /// distance meter and the checks, built once.
  std::shared_ptr<const FrameProcessor> processor;
  int threads = 1;            ///< resolved worker threads
  int frames_in_flight = 2;   ///< resolved pipeline tokens
  std::string config_hash;    ///< frame_config_hash(config), kept in every frame record
  std::string template_hash;  ///< template_hash(templ)
  std::vector<std::string> warnings;
};

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

}  // namespace sm
