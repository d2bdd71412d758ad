/// seqmassage.run_job(): the command line's job of a config, returning its report.
#include <signal.h>

#include <atomic>
#include <filesystem>
#include <variant>

#include "config/config.hpp"
#include "pipeline/mesh_job.hpp"
#include "pipeline/mesh_report.hpp"
#include "pipeline/report.hpp"
#include "pipeline/sequence_job.hpp"
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

// The sequence job as the command line runs it; Ctrl-C stops it the way SIGINT stops the
// command (the frames in flight are finished and written, the report records the
// interruption), then raises KeyboardInterrupt.
nlohmann::json run_sequence(const SequenceJobOptions& config) {
  nlohmann::json report;
  bool interrupted = false;
  {
    SigintAsCancel sigint;
    RunHooks hooks;
    hooks.cancel = sigint.flag();
    py::gil_scoped_release unlocked;
    const SequencePlan plan = plan_sequence_job(config);
    const SequenceResult result = run_sequence_job(plan, hooks);
    interrupted = result.interrupted;
    report = make_report(plan, result);
  }
  if (interrupted) {
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

}  // namespace

void bind_jobs(py::module_& m) {
  m.def(
      "run_job",
      [](const py::object& config) {
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
            [](const auto& options) {
              if constexpr (std::is_same_v<std::decay_t<decltype(options)>, SequenceJobOptions>)
                return run_sequence(options);
              else
                return run_mesh(options);
            },
            job);
        return from_json(report);
      },
      py::arg("config"),
      "run_job(config) -> dict: runs the job of a config, a dict (paths relative to the working "
      "directory) or the path of a JSON file (paths relative to its folder), as `seqmassage "
      "CONFIG.json` does, writing the same files, and returns its report (report.json). A "
      "sequence whose frames fail still returns: see the report's failures.");
}

}  // namespace sm::python
