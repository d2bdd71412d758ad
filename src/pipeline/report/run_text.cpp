#include "pipeline/report/run_text.hpp"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "pipeline/report/report.hpp"
#include "pipeline/sequence/shard.hpp"
#include "massage/massage_keys.hpp"

namespace sm {

namespace {

// Frames per second and the seconds left after `done` of `total` frames in `elapsed` seconds.
std::pair<double, double> rate_and_eta(int done, int total, double elapsed) {
  const double rate = elapsed > 0 ? done / elapsed : 0.0;
  return {rate, rate > 0 ? (total - done) / rate : -1.0};
}

}  // namespace

std::string fixed_text(double x, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, x);
  return buffer;
}

std::string clock_text(double seconds) {
  if (!(seconds >= 0) || seconds > 359999) return "--:--";
  const long s = static_cast<long>(seconds + 0.5);
  char buffer[32];
  if (s >= 3600)
    std::snprintf(buffer, sizeof buffer, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(buffer, sizeof buffer, "%ld:%02ld", s / 60, s % 60);
  return buffer;
}

std::string run_start_text(const SequencePlan& plan) {
  std::string text = std::to_string(plan.run_frames.size()) + " frames";
  if (plan.config.shard.sharded())
    text += " (" + shard_label(plan.config.shard) + " of " + std::to_string(plan.selected.size()) +
            " selected)";
  return text + ", template " + plan.template_source + ", " + std::to_string(plan.threads) +
         " threads" + (plan.config.resume ? ", resuming" : "");
}

std::string frame_progress_text(const FrameSummary& f, int done, int total, double elapsed) {
  const auto [rate, eta] = rate_and_eta(done, total, elapsed);
  return "frame " + std::to_string(done) + "/" + std::to_string(total) + " " + f.file + ": " +
         status_name(f.status) + (f.resumed ? " (kept from an earlier run)" : "") +
         ", mean shear " + fixed_text(f.shear_before.mean, 4) + " -> " +
         fixed_text(f.shear_after.mean, 4) + ", " + std::to_string(f.iterations) + " iterations, " +
         fixed_text(rate, 2) + " frames/s, ETA " + clock_text(eta);
}

std::string progress_bar_text(int done, int total, double elapsed) {
  const auto [rate, eta] = rate_and_eta(done, total, elapsed);
  const int width = 30;
  const int filled = total > 0 ? width * done / total : width;
  return "[" + std::string(filled, '#') + std::string(width - filled, '.') + "] " +
         std::to_string(done) + "/" + std::to_string(total) + " frames  " + fixed_text(rate, 2) +
         " frames/s  ETA " + clock_text(eta);
}

std::string frame_failure_text(const FrameSummary& f, OnFailure on_failure) {
  return "frame " + std::to_string(f.frame) + " (" + f.file + ") failed, " +
         (on_failure == OnFailure::Skip ? "not written" : "written unchanged") +
         (f.resumed ? " (in an earlier run)" : "") + ": " + f.failure;
}

std::string resume_text(const SequenceResult& result) {
  std::string why;
  for (const auto& [reason, count] : result.redone)
    why += (why.empty() ? "" : ", ") + std::to_string(count) + " " + reason;
  return "resume: " + std::to_string(result.resumed) + " frames kept from earlier runs, " +
         std::to_string(result.frames.size() - size_t(result.resumed)) + " processed" +
         (why.empty() ? "" : " (" + why + ")");
}

std::string run_end_text(const SequenceResult& result) {
  const ShearMeans shear = mean_shear(result.frames);
  return std::to_string(result.frames.size()) + " frames in " + fixed_text(result.seconds, 1) +
         " s (" + std::to_string(result.failed) + " failed), mean shear " +
         fixed_text(shear.before, 4) + " -> " + fixed_text(shear.after, 4);
}

std::string massage_text(const MassageOptions& m) {
  return std::string(name_of(m.weights, kWeightKindNames)) + " weights, " +
         std::to_string(m.iterations) + " iterations, mu " +
         (m.mu ? nlohmann::json(*m.mu).dump() : "auto") + ", samples " +
         std::string(name_of(m.samples, kSampleKindNames)) + ", solver " +
         std::string(name_of(m.solver, kSolverKindNames));
}

}  // namespace sm
