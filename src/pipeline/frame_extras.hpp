#pragma once
/// The sequence job's optional visual outputs, written beside the frames: shear as coloured PLY
/// meshes (output.colored: colored/before|after/<frame>.ply), the frames with a checkerboard
/// texture (output.checker: checker/before|after/<frame>.obj, checker.mtl, checker.png) and the
/// optimizer's course (output.iterations: iterations.csv). Like a FrameSink, each frame's files
/// are encoded in the pipeline's parallel stage and written in frame order.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "massage/massage.hpp"
#include "pipeline/checker.hpp"
#include "pipeline/frame_source.hpp"
#include "pipeline/iteration_log.hpp"
#include "pipeline/sequence_options.hpp"

namespace sm {

struct SequencePlan;

/// A processed frame, as the extras see it (valid during the call).
struct FrameOutcome {
  int index = 0;
  const SourceFrame* input = nullptr;             ///< the frame as read
  const Positions* output = nullptr;              ///< its output positions (n×3)
  const Eigen::VectorXd* shear_before = nullptr;  ///< eq. 8 of the input frame (m values)
  const Eigen::VectorXd* shear_after = nullptr;   ///< eq. 8 of the output frame
  const MassageResult* result = nullptr;          ///< the optimizer's run; null if not optimized
  const Reference* reference = nullptr;           ///< its reference; null if not optimized
  /// The shear after every iteration of `result` (shear_observer), for the frames whose
  /// iterations.csv rows carry it (FrameExtras::wants_shear_per_iteration); else null.
  const std::vector<std::optional<DistortionSummary>>* shear_per_iteration = nullptr;
};

/// A frame's encoded extras.
struct ExtraFrame {
  std::vector<std::pair<std::filesystem::path, std::string>> files;  ///< relative to output.dir
  int frame = 0;
  std::string file;                      ///< the frame's name (iterations.csv `file`)
  std::vector<IterationRow> iterations;  ///< empty when the frame is not logged
  std::string iterations_csv;            ///< `iterations` as iterations.csv rows (no header)
  std::string warning;
};

/// One run's extras: started by FrameExtras::start once the inputs exist.
class ExtrasRun {
 public:
  virtual ~ExtrasRun() = default;
  /// The extras of one frame. Thread-safe.
  virtual ExtraFrame encode(const FrameOutcome& outcome) const = 0;
  /// Writes a frame's files (and the checker texture with the first checker frame). Called in
  /// frame order, one thread at a time.
  virtual void write(const ExtraFrame& frame) = 0;
  /// A frame resumed from its record: its files are in place; its iterations.csv rows (as
  /// ExtraFrame::iterations_csv) are added. Called in frame order like write().
  virtual void keep(const std::string& iterations_csv) = 0;
  /// Writes iterations.csv (iterations.shard-I-of-N.csv for a shard) of the frames written and
  /// kept; returns report.json "outputs" entries.
  virtual nlohmann::json finish() = 0;
};

class FrameExtras {
 public:
  FrameExtras(const SequenceJobOptions& config, std::shared_ptr<const FrameSource> source);

  /// Whether any extra output is enabled.
  bool any() const;
  /// The files a run of `frames` writes (for the overwrite check).
  std::vector<std::filesystem::path> files(const std::vector<int>& frames) const;
  /// The folders the extras write into (for stale temporary files).
  std::vector<std::filesystem::path> folders() const;
  /// Whether frame `index`'s iterations.csv rows carry the shear after every iteration
  /// (output.iterations.shear_frames): the frame's run then takes a shear_observer.
  bool wants_shear_per_iteration(int index) const;
  /// Plan lines, each "  <file>: <what>\n".
  std::string describe(const std::vector<int>& frames) const;
  /// Warnings for frames listed in a selection that the run does not process.
  std::vector<std::string> check(const std::vector<int>& frames) const;
  /// Starts a run: reads the template's texture coordinates (the template frame as read, after
  /// the source is prepared), nothing is written yet.
  std::unique_ptr<ExtrasRun> start(const SequencePlan& plan) const;

 private:
  SequenceJobOptions config_;
  std::shared_ptr<const FrameSource> source_;
};

}  // namespace sm
