#pragma once
/// The Python module's conversions (internal to src/python): numpy arrays to the library's mesh
/// types and back, Python values to JSON (the config reader's input) and back.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "mesh/mesh.hpp"

namespace sm::python {

namespace py = pybind11;

/// A C-contiguous float64 array; pybind11 converts (copies) only an array of another layout or
/// dtype, or a nested list.
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// `object` (n×3 numbers: an array of any real dtype, or nested lists) as positions: one copy
/// into the library's matrix, which owns its data (the engine keeps the meshes it is given).
/// Throws InputError naming `what` for another shape; TypeError for complex values (their
/// imaginary part would be lost) or anything that is not numbers; MemoryError when a converted
/// copy (float64, C order) cannot be allocated.
Positions to_positions(const py::handle& object, const char* what);

/// `object` (m×3, any integer dtype; int32 C-contiguous is read in place) as triangles. Throws
/// InputError naming `what` for another shape, a non-integer dtype or an index outside
/// [0, 2^31 − 1] (validate_mesh checks it against the vertex count); TypeError for complex values,
/// MemoryError when a converted copy cannot be allocated.
Triangles to_triangles(const py::handle& object, const char* what);

/// `object` (a 1-D array or list of numbers: integers, floats or booleans) as doubles, copied.
/// Throws ConfigError "<path>: expected ..., got ..." (the config reader's style) for another
/// shape or dtype, TypeError for complex values, MemoryError when the copy cannot be allocated.
std::vector<double> to_numbers(const py::handle& object, const std::string& path);

/// A new numpy array (n×3 float64) holding a copy of `V`.
py::array_t<double> to_numpy(const Positions& V);
/// A new numpy array (n float64) holding a copy of `x`.
py::array_t<double> to_numpy(const Eigen::VectorXd& x);

/// A Python value as JSON: dict (str keys), list, tuple, str, bool, int, float, None, a numpy
/// array or scalar (through tolist()/item()), an os.PathLike (its path). Throws ConfigError
/// "<path>: ..." for anything else, and "<path>: nested deeper than 64 levels" as the config
/// reader does (the keyword arguments' dict is the first level). Paths are built only for a
/// message: time and memory are linear in the value's size.
nlohmann::json to_json(const py::handle& value, const std::string& path);
/// Keyword arguments as a JSON object.
nlohmann::json to_json(const py::kwargs& kwargs, const std::string& path);

/// JSON as a Python value (objects as dicts in key order, arrays as lists). With
/// `non_finite_strings`, the strings "inf", "-inf" and "nan" (report_json.hpp's json_number) are
/// floats again.
py::object from_json(const nlohmann::json& value, bool non_finite_strings = false);

}  // namespace sm::python
