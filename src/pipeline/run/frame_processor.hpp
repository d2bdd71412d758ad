#pragma once
/// The sequence job's work on one frame, in named stages: optimize (the template's Massager,
/// paper §3.1) → check (finite positions, folded triangles against `checks`) → measure (shear
/// eq. 8 both ways, Metro distances both ways, ground truth) → encode (every output's part).
/// Built once per plan; every stage is const and thread-safe, so frames go through it in
/// parallel.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geometry/distance_meter.hpp"
#include "massage/massage.hpp"
#include "massage/reference.hpp"
#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/sequence/frame_source.hpp"
#include "pipeline/sequence/frame_summary.hpp"
#include "pipeline/sequence/sequence_options.hpp"

namespace sm {

/// One frame on its way through the stages.
struct ProcessedFrame {
  int index = 0;
  SourceFrame input;       ///< the frame as read (its connectivity is the template's)
  Positions V;             ///< the output positions (n×3); the input's while `unchanged`
  bool unchanged = true;   ///< the output is the input (template frame, failed frame)
  std::optional<Reference> reference;  ///< the input's surface, for an optimized frame
  MassageResult result;                ///< the optimizer's run (with `reference`)
  /// The shear after every iteration of `result`, when an output asked for it.
  std::vector<std::optional<DistortionSummary>> shear_per_iteration;
  Eigen::VectorXd shear_before, shear_after;  ///< eq. 8 per triangle (m values)
  /// Folded triangles of `result.V` against the input, when the fold repair already counted them
  /// (so check() does not count them again).
  std::optional<int> folded;
  FrameSummary summary;
};

class FrameProcessor {
 public:
  /// For frames like `templ` (the original template, named `template_source` in messages; the
  /// frame `template_frame` of the sequence, or -1 for a rest mesh). Builds the Massager
  /// (Massager's errors) and the distance meter.
  FrameProcessor(TriMesh templ, const SequenceJobOptions& config, std::string template_source,
                 int template_frame);

  const Massager& massager() const { return *massager_; }
  const TriMesh& templ() const { return templ_; }

  /// Why `frame` (named `who` in the message) cannot be massaged with the template's
  /// connectivity, or "" if it can.
  std::string connectivity_mismatch(const std::string& who, const TriMesh& frame) const;

  /// The frame `index` read as `input` (named `label`), ready for the stages: its summary's
  /// identity and counts and its shear before. Throws InputError when its connectivity is not
  /// the template's.
  ProcessedFrame start(int index, SourceFrame input, const std::string& label) const;
  /// Massages the frame (unless it is the template frame written unchanged, or has non-finite
  /// input positions: then it fails), with the shear after every iteration when asked.
  void optimize(ProcessedFrame& frame, const std::string& label, bool shear_per_iteration) const;
  /// A massaged frame's output against the checks: the optimizer's failure, non-finite
  /// positions, more folded triangles than checks allow fail it; else its positions are taken.
  void check(ProcessedFrame& frame) const;
  /// Shear after, the summaries, the distances both ways (optimized frames) and the ground truth
  /// error (a generated sequence).
  void measure(ProcessedFrame& frame) const;
  /// Every output's part of the frame, in the order of `outputs`.
  std::vector<OutputFrame> encode(const ProcessedFrame& frame,
                                  const std::vector<std::shared_ptr<FrameOutput>>& outputs) const;

 private:
  std::string fold_check(const ProcessedFrame& frame, const Positions& V, int& folded) const;
  std::string fold_limit_exceeded(int folded) const;
  void repair(ProcessedFrame& frame) const;

  TriMesh templ_;
  std::string template_source_;
  int template_frame_;
  bool optimize_template_;
  SampleKind samples_;
  FrameCheckOptions checks_;
  MassageOptions massage_;  // for the fold repair's re-solves
  std::shared_ptr<const Massager> massager_;
  DistanceMeter meter_;
};

}  // namespace sm
