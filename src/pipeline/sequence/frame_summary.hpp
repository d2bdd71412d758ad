#pragma once
/// What the sequence job keeps of one frame: its status and its row of summary.csv (also the
/// frame's part of report.json and of its record). A low header: every pipeline stage, the
/// outputs, the records and the reports include it, it includes none of them.
#include <optional>
#include <string>
#include <vector>

#include "geometry/distance.hpp"
#include "geometry/ground_truth.hpp"
#include "geometry/shear.hpp"

namespace sm {

/// What happened to a frame.
enum class FrameStatus {
  Optimized,  ///< "optimized": massaged and written with its new positions
  Template,   ///< "template": the template frame, written unchanged (byte for byte)
  Failed,     ///< "failed": numerical failure; written unchanged or not at all (output.on_failure),
              ///< the reason in `failure`
};

/// The column value of a status: "optimized", "template", "failed".
const char* status_name(FrameStatus status);

/// Distances of the synthetic sequence's vertices to their ground-truth positions, in units of
/// the template's mean edge length.
struct GroundTruthError {
  double mean_before = 0.0, max_before = 0.0;  ///< the input (drifted) frame
  double mean_after = 0.0, max_after = 0.0;    ///< the output frame
  /// The same split along and off the true surface (geometry/ground_truth.hpp).
  CorrespondenceError split_before, split_after;
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

}  // namespace sm
