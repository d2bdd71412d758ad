#pragma once
/// The track job ("job": "track"): one template tracked through a folder of raw frames of any
/// connectivity (track/tracker.hpp: deformation graph and robust non-rigid ICP, then Mesh
/// Massage toward each raw frame), its connectivity written on every frame through the sequence
/// job's per-frame outputs (frame_output.hpp: OBJ frames with the template's texture coordinates
/// and materials, PC2/MDD with rest.obj, checker, coloured shear, report.html), with
/// summary.csv's per-frame fit figures and status (ok, recovered, lost) and report.json.
///
/// Frames are tracked in order, each from the previous one's fit: from a template frame K
/// forward to the last selected frame, then from K backward to the first (the template placed
/// where it was captured); from a template mesh forward from the first selected frame. A shard
/// (--shard I/N, "shard") tracks its block of the selected frames the same way when the block
/// holds frame K, else forward from the block's first frame, onto which the template is
/// registered directly (the tracker's recovery aligns it when it does not fit as placed); its
/// summary and report are named by shard and `seqmassage merge` (track_merge.hpp) combines them,
/// reporting the seams, the first frames of the shards after the first. The
/// parallelism is inside each frame (TBB); the output bytes do not depend on the thread count.
#include <atomic>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "io/gltf/gltf_weld.hpp"
#include "pipeline/run/sequence_plan.hpp"
#include "pipeline/track/track_frames.hpp"
#include "pipeline/track/track_job_options.hpp"
#include "track/tracker.hpp"

namespace sm {

/// Everything a run needs, checked (plan_track_job writes nothing).
struct TrackPlan {
  TrackJobOptions config;
  std::vector<std::filesystem::path> files;  ///< every raw frame, in natural order
  std::vector<int> selected;                 ///< the frames to track, in frame order
  std::vector<int> block;                    ///< the shard's part of them (all, unsharded)
  std::vector<int> order;                    ///< the block, in the order it is tracked
  int start_frame = 0;  ///< the block's frames from here on go forward, those before backward
  int template_frame = -1;                   ///< -1 for template.mesh
  std::string template_source;               ///< "frame 0 (a.obj)" or the mesh's file name
  TemplateLayout layout;                     ///< the template as the outputs write it
  GltfWeld weld;                             ///< the template welded by position
  /// What the per-frame outputs are built and started with: the sequence job's options of the
  /// output (output_job_options), the layout source, the outputs, the template.
  SequencePlan outputs;
  int threads = 1;
  std::vector<std::string> warnings;
};

/// Lists the frames, selects them (input.range), reads the template and builds the tracker once
/// (so that its options and the template are checked), builds the outputs and refuses an output
/// that would overwrite an input. Throws ConfigError (template.frame out of range, an output
/// format the job cannot feed), InputError (no frame, an unreadable template, two frames whose
/// outputs would share a name) or IoError (a missing folder).
TrackPlan plan_track_job(const TrackJobOptions& config);

/// What a run of `plan` would do, several lines (for --dry-run).
std::string describe_track_plan(const TrackPlan& plan);

/// One tracked frame: its summary.csv row.
struct TrackRow {
  int frame = 0;
  std::string file;  ///< the raw frame's file name
  int raw_vertices = 0, raw_triangles = 0;  ///< welded
  TrackStatus status = TrackStatus::Ok;
  std::string recovery;
  std::string beyond;  ///< a lost frame: which figures exceed which tolerance
  FitFigures fit, registration_fit;
  int iterations = 0;
  double seconds_register = 0, seconds_refine = 0;  ///< 0 without output.timings
};

struct TrackResult {
  std::vector<TrackRow> frames;  ///< in frame order
  std::vector<std::string> warnings;
  int lost = 0, recovered = 0;
  bool interrupted = false;
  double seconds = 0;
};

struct TrackHooks {
  /// After each frame is written, in tracking order.
  std::function<void(const TrackRow& row, int done, int total, double elapsed_seconds)> progress;
  /// When it becomes true, no further frame is tracked; what is done is written and reported.
  const std::atomic<bool>* cancel = nullptr;
};

/// Runs the job: takes the output folder's lock, tracks every selected frame and writes its
/// outputs (atomically), then the outputs' whole-run files, summary.csv and report.json. A lost
/// frame is written as its best attempt and listed in report.json's "lost". Throws InputError
/// naming the frame and file for a raw frame that cannot be read, IoError for a write.
TrackResult run_track_job(const TrackPlan& plan, const TrackHooks& hooks = {});

/// summary.csv of the track job: one row per frame, in frame order.
std::string format_track_summary_csv(const std::vector<TrackRow>& rows);

/// A frame's entry in report.json's "frames": every field of its row, exact.
nlohmann::json to_json(const TrackRow& row);
/// Throws InputError naming the missing or wrong key.
TrackRow track_row_from_json(const nlohmann::json& json);

/// report.json of the track job. A shard's report.shard-I-of-N.json adds its "shard" section
/// (track_job.cpp): index, count, its frames, whether it completed them, and every frame's
/// row, report.html row and outputs' record rows, from which merge finishes the run.
nlohmann::json make_track_report(const TrackPlan& plan, const TrackResult& result);

}  // namespace sm
