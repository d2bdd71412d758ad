#include "pipeline/report.hpp"

#include <oneapi/tbb/version.h>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "io/csv.hpp"

#ifndef SEQMASSAGE_VERSION
#error "SEQMASSAGE_VERSION must be defined by the build"
#endif

namespace sm {
using json = nlohmann::json;

namespace {

// Finite numbers as JSON numbers; infinity and NaN as the strings CSV uses ("inf", "nan").
json number(double x) {
  return std::isfinite(x) ? json(x) : json(format_number(x));
}

}  // namespace

std::vector<std::string> summary_columns() {
  return {"frame",
          "file",
          "vertices",
          "triangles",
          "shear_max_before",
          "shear_mean_before",
          "shear_p95_before",
          "shear_max_after",
          "shear_mean_after",
          "shear_p95_after",
          "dist_out_to_in_max",
          "dist_out_to_in_rms",
          "dist_in_to_out_max",
          "dist_in_to_out_rms",
          "iterations",
          "seconds",
          "status",
          "failure",
          "time"};
}

std::string format_summary_csv(const std::vector<FrameSummary>& frames, bool timings) {
  CsvWriter csv(summary_columns());
  for (const FrameSummary& f : frames) {
    csv.cell(f.frame).cell(f.file).cell(f.vertices).cell(f.triangles);
    csv.cell(f.shear_before.max).cell(f.shear_before.mean).cell(f.shear_before.p95);
    csv.cell(f.shear_after.max).cell(f.shear_after.mean).cell(f.shear_after.p95);
    csv.cell(f.out_to_in.max).cell(f.out_to_in.rms).cell(f.in_to_out.max).cell(f.in_to_out.rms);
    csv.cell(f.iterations).cell(timings ? f.seconds : 0.0);
    csv.cell(status_name(f.status)).cell(f.failure);
    if (f.time) csv.cell(*f.time);
    csv.end_row();
  }
  return csv.str();
}

std::string format_distortion_csv(const Eigen::VectorXd& before, const Eigen::VectorXd& after) {
  CsvWriter csv({"triangle", "shear_before", "shear_after"});
  for (Eigen::Index t = 0; t < before.size(); ++t)
    csv.cell(static_cast<int64_t>(t)).cell(before[t]).cell(after[t]).end_row();
  return csv.str();
}

json version_info() {
#if defined(__clang__)
  const std::string compiler = "clang " __clang_version__;
#elif defined(__GNUC__)
  const std::string compiler = "gcc " __VERSION__;
#else
  const std::string compiler = "unknown";
#endif
  const auto dotted = [](int a, int b) { return std::to_string(a) + "." + std::to_string(b); };
  return {{"seqmassage", SEQMASSAGE_VERSION},
          {"eigen", dotted(EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION) + "." +
                        std::to_string(EIGEN_MINOR_VERSION)},
          {"onetbb", dotted(TBB_VERSION_MAJOR, TBB_VERSION_MINOR)},
          {"nlohmann_json", dotted(NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR) + "." +
                                std::to_string(NLOHMANN_JSON_VERSION_PATCH)},
          {"compiler", compiler}};
}

json make_report(const SequencePlan& plan, const SequenceResult& result) {
  const JobConfig& c = plan.config;
  json r;
  r["versions"] = version_info();
  r["config"] = to_json(c);
  r["input"] = plan.source->report();
  r["template"] = {{"source", plan.template_source},
                   {"vertices", plan.templ.num_vertices()},
                   {"triangles", plan.templ.num_triangles()},
                   {"weight_fallback_vertices", plan.massager->weights().fallback_vertices}};

  int optimized = 0, unchanged = 0, iterations = 0;
  double mean_before = 0, mean_after = 0, p95_before = 0, p95_after = 0;
  double max_before = 0, max_after = 0, out_to_in = 0, in_to_out = 0;
  for (const FrameSummary& f : result.frames) {
    optimized += f.status == FrameStatus::Optimized;
    unchanged += f.status == FrameStatus::Template;
    iterations += f.iterations;
    mean_before += f.shear_before.mean;
    mean_after += f.shear_after.mean;
    p95_before += f.shear_before.p95;
    p95_after += f.shear_after.p95;
    max_before = std::max(max_before, f.shear_before.max);
    max_after = std::max(max_after, f.shear_after.max);
    out_to_in = std::max(out_to_in, f.out_to_in.max);
    in_to_out = std::max(in_to_out, f.in_to_out.max);
  }
  const double n = std::max<size_t>(1, result.frames.size());
  r["totals"] = {{"frames_listed", plan.source->size()},
                 {"frames_selected", plan.selected.size()},
                 {"frames_written", result.frames.size()},
                 {"optimized", optimized},
                 {"template_unchanged", unchanged},
                 {"failed", result.failed},
                 {"iterations", iterations},
                 {"shear_before",
                  {{"max", number(max_before)},
                   {"mean_of_means", number(mean_before / n)},
                   {"mean_of_p95", number(p95_before / n)}}},
                 {"shear_after",
                  {{"max", number(max_after)},
                   {"mean_of_means", number(mean_after / n)},
                   {"mean_of_p95", number(p95_after / n)}}},
                 {"dist_out_to_in_max", number(out_to_in)},
                 {"dist_in_to_out_max", number(in_to_out)},
                 {"hausdorff_max", number(std::max(out_to_in, in_to_out))}};
  r["interrupted"] = result.interrupted;

  if (const std::filesystem::path truth = plan.source->ground_truth_dir(); !truth.empty()) {
    json frames = json::array();
    double before = 0, after = 0;
    for (const FrameSummary& f : result.frames) {
      if (!f.ground_truth) continue;
      const GroundTruthError& g = *f.ground_truth;
      before += g.mean_before;
      after += g.mean_after;
      frames.push_back({{"frame", f.frame},
                        {"mean_before", number(g.mean_before)},
                        {"max_before", number(g.max_before)},
                        {"mean_after", number(g.mean_after)},
                        {"max_after", number(g.max_after)}});
    }
    r["ground_truth"] = {
        {"folder", truth.string()},
        {"unit", "mean edge length of the template"},
        {"what", "distance of every vertex to its position on the clean (undrifted) frame"},
        {"mean_before", number(before / n)},
        {"mean_after", number(after / n)},
        {"frames", frames}};
  }

  json failures = json::array();
  for (const FrameSummary& f : result.frames)
    if (f.status == FrameStatus::Failed)
      failures.push_back({{"frame", f.frame}, {"file", f.file}, {"reason", f.failure}});
  r["failures"] = failures;
  r["warnings"] = result.warnings;
  r["outputs"] = {{"dir", c.output.dir.string()},
                  {"distortion", c.output.per_triangle_csv ? json("distortion/") : json(nullptr)},
                  {"summary", "summary.csv"}};
  r["outputs"].update(plan.sink->report());
  if (c.output.timings)
    r["run"] = {
        {"threads", plan.threads},
        {"frames_in_flight", plan.frames_in_flight},
        {"seconds", result.seconds},
        {"frames_per_second", result.seconds > 0 ? result.frames.size() / result.seconds : 0.0}};
  return r;
}

}  // namespace sm
