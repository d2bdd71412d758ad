/// seqmassage.Massager: a Massager built once from a template, run on frames from any number of
/// Python threads at once (Massager::run is const and its state read-only; the GIL is released
/// while it runs).
#include <atomic>
#include <memory>
#include <optional>
#include <thread>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <oneapi/tbb/parallel_for.h>
#include <pybind11/stl.h>  // std::optional (Result.failure)

#include "io/options_json.hpp"
#include "io/vertex_weights.hpp"
#include "massage/iteration_fields.hpp"
#include "massage/massage.hpp"
#include "massage/massage_keys.hpp"
#include "core/errors.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"

namespace sm::python {
namespace {

namespace fs = std::filesystem;

py::dict iteration_dict(const IterationStats& it) {
  py::dict d;
  for (const IterationField& field : iteration_fields())
    if (field.writers & kPythonDict)
      std::visit([&](auto member) { d[field.name] = it.*member; }, field.member);
  return d;
}

// Result.iterations' docstring: the dict's keys.
const char* iterations_doc() {
  static const std::string doc = [] {
    std::string text = "one dict per outer iteration: ";
    const std::vector<const char*> names = iteration_field_names(kPythonDict);
    for (size_t k = 0; k < names.size(); ++k) text += (k ? ", " : "") + std::string(names[k]);
    return text;
  }();
  return doc.c_str();
}

// The result's positions as a numpy array that owns them (no copy).
py::array_t<double> take_positions(Positions&& V) {
  auto* owned = new Positions(std::move(V));
  py::capsule free_it(owned, [](void* p) { delete static_cast<Positions*>(p); });
  return py::array_t<double>({static_cast<py::ssize_t>(owned->rows()), py::ssize_t{3}},
                             owned->data(), free_it);
}

/// What Massager.run returns.
struct Result {
  py::array_t<double> vertices;
  bool ok = true;
  std::optional<std::string> failure;
  py::list iterations;
  bool stopped_early = false;
  int folded_triangles = 0;
  int target_fallback_vertices = 0;
  double seconds = 0.0;
};

Result to_result(MassageResult&& r) {
  Result out;
  out.ok = r.ok;
  if (!r.ok) out.failure = r.failure;
  for (const IterationStats& it : r.iterations) out.iterations.append(iteration_dict(it));
  out.stopped_early = r.stopped_early;
  out.folded_triangles = r.folded_triangles;
  out.target_fallback_vertices = r.target_fallback_vertices;
  out.seconds = r.seconds;
  out.vertices = take_positions(std::move(r.V));
  return out;
}

// vertex_weights given as numbers (a numpy array or a list) rather than a file: not for the
// config's reader, which takes a path.
bool weights_as_numbers(const py::handle& value) {
  return !value.is_none() && !py::isinstance<py::str>(value) && !py::isinstance<py::bytes>(value) &&
         !py::hasattr(value, "__fspath__");
}

// One frame as the sequence job runs it (pipeline/run/sequence_job.cpp): the frame is the reference,
// with the template's topology and a refit of its BVH; the start is the reference's copy of the
// positions. Massager.run(vertices) and Massager.run_many use this, so they agree bit for bit.
MassageResult run_frame(const Massager& engine, Positions V, const IterationObserver& observer) {
  const Reference ref(TriMesh{std::move(V), engine.triangles()}, engine.options().samples,
                      "vertices", engine.shared_topology(), &engine.template_bvh());
  return engine.run(ref.mesh().V, ref, observer);
}

// Thrown from an iteration observer to stop a run: Ctrl-C (a Python exception is then set) or
// another run of run_many stopped by it.
struct Stopped {};

// Ctrl-C between iterations: on the thread Python delivers signals to, each iteration takes the
// GIL and runs the signal handlers (PyErr_CheckSignals); KeyboardInterrupt (or whatever the
// handler raised) stops the run, and `stop` stops the other runs of a batch at their next
// iteration. The iterates are the observer's to see, not to change, so a run checked this way
// gives the same bits as one that is not.
class SignalCheck {
 public:
  SignalCheck() : main_(std::this_thread::get_id()) {
    const py::module_ threading = py::module_::import("threading");
    active_ = threading.attr("current_thread")().is(threading.attr("main_thread")());
  }
  // Throws Stopped if the run should stop.
  void operator()() {
    if (stop_) throw Stopped{};
    if (!active_ || std::this_thread::get_id() != main_) return;
    py::gil_scoped_acquire locked;
    if (PyErr_CheckSignals() != 0) {
      stop_ = true;
      error_.emplace();  // fetches the exception the handler raised
      throw Stopped{};
    }
  }
  // After the run(s), with the GIL: raises what a signal handler raised.
  void rethrow() {
    if (error_) {
      py::error_already_set e = std::move(*error_);
      error_.reset();
      throw e;
    }
  }

 private:
  std::thread::id main_;
  bool active_ = false;
  std::atomic<bool> stop_{false};
  std::optional<py::error_already_set> error_;
};

class PyMassager {
 public:
  PyMassager(const py::object& template_vertices, const py::handle& triangles,
             const py::kwargs& massage) {
    MassageOptions options;
    // A copy, from which vertex_weights as numbers is taken out.
    py::dict keys = massage.attr("copy")().cast<py::dict>();
    py::object numbers = py::none();
    if (keys.contains("vertex_weights") && weights_as_numbers(keys["vertex_weights"]))
      numbers = keys.attr("pop")("vertex_weights");
    // The config's reader on the config's "massage" object: the same keys, checks and messages.
    read_options(to_json(keys, "massage"), options, fs::current_path(), "massage");
    TriMesh templ{to_positions(template_vertices, "template_vertices"),
                  to_triangles(triangles, "triangles")};
    // The weights as the jobs take them: numbers directly (the Massager checks their count and
    // range, in the config's words), a file (relative to the working directory) read as the
    // config's.
    if (!numbers.is_none()) {
      options.vertex_weights = to_numbers(numbers, "massage.vertex_weights");
      // No numbers are no weights for the engine: refused, as a file holding none is.
      if (options.vertex_weights.empty())
        throw ConfigError("massage.vertex_weights: expected " + std::to_string(templ.V.rows()) +
                          " weights (one per template vertex), got 0");
    }
    else if (!options.vertex_weights_file.empty())
      options.vertex_weights = read_vertex_weights(
          options.vertex_weights_file, static_cast<int>(templ.V.rows()), "template_vertices");
    py::gil_scoped_release unlocked;
    engine_ = with_option_path("massage", [&] {
      return std::make_shared<const Massager>(templ, std::move(options), "template");
    });
  }

  Result run(const py::object& vertices, const py::object& reference,
             const py::object& on_iteration) const {
    const Massager& engine = *engine_;
    const SampleKind samples = engine.options().samples;
    std::optional<TriMesh> other;  // a reference mesh of its own (remesh use)
    if (!reference.is_none()) {
      if (!py::isinstance<py::tuple>(reference) && !py::isinstance<py::list>(reference))
        throw InputError("reference: expected None or a mesh (vertices, triangles)");
      const py::sequence mesh = reference.cast<py::sequence>();
      if (mesh.size() != 2)
        throw InputError("reference: expected a mesh (vertices, triangles), got " +
                         std::to_string(mesh.size()) + " items");
      other.emplace(TriMesh{to_positions(mesh[0], "reference vertices"),
                            to_triangles(mesh[1], "reference triangles")});
    }
    Positions start;
    if (other) start = to_positions(vertices, "vertices");
    TriMesh frame;  // the sequence use: the frame is its own reference
    if (!other) frame = TriMesh{to_positions(vertices, "vertices"), engine.triangles()};
    const Eigen::Index rows = other ? start.rows() : frame.V.rows();
    if (rows != engine.num_vertices())
      throw InputError("vertices: " + std::to_string(rows) + " rows, the template has " +
                       std::to_string(engine.num_vertices()) + " vertices");

    SignalCheck signals;
    IterationObserver observer = [&signals, &on_iteration](const IterationStats& stats,
                                                           const Positions& V) {
      if (!on_iteration.is_none()) {
        py::gil_scoped_acquire locked;
        on_iteration(iteration_dict(stats), to_numpy(V));
      }
      signals();
    };
    MassageResult result;
    try {
      py::gil_scoped_release unlocked;
      if (other) {
        // As the single-mesh jobs build theirs; with the template's triangles, as a frame's.
        const bool same =
            other->F.rows() == engine.triangles().rows() && other->F == engine.triangles();
        const Reference ref(std::move(*other), samples, "reference",
                            same ? engine.shared_topology() : nullptr,
                            same ? &engine.template_bvh() : nullptr);
        result = engine.run(start, ref, observer);
      } else {
        result = run_frame(engine, std::move(frame.V), observer);
      }
    } catch (const Stopped&) {
      signals.rethrow();
      throw;
    }
    return to_result(std::move(result));
  }

  // Many frames, in parallel (TBB; the GIL released): each exactly as run(frame) computes it.
  std::vector<Result> run_many(const py::object& frames) const {
    const Massager& engine = *engine_;
    std::vector<Positions> inputs;
    {
      const py::iterator it = py::iter(frames);
      for (const py::handle item : it) {
        const std::string what = "frames[" + std::to_string(inputs.size()) + "]";
        inputs.push_back(to_positions(item, what.c_str()));
        if (inputs.back().rows() != engine.num_vertices())
          throw InputError(what + ": " + std::to_string(inputs.back().rows()) +
                           " rows, the template has " + std::to_string(engine.num_vertices()) +
                           " vertices");
      }
    }
    std::vector<MassageResult> results(inputs.size());
    SignalCheck signals;
    const IterationObserver observer = [&signals](const IterationStats&, const Positions&) {
      signals();
    };
    try {
      py::gil_scoped_release unlocked;
      tbb::parallel_for(size_t{0}, inputs.size(), [&](size_t k) {
        results[k] = run_frame(engine, std::move(inputs[k]), observer);
      });
    } catch (const Stopped&) {
      signals.rethrow();
      throw;
    }
    std::vector<Result> out;
    out.reserve(results.size());
    for (MassageResult& r : results) out.push_back(to_result(std::move(r)));
    return out;
  }

  int num_vertices() const { return engine_->num_vertices(); }
  int num_triangles() const { return static_cast<int>(engine_->triangles().rows()); }
  // Every key in table order, as the config writes it.
  py::dict options() const {
    MassageOptions copy = engine_->options();
    py::dict out;
    for (const Entry& e : entries_of(copy))
      if (const std::optional<nlohmann::json> value = write_value(e))
        out[py::str(std::string(e.info->key))] = from_json(*value);
    return out;
  }

 private:
  std::shared_ptr<const Massager> engine_;
};

}  // namespace

void bind_massager(py::module_& m) {
  py::class_<Result>(m, "Result", "What Massager.run returns.")
      .def_readonly("vertices", &Result::vertices,
                    "optimized positions (n×3 float64); the start positions if not ok")
      .def_readonly("ok", &Result::ok, "False: numerical failure, see failure")
      .def_readonly("failure", &Result::failure, "why the run failed, or None")
      .def_readonly("iterations", &Result::iterations,
                    iterations_doc())
      .def_readonly("stopped_early", &Result::stopped_early,
                    "the movement tolerance was met before the last iteration")
      .def_readonly("folded_triangles", &Result::folded_triangles,
                    "triangles whose normal opposes the reference's where they land")
      .def_readonly("target_fallback_vertices", &Result::target_fallback_vertices,
                    "with shape_target \"template\": vertices that keep the target 0")
      .def_readonly("seconds", &Result::seconds, "wall time of the run")
      .def("__repr__", [](const Result& r) {
        return "<seqmassage.Result ok=" + std::string(r.ok ? "True" : "False") +
               " iterations=" + std::to_string(py::len(r.iterations)) + ">";
      });

  py::class_<PyMassager>(m, "Massager",
                         "The optimizer for one template: built once, run on any number of "
                         "frames, from several threads at once.")
      .def(py::init<const py::object&, const py::handle&, const py::kwargs&>(),
           py::arg("template_vertices"), py::arg("triangles"),
           "Massager(template_vertices, triangles, **massage): n×3 float64 positions and m×3 "
           "integer triangles of the template T; the keyword arguments are the keys of the "
           "config's \"massage\" object (massage_keys()), checked the same way (ValueError).")
      .def("run", &PyMassager::run, py::arg("vertices"), py::arg("reference") = py::none(),
           py::arg("on_iteration") = py::none(),
           "run(vertices, reference=None, on_iteration=None) -> Result: optimizes the mesh with "
           "the template's triangles starting at `vertices` (n×3); the reference surface is the "
           "frame itself (None, the sequence job's use) or a mesh (vertices, triangles) (the "
           "remesh job's use). on_iteration(stats, vertices), if given, is called after every "
           "iteration. The GIL is released while it runs; Ctrl-C stops it between iterations "
           "(KeyboardInterrupt).")
      .def("run_many", &PyMassager::run_many, py::arg("frames"),
           "run_many(frames) -> list[Result]: run(frame) for every frame of `frames` (an "
           "iterable of n×3 arrays, or an F×n×3 array), in parallel on TBB's threads with the "
           "GIL released; each result is bit for bit the one run(frame) returns. Ctrl-C stops "
           "the batch between iterations (KeyboardInterrupt).")
      .def_property_readonly("num_vertices", &PyMassager::num_vertices,
                             "vertices of the template (rows of every frame)")
      .def_property_readonly("num_triangles", &PyMassager::num_triangles,
                             "triangles of the template")
      .def_property_readonly("options", &PyMassager::options,
                             "every massage key with its value, as a dict");
}

}  // namespace sm::python
