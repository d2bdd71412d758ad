#pragma once
/// The parts of the Python module `seqmassage` (internal to src/python), each adding its
/// functions and classes to the module; module.cpp calls them in order.
#include <pybind11/pybind11.h>

namespace sm::python {

/// The exception classes: ConfigError and InputError (ValueError), IoError (OSError),
/// SolverError (RuntimeError), and the translation of the library's exceptions into them.
void bind_errors(pybind11::module_& m);
/// Massager and Result.
void bind_massager(pybind11::module_& m);
/// massage_keys() and measure_keys(): the options tables as data.
void bind_keys(pybind11::module_& m);
/// shear() and distances().
void bind_measures(pybind11::module_& m);
/// run_job().
void bind_jobs(pybind11::module_& m);
/// read_point_cache(), write_point_cache() and PointCache.
void bind_point_caches(pybind11::module_& m);
/// Tracker (frames of any connectivity).
void bind_tracker(pybind11::module_& m);

}  // namespace sm::python
