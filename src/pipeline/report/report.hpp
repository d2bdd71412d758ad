#pragma once
/// The tables and the report of a sequence job: summary.csv (one row per frame) and report.json.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "pipeline/sequence/frame_summary.hpp"
#include "pipeline/sequence/sequence_types.hpp"
#include "pipeline/sequence/sequence_options.hpp"

namespace sm {

/// The columns of summary.csv: frame, file, vertices, triangles, shear_{max,mean,p95}_{before,
/// after}, dist_out_to_in_{max,rms}, dist_in_to_out_{max,rms}, iterations, seconds, then status,
/// failure, time (seconds into the animation for glTF input, empty otherwise) and
/// folded_triangles; with `ground_truth` (a generated input), then truth_{,tangential_,normal_}
/// {mean,max}_{before,after} (GroundTruthError, in template mean edge lengths).
std::vector<std::string> summary_columns(bool ground_truth = false);

/// summary.csv, one row per frame in order. Without `timings`, the seconds column holds 0.
std::string format_summary_csv(const std::vector<FrameSummary>& frames, bool timings);

/// Appends the warnings report.json lists for a frame, in this order: its own (reading it),
/// its failure ("frame 3 (frame_0003.obj) failed, written unchanged: ..."; "not written" with
/// on_failure "skip") and its folded triangles, each prefixed by the frame's label.
void append_frame_warnings(const FrameSummary& frame, OnFailure on_failure,
                           std::vector<std::string>& warnings);

/// Program and library versions: seqmassage, Eigen, oneTBB, nlohmann-json, compiler.
nlohmann::json version_info();

/// The parts of report.json that the plan decides, the same in every shard of a job (a planned
/// run's: run/sequence_report.hpp).
struct ReportHeader {
  nlohmann::json versions;  ///< version_info()
  /// The job's resolved config (to_json) with the run controls reset: "shard" {0, 1} and
  /// "resume" false, so that a sharded, merged or resumed run reports the same config as one run.
  nlohmann::json config;
  nlohmann::json input;               ///< FrameSource::report()
  nlohmann::json templ;               ///< "template": source, counts, fallback vertices, hash
  nlohmann::json outputs;             ///< file names, relative to output.dir (every output's)
  int frames_listed = 0;              ///< frames of the input
  int frames_selected = 0;            ///< frames input.range selects (all shards together)
  std::string ground_truth;           ///< folder of a synthetic input's clean frames, or ""
  std::string config_hash;            ///< frame_config_hash
  std::vector<std::string> warnings;  ///< the plan's (template, range)
};

/// The header of a shard's report (report.shard-I-of-N.json), which keeps the plan's warnings
/// in "shard"."plan_warnings". Throws InputError naming the missing key.
ReportHeader report_header_from_json(const nlohmann::json& shard_report);

/// report.json: versions, the config, input and template of `header`, totals over `frames`,
/// ground truth errors (synthetic input), failures, `warnings` (the header's, the frames', the
/// output's), whether the run was `interrupted`, and `run` (timings) unless it is null.
nlohmann::json make_report(const ReportHeader& header, const std::vector<FrameSummary>& frames,
                           const std::vector<std::string>& warnings, bool interrupted,
                           const nlohmann::json& run);

/// The mean over `frames` of each frame's mean shear, before and after (report.json's
/// totals.shear_before.mean_of_means and shear_after.mean_of_means).
struct ShearMeans {
  double before = 0.0;
  double after = 0.0;
};
ShearMeans mean_shear(const std::vector<FrameSummary>& frames);

}  // namespace sm
