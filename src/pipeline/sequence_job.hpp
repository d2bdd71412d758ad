#pragma once
/// The sequence job (paper §3.1): every frame of a mesh sequence is massaged towards the triangle
/// shapes of a template frame while it stays on its own surface, streamed through a bounded TBB
/// pipeline (read in order → decode, optimize, measure and encode in parallel → write in order)
/// from a FrameSource (OBJ folder, synthetic, glTF, point cache) to a FrameSink (OBJ frames, GLB,
/// point cache).
#include <atomic>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geometry/distance.hpp"
#include "geometry/shear.hpp"
#include "massage/massage.hpp"
#include "pipeline/frame_sink.hpp"
#include "pipeline/frame_source.hpp"
#include "pipeline/sequence_options.hpp"

namespace sm {

class FrameExtras;

/// What happened to a frame.
enum class FrameStatus {
  Optimized,  ///< "optimized": massaged and written with its new positions
  Template,   ///< "template": the template frame, written unchanged (byte for byte)
  Failed,     ///< "failed": numerical failure; written unchanged or not at all (output.on_failure),
              ///< the reason in `failure`
};

/// Distances of the synthetic sequence's vertices to their ground-truth positions, in units of
/// the template's mean edge length.
struct GroundTruthError {
  double mean_before = 0.0, max_before = 0.0;  ///< the input (drifted) frame
  double mean_after = 0.0, max_after = 0.0;    ///< the output frame
};

/// One row of summary.csv.
struct FrameSummary {
  int frame = 0;               ///< index in the natural order of the input frames
  std::string file;            ///< the frame's file name (FrameSource::name)
  std::optional<double> time;  ///< seconds into the animation (glTF input)
  int vertices = 0;
  int triangles = 0;
  DistortionSummary shear_before;  ///< eq. 8 against the original template, input frame
  DistortionSummary shear_after;   ///< the same for the output frame
  DistanceStats out_to_in;         ///< output frame sampled, to the input frame's surface
  DistanceStats in_to_out;         ///< input frame sampled, to the output frame's surface
  int iterations = 0;              ///< outer iterations run
  double seconds = 0.0;            ///< optimization and measures of this frame
  FrameStatus status = FrameStatus::Optimized;
  /// Why the frame failed (status Failed): "optimizer failed: ...", "non-finite positions: ..."
  /// or "folded triangles: ...".
  std::string failure;
  /// Output triangles whose normal opposes the same triangle's normal in the input frame
  /// (count_folded_triangles); checks.max_folded_triangles decides whether the frame fails.
  int folded_triangles = 0;
  std::optional<GroundTruthError> ground_truth;  ///< synthetic input only
  std::vector<std::string> warnings;             ///< from reading the frame (e.g. glTF welding)
  /// Not processed by this run: taken from the frame's record by resume (not in summary.csv).
  bool resumed = false;
};

/// Everything a run needs, checked: built by plan_sequence_job without writing anything.
struct SequencePlan {
  SequenceJobOptions config;
  std::shared_ptr<const FrameSource> source;  ///< every input frame, in order
  std::shared_ptr<const FrameSink> sink;      ///< where the corrected frames go
  std::shared_ptr<const FrameExtras> extras;  ///< colored, checker and iterations outputs
  std::vector<int> selected;                  ///< indices of the job's selected frames, in order
  std::vector<int> run_frames;  ///< the frames this run processes: `selected`, or its shard of them
  int template_frame = -1;      ///< index of the template frame, -1 for a mesh
  std::string template_source;  ///< e.g. "frame 0 (frame_0000.obj)"
  TriMesh templ;                ///< the original template: weights and shear
  std::shared_ptr<const Massager> massager;  ///< built once from the template
  /// The distances' sampling layout of the template's triangles (every frame's), built once.
  std::shared_ptr<const DistanceLayout> distance_layout;
  /// Their scratch memory, one workspace per frame being measured, kept from frame to frame.
  std::shared_ptr<DistanceWorkspaces> distance_workspaces;
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
  nlohmann::json extra_outputs = nlohmann::json::object();  ///< report.json "outputs" entries
};

struct RunHooks {
  /// Called after each frame is written, in frame order, from one thread at a time.
  std::function<void(const FrameSummary& frame, int done, int total, double elapsed_seconds)>
      progress;
  /// When it becomes true, no further frame is started; frames in flight are finished and
  /// written, then summary.csv and report.json record the interruption.
  const std::atomic<bool>* cancel = nullptr;
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

/// Runs the job: writes the synthetic input (if any), then per frame frames/<name>.obj (or
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

/// The column value of a status: "optimized", "template", "failed".
const char* status_name(FrameStatus status);

}  // namespace sm
