#include "pipeline/report/report.hpp"

#include <oneapi/tbb/version.h>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "io/csv.hpp"
#include "core/errors.hpp"
#include "pipeline/report/report_json.hpp"
#include "pipeline/sequence/shard.hpp"

#ifndef SEQMASSAGE_VERSION
#error "SEQMASSAGE_VERSION must be defined by the build"
#endif

namespace sm {
using json = nlohmann::json;

std::vector<std::string> summary_columns(bool ground_truth) {
  std::vector<std::string> columns = {"frame",
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
                                      "time",
                                      "folded_triangles"};
  if (ground_truth)
    for (const char* part : {"", "tangential_", "normal_"})
      for (const char* what : {"mean_before", "max_before", "mean_after", "max_after"})
        columns.push_back(std::string("truth_") + part + what);
  return columns;
}

std::string format_summary_csv(const std::vector<FrameSummary>& frames, bool timings) {
  const bool truth = std::any_of(frames.begin(), frames.end(),
                                 [](const FrameSummary& f) { return f.ground_truth.has_value(); });
  CsvWriter csv(summary_columns(truth));
  for (const FrameSummary& f : frames) {
    csv.cell(f.frame).cell(f.file).cell(f.vertices).cell(f.triangles);
    csv.cell(f.shear_before.max).cell(f.shear_before.mean).cell(f.shear_before.p95);
    csv.cell(f.shear_after.max).cell(f.shear_after.mean).cell(f.shear_after.p95);
    csv.cell(f.out_to_in.max).cell(f.out_to_in.rms).cell(f.in_to_out.max).cell(f.in_to_out.rms);
    csv.cell(f.iterations).cell(timings ? f.seconds : 0.0);
    csv.cell(status_name(f.status)).cell(f.failure);
    if (f.time)
      csv.cell(*f.time);
    else
      csv.cell("");
    csv.cell(f.folded_triangles);
    if (truth) {
      const GroundTruthError g = f.ground_truth.value_or(GroundTruthError{});
      const CorrespondenceError &b = g.split_before, &a = g.split_after;
      for (double x : {g.mean_before, g.max_before, g.mean_after, g.max_after, b.tangential_mean,
                       b.tangential_max, a.tangential_mean, a.tangential_max, b.normal_mean,
                       b.normal_max, a.normal_mean, a.normal_max})
        csv.cell(x);
    }
    csv.end_row();
  }
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

void append_frame_warnings(const FrameSummary& f, OnFailure on_failure,
                           std::vector<std::string>& warnings) {
  const std::string who = frame_label(f.frame, f.file, f.time);
  for (const std::string& warning : f.warnings) warnings.push_back(who + ": " + warning);
  if (f.status == FrameStatus::Failed)
    warnings.push_back(who + " failed, " +
                       (on_failure == OnFailure::Skip ? "not written: " : "written unchanged: ") +
                       f.failure);
  if (f.folded_triangles > 0)
    warnings.push_back(who + ": " + std::to_string(f.folded_triangles) +
                       " triangles folded over (normal opposed to the input frame's)");
}

ReportHeader report_header_from_json(const json& r) {
  const auto need = [&](const json& j, const char* key, const char* where) -> const json& {
    if (!j.is_object() || !j.contains(key))
      throw InputError(std::string(where) + key + ": missing");
    return j.at(key);
  };
  try {
    ReportHeader h;
    h.versions = need(r, "versions", "");
    h.config = need(r, "config", "");
    h.input = need(r, "input", "");
    h.templ = need(r, "template", "");
    h.outputs = need(r, "outputs", "");
    h.outputs["summary"] = "summary.csv";  // a shard's own names are the run's
    if (h.outputs.contains("iterations")) h.outputs["iterations"] = "iterations.csv";
    const json& totals = need(r, "totals", "");
    h.frames_listed = need(totals, "frames_listed", "totals.").get<int>();
    h.frames_selected = need(totals, "frames_selected", "totals.").get<int>();
    if (r.contains("ground_truth"))
      h.ground_truth = need(r["ground_truth"], "folder", "ground_truth.").get<std::string>();
    h.config_hash = need(need(r, "hashes", ""), "config", "hashes.").get<std::string>();
    h.warnings =
        need(need(r, "shard", ""), "plan_warnings", "shard.").get<std::vector<std::string>>();
    return h;
  } catch (const json::exception& e) {
    throw InputError(std::string("wrong type: ") + e.what());
  }
}

namespace {

// "totals": frame counts, and the shear and distances over the frames.
json report_totals(const ReportHeader& header, const std::vector<FrameSummary>& frames) {
  int optimized = 0, unchanged = 0, failed = 0, iterations = 0;
  double mean_before = 0, mean_after = 0, p95_before = 0, p95_after = 0;
  double max_before = 0, max_after = 0, out_to_in = 0, in_to_out = 0;
  for (const FrameSummary& f : frames) {
    optimized += f.status == FrameStatus::Optimized;
    unchanged += f.status == FrameStatus::Template;
    failed += f.status == FrameStatus::Failed;
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
  const double n = std::max<size_t>(1, frames.size());
  return {{"frames_listed", header.frames_listed},
          {"frames_selected", header.frames_selected},
          {"frames_written", frames.size()},
          {"optimized", optimized},
          {"template_unchanged", unchanged},
          {"failed", failed},
          {"iterations", iterations},
          {"shear_before",
           {{"max", json_number(max_before)},
            {"mean_of_means", json_number(mean_before / n)},
            {"mean_of_p95", json_number(p95_before / n)}}},
          {"shear_after",
           {{"max", json_number(max_after)},
            {"mean_of_means", json_number(mean_after / n)},
            {"mean_of_p95", json_number(p95_after / n)}}},
          {"dist_out_to_in_max", json_number(out_to_in)},
          {"dist_in_to_out_max", json_number(in_to_out)},
          {"hausdorff_max", json_number(std::max(out_to_in, in_to_out))}};
}

json ground_truth_frame(int frame, const GroundTruthError& g) {
  const CorrespondenceError &b = g.split_before, &a = g.split_after;
  return {{"frame", frame},
          {"mean_before", json_number(g.mean_before)},
          {"max_before", json_number(g.max_before)},
          {"mean_after", json_number(g.mean_after)},
          {"max_after", json_number(g.max_after)},
          {"tangential_mean_before", json_number(b.tangential_mean)},
          {"tangential_max_before", json_number(b.tangential_max)},
          {"tangential_mean_after", json_number(a.tangential_mean)},
          {"tangential_max_after", json_number(a.tangential_max)},
          {"normal_mean_before", json_number(b.normal_mean)},
          {"normal_max_before", json_number(b.normal_max)},
          {"normal_mean_after", json_number(a.normal_mean)},
          {"normal_max_after", json_number(a.normal_max)}};
}

// "ground_truth": every frame's error against its clean frame and the means (over all frames).
json ground_truth_section(const std::string& folder, const std::vector<FrameSummary>& frames) {
  json list = json::array();
  double before = 0, after = 0, tangential_before = 0, tangential_after = 0, normal_before = 0,
         normal_after = 0;
  for (const FrameSummary& f : frames) {
    if (!f.ground_truth) continue;
    const GroundTruthError& g = *f.ground_truth;
    before += g.mean_before;
    after += g.mean_after;
    tangential_before += g.split_before.tangential_mean;
    tangential_after += g.split_after.tangential_mean;
    normal_before += g.split_before.normal_mean;
    normal_after += g.split_after.normal_mean;
    list.push_back(ground_truth_frame(f.frame, g));
  }
  const double n = std::max<size_t>(1, frames.size());
  return {{"folder", folder},
          {"unit", "mean edge length of the template"},
          {"what",
           "distance of every vertex to its position on the clean (undrifted) frame; "
           "tangential: its part along the clean surface (vertex normal), normal: off it"},
          {"mean_before", json_number(before / n)},
          {"mean_after", json_number(after / n)},
          {"tangential_mean_before", json_number(tangential_before / n)},
          {"tangential_mean_after", json_number(tangential_after / n)},
          {"normal_mean_before", json_number(normal_before / n)},
          {"normal_mean_after", json_number(normal_after / n)},
          {"frames", list}};
}

}  // namespace

json make_report(const ReportHeader& header, const std::vector<FrameSummary>& frames,
                 const std::vector<std::string>& warnings, bool interrupted, const json& run) {
  json r;
  r["versions"] = header.versions;
  r["config"] = header.config;
  r["input"] = header.input;
  r["template"] = header.templ;
  r["hashes"] = {{"config", header.config_hash},
                 {"template", header.templ.value("hash", std::string())}};
  r["totals"] = report_totals(header, frames);
  r["interrupted"] = interrupted;
  if (!header.ground_truth.empty())
    r["ground_truth"] = ground_truth_section(header.ground_truth, frames);
  json failures = json::array();
  for (const FrameSummary& f : frames)
    if (f.status == FrameStatus::Failed)
      failures.push_back({{"frame", f.frame}, {"file", f.file}, {"reason", f.failure}});
  r["failures"] = failures;
  r["warnings"] = warnings;
  r["outputs"] = header.outputs;
  if (!run.is_null()) r["run"] = run;
  return r;
}

ShearMeans mean_shear(const std::vector<FrameSummary>& frames) {
  ShearMeans m;
  for (const FrameSummary& f : frames) {
    m.before += f.shear_before.mean;
    m.after += f.shear_after.mean;
  }
  const double n = std::max<size_t>(1, frames.size());
  m.before /= n;
  m.after /= n;
  return m;
}

}  // namespace sm
