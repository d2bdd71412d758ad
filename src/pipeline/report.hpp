#pragma once
/// The tables and the report of a sequence job: summary.csv (one row per frame),
/// distortion/<frame>.csv (one row per triangle) and report.json.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "pipeline/sequence_job.hpp"

namespace sm {

/// The columns of summary.csv: frame, file, vertices, triangles, shear_{max,mean,p95}_{before,
/// after}, dist_out_to_in_{max,rms}, dist_in_to_out_{max,rms}, iterations, seconds, then status,
/// failure and time (seconds into the animation for glTF input, empty otherwise).
std::vector<std::string> summary_columns();

/// summary.csv, one row per frame in order. Without `timings`, the seconds column holds 0.
std::string format_summary_csv(const std::vector<FrameSummary>& frames, bool timings);

/// distortion/<frame>.csv: `triangle,shear_before,shear_after`, one row per triangle (0-based).
std::string format_distortion_csv(const Eigen::VectorXd& before, const Eigen::VectorXd& after);

/// Program and library versions: seqmassage, Eigen, oneTBB, nlohmann-json, compiler.
nlohmann::json version_info();

/// report.json: the resolved config, versions, template, totals over the frames, ground truth
/// errors (synthetic input), failures, warnings and, with timings, the run time.
nlohmann::json make_report(const SequencePlan& plan, const SequenceResult& result);

}  // namespace sm
