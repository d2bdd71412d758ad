/// The Python module `seqmassage`: the optimizer, the measures and the jobs of the library on
/// numpy arrays and dicts (docs/python.md). With cli/, the only place that catches the library's
/// exceptions: bind_errors maps them onto Python's.
#include <pybind11/pybind11.h>

#include "core/errors.hpp"
#include "pipeline/report/report.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"

namespace sm::python {

void bind_errors(py::module_& m) {
  // Translators are tried from the last registered one; the four classes are siblings, so the
  // order does not matter. Any other std::exception becomes a RuntimeError (pybind11's default).
  auto config_error = py::register_exception<ConfigError>(m, "ConfigError", PyExc_ValueError);
  config_error.attr("__doc__") =
      "A key or value of **massage, **measures or a config: unknown key, wrong type, out of range "
      "(the message names the key).";
  // The module names the path of every option it passes on (with_option_path); should one reach
  // Python without it, it is still a ConfigError.
  py::register_exception<OptionError>(m, "OptionError", config_error.ptr())
      .attr("__doc__") = "A ConfigError naming an option's member without its config path.";
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError)
      .attr("__doc__") = "A malformed mesh, array, frame or input file (the message names it).";
  py::register_exception<IoError>(m, "IoError", PyExc_OSError)
      .attr("__doc__") = "A file or folder that cannot be read or written.";
  py::register_exception<SolverError>(m, "SolverError", PyExc_RuntimeError)
      .attr("__doc__") = "An internal numerical failure.";
}

}  // namespace sm::python

PYBIND11_MODULE(seqmassage, m) {
  namespace py = pybind11;
  m.doc() =
      "Mesh Massage (Winkler, Hormann, Gotsman): move a mesh's vertices so its triangles take a "
      "template's shapes while it stays on a reference surface. See docs/python.md.";
  sm::python::bind_errors(m);
  sm::python::bind_massager(m);
  sm::python::bind_keys(m);
  sm::python::bind_measures(m);
  sm::python::bind_jobs(m);
  sm::python::bind_point_caches(m);
  sm::python::bind_tracker(m);
  const nlohmann::json versions = sm::version_info();
  m.attr("__version__") = versions["seqmassage"].get<std::string>();
  m.attr("versions") = sm::python::from_json(versions);
}
