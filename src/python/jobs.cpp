/// seqmassage.run_job(): the command line's job of a config, returning its report.
#include <signal.h>

#include <atomic>
#include <filesystem>
#include <optional>
#include <variant>

#include "config/config.hpp"
#include "pipeline/cluster/frame_record.hpp"
#include "pipeline/mesh_jobs/mesh_job.hpp"
#include "pipeline/mesh_jobs/mesh_report.hpp"
#include "pipeline/report/report.hpp"
#include "pipeline/run/sequence_report.hpp"
#include "pipeline/run/sequence_job.hpp"
#include "pipeline/track/track_job.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"

namespace sm::python {
namespace {

namespace fs = std::filesystem;

std::atomic<bool> g_cancel{false};

extern "C" void on_sigint(int) {
  g_cancel.store(true);
}

// SIGINT handled as the command line handles it, while a job runs on Python's main thread (where
// Python delivers signals): the previous handler (Python's) comes back afterwards.
class SigintAsCancel {
 public:
  SigintAsCancel() {
    const py::module_ threading = py::module_::import("threading");
    active_ = threading.attr("current_thread")().is(threading.attr("main_thread")());
    if (!active_) return;
    g_cancel = false;
    struct sigaction action {};
    action.sa_handler = on_sigint;
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGINT, &action, &previous_);
  }
  ~SigintAsCancel() {
    if (active_) ::sigaction(SIGINT, &previous_, nullptr);
  }
  SigintAsCancel(const SigintAsCancel&) = delete;
  SigintAsCancel& operator=(const SigintAsCancel&) = delete;
  const std::atomic<bool>* flag() const { return active_ ? &g_cancel : nullptr; }

 private:
  bool active_ = false;
  struct sigaction previous_ {};
};

// run_job's progress callback, called per frame as the job writes them (in frame order, one at a
// time, with the GIL): progress(frame, status, figures). It cancels the job by returning False
// or raising; the exception is raised again once the frames in flight are written.
class ProgressCallback {
 public:
  explicit ProgressCallback(py::object callback) : callback_(std::move(callback)) {}

  bool given() const { return !callback_.is_none(); }
  bool cancelled() const { return cancel_; }

  void operator()(const FrameSummary& frame, int done, int total, double elapsed) {
    py::gil_scoped_acquire locked;
    if (cancel_) return;  // cancelled already: the frames in flight still arrive
    try {
      py::dict figures = from_json(to_json(frame), true).cast<py::dict>();
      figures["done"] = done;
      figures["total"] = total;
      figures["elapsed_seconds"] = elapsed;
      const py::object answer =
          callback_(frame.frame, std::string(status_name(frame.status)), figures);
      if (!answer.is_none() && !answer.cast<bool>()) cancel_ = true;
    } catch (py::error_already_set& e) {
      error_ = std::move(e);
      cancel_ = true;
    }
  }

  /// Raises what the callback raised, if it did.
  void rethrow() {
    if (error_) {
      py::error_already_set e = std::move(*error_);
      error_.reset();
      throw e;
    }
  }

 private:
  py::object callback_;
  std::atomic<bool> cancel_{false};
  std::optional<py::error_already_set> error_;
};

// The sequence job as the command line runs it; Ctrl-C stops it the way SIGINT stops the
// command (the frames in flight are finished and written, the report records the
// interruption), then raises KeyboardInterrupt. A progress callback that cancels stops it the
// same way; run_job then returns the report (its "interrupted" says so).
nlohmann::json run_sequence(const SequenceJobOptions& config, const py::object& callback) {
  nlohmann::json report;
  bool interrupted = false;
  ProgressCallback progress(callback);
  {
    SigintAsCancel sigint;
    // The one flag the job polls: SIGINT's (on the main thread) or a local one; the callback's
    // cancel sets it too.
    std::atomic<bool> local{false};
    std::atomic<bool>& stop = sigint.flag() ? g_cancel : local;
    RunHooks hooks;
    hooks.cancel = &stop;
    if (progress.given())
      hooks.progress = [&](const FrameSummary& f, int done, int total, double elapsed) {
        progress(f, done, total, elapsed);
        if (progress.cancelled()) stop = true;
      };
    py::gil_scoped_release unlocked;
    const SequencePlan plan = plan_sequence_job(config);
    const SequenceResult result = run_sequence_job(plan, hooks);
    interrupted = result.interrupted;
    report = make_report(plan, result);
  }
  progress.rethrow();
  if (interrupted && !progress.cancelled()) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  return report;
}

nlohmann::json run_mesh(const MeshJobOptions& config) {
  py::gil_scoped_release unlocked;
  const MeshJobPlan plan = plan_mesh_job(config);
  return make_mesh_report(plan, run_mesh_job(plan));
}

// The track job; its frames are not reported through progress.
nlohmann::json run_track(const TrackJobOptions& config) {
  py::gil_scoped_release unlocked;
  const TrackPlan plan = plan_track_job(config);
  return make_track_report(plan, run_track_job(plan));
}

}  // namespace

void bind_jobs(py::module_& m) {
  m.def(
      "run_job",
      [](const py::object& config, const py::object& progress) {
        AnyJobOptions job;
        if (py::isinstance<py::dict>(config)) {
          // Relative paths resolve against the working directory (a file's: against its folder).
          job = parse_any_config(to_json(config, ""), fs::current_path());
        } else {
          const fs::path path = py::str(py::module_::import("os").attr("fspath")(config))
                                    .cast<std::string>();
          py::gil_scoped_release unlocked;
          job = load_any_config(path);
        }
        const nlohmann::json report = std::visit(
            [&progress](const auto& options) {
              using T = std::decay_t<decltype(options)>;
              if constexpr (std::is_same_v<T, SequenceJobOptions>)
                return run_sequence(options, progress);
              else if constexpr (std::is_same_v<T, TrackJobOptions>)
                return run_track(options);
              else
                return run_mesh(options);
            },
            job);
        return from_json(report);
      },
      py::arg("config"), py::arg("progress") = py::none(),
      "run_job(config, progress=None) -> dict: runs the job of a config, a dict (paths relative "
      "to the working directory) or the path of a JSON file (paths relative to its folder), as "
      "`seqmassage CONFIG.json` does, writing the same files, and returns its report "
      "(report.json). A sequence whose frames fail still returns: see the report's failures.\n\n"
      "progress(frame, status, figures), if given, is called for each frame of a sequence as it "
      "is written, in frame order: the frame's index, its status (\"optimized\", \"failed\", "
      "...) and its figures (the frame's record: shear_before, shear_after, distances, "
      "iterations, seconds, ... and done, total, elapsed_seconds). Returning False cancels the "
      "job: no further frame starts, the frames in flight are written, and the report (with "
      "\"interrupted\") is returned; an exception raised by the callback cancels it the same "
      "way and is raised again. Ctrl-C stops it likewise and raises KeyboardInterrupt. Mesh "
      "jobs (one mesh) do not call it.");
}

}  // namespace sm::python
