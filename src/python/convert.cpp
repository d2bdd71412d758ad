#include "python/convert.hpp"

#include <climits>
#include <cmath>
#include <cstring>

#include "core/errors.hpp"

namespace sm::python {
namespace {

std::string shape_text(const py::array& a) {
  std::string out = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d)
    out += (d ? ", " : "") + std::to_string(a.shape(d));
  return out + (a.ndim() == 1 ? ",)" : ")");
}

void check_rows_of_three(const py::array& a, const char* what, const char* rows) {
  if (a.size() == 0 && a.ndim() <= 2) return;  // an empty list: no rows
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw InputError(std::string(what) + ": expected an array of shape (" + rows +
                     ", 3), got shape " + shape_text(a));
}

std::string type_name(const py::handle& value) {
  return py::str(py::type::of(value).attr("__name__")).cast<std::string>();
}

std::string dtype_text(const py::array& a) {
  return py::str(a.dtype()).cast<std::string>();
}

// Complex values are no coordinates, weights or indices: numpy's cast would drop the imaginary
// part (with a warning at most).
void refuse_complex(const py::array& a, const std::string& what) {
  if (a.dtype().kind() == 'c')
    throw py::type_error(what + ": complex values (dtype " + dtype_text(a) +
                         ") are not accepted; pass the real part (numpy.real) if it is meant");
}

// `a` as a C-contiguous array of T, converted (copied) if need be. `a` holds numbers, so a copy
// that cannot be made is one that cannot be allocated (pybind11's ensure() returns null and
// clears the error): MemoryError, not a null array read.
template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> converted(const py::array& a,
                                                                    const std::string& what) {
  auto out = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!out) {
    const double bytes = double(a.size()) * double(sizeof(T));
    PyErr_SetString(PyExc_MemoryError,
                    (what + ": cannot allocate a converted copy of the array of shape " +
                     shape_text(a) + " (" + std::to_string(static_cast<long long>(bytes)) +
                     " bytes)")
                        .c_str());
    throw py::error_already_set();
  }
  return out;
}

}  // namespace

Positions to_positions(const py::handle& object, const char* what) {
  const auto not_numbers = [&] {
    return py::type_error(std::string(what) + ": expected an array of numbers of shape (n, 3), " +
                          "got a " + type_name(object));
  };
  if (object.is_none()) throw not_numbers();
  const py::array a = py::array::ensure(object);
  if (!a) throw not_numbers();
  refuse_complex(a, what);
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b' && kind != 'O')
    throw py::type_error(std::string(what) + ": expected an array of numbers, got dtype " +
                         dtype_text(a));
  check_rows_of_three(a, what, "n");
  DoubleArray array;
  if (kind == 'O') {  // Python objects: a cast that fails is a wrong value, not memory
    array = DoubleArray::ensure(a);
    if (!array)
      throw py::type_error(std::string(what) + ": an object array that is not numbers");
  } else {
    array = converted<double>(a, what);
  }
  Positions V(array.size() / 3, 3);
  if (V.size() > 0) std::memcpy(V.data(), array.data(), sizeof(double) * V.size());
  return V;
}

Triangles to_triangles(const py::handle& object, const char* what) {
  py::array a = py::array::ensure(object);
  if (!a) throw InputError(std::string(what) + ": expected an integer array of shape (m, 3)");
  refuse_complex(a, what);
  check_rows_of_three(a, what, "m");
  Triangles F(a.size() / 3, 3);
  if (F.size() == 0) return F;
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw InputError(std::string(what) + ": expected an integer array, got dtype " +
                     py::str(a.dtype()).cast<std::string>());
  if (a.dtype().is(py::dtype::of<int32_t>()) && (a.flags() & py::array::c_style)) {
    std::memcpy(F.data(), a.data(), sizeof(int) * F.size());
    return F;
  }
  // Any other integer type through int64 (uint64 values above INT64_MAX wrap to negative ones
  // and are refused below like every negative index).
  const auto wide = converted<int64_t>(a, what);
  const int64_t* p = wide.data();
  for (Eigen::Index i = 0; i < F.size(); ++i) {
    if (p[i] < 0 || p[i] > INT_MAX)
      throw InputError(std::string(what) + ": triangle " + std::to_string(i / 3) +
                       " has vertex index " + std::to_string(p[i]) + ", outside [0, " +
                       std::to_string(INT_MAX) + "]");
    F.data()[i] = static_cast<int>(p[i]);
  }
  return F;
}

std::vector<double> to_numbers(const py::handle& object, const std::string& path) {
  const bool sequence = py::isinstance<py::array>(object) || py::isinstance<py::list>(object) ||
                        py::isinstance<py::tuple>(object);
  if (!sequence)
    throw ConfigError(path + ": expected an array of numbers, got a " + type_name(object));
  py::array a = py::array::ensure(object);
  if (!a) throw ConfigError(path + ": expected an array of numbers");
  refuse_complex(a, path);
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b')
    throw ConfigError(path + ": expected an array of numbers, got dtype " +
                      py::str(a.dtype()).cast<std::string>());
  if (a.ndim() != 1)
    throw ConfigError(path + ": expected a 1-D array (one number per vertex), got shape " +
                      shape_text(a));
  const auto doubles = converted<double>(a, path);
  return std::vector<double>(doubles.data(), doubles.data() + doubles.size());
}

py::array_t<double> to_numpy(const Positions& V) {
  py::array_t<double> out({static_cast<py::ssize_t>(V.rows()), py::ssize_t{3}});
  if (V.size() > 0) std::memcpy(out.mutable_data(), V.data(), sizeof(double) * V.size());
  return out;
}

py::array_t<double> to_numpy(const Eigen::VectorXd& x) {
  py::array_t<double> out(static_cast<py::ssize_t>(x.size()));
  if (x.size() > 0) std::memcpy(out.mutable_data(), x.data(), sizeof(double) * x.size());
  return out;
}

namespace {

// The nesting the config reader accepts (io/json_text.cpp): a Python value nested deeper is refused
// as a config file would be, before the recursion below could exhaust the stack.
constexpr int kMaxDepth = 64;

// Where a value sits: its parent's place and its key or index. Built on the stack as the
// recursion goes; the path's text is made only for a message, so that converting a value costs
// time and memory linear in its size whatever its depth.
struct Place {
  const Place* parent = nullptr;
  const std::string* root = nullptr;  // the outermost place's path
  const std::string* key = nullptr;   // a dict item's key, else an index
  size_t index = 0;
  int depth = 0;                      // containers around this place

  std::string text() const {
    if (!parent) return *root;
    std::string path = parent->text();
    if (!key) return path + "[" + std::to_string(index) + "]";
    return path.empty() ? *key : path + "." + *key;
  }
  std::string label() const {
    const std::string path = text();
    return path.empty() ? std::string("config") : path;
  }
};

nlohmann::json value_to_json(const py::handle& value, const Place& at) {
  using nlohmann::json;
  if (value.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) {
    try {
      return value.cast<int64_t>();
    } catch (const py::cast_error&) {
      throw ConfigError(at.text() + ": the integer " + py::str(value).cast<std::string>() +
                        " is too large");
    }
  }
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  const bool dict = py::isinstance<py::dict>(value);
  if (dict || py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    if (at.depth >= kMaxDepth)
      throw ConfigError(at.label() + ": nested deeper than " + std::to_string(kMaxDepth) +
                        " levels");
    if (dict) {
      json out = json::object();
      for (const auto& [key, item] : value.cast<py::dict>()) {
        if (!py::isinstance<py::str>(key))
          throw ConfigError(at.text() + ": keys must be strings, got a " + type_name(key));
        const std::string name = key.cast<std::string>();
        const Place inner{&at, nullptr, &name, 0, at.depth + 1};
        out[name] = value_to_json(item, inner);
      }
      return out;
    }
    json out = json::array();
    size_t i = 0;
    for (const py::handle item : value) {
      const Place inner{&at, nullptr, nullptr, i++, at.depth + 1};
      out.push_back(value_to_json(item, inner));
    }
    return out;
  }
  // An array, a path, a numpy scalar (numpy.int64 is no int, numpy.bool_ no bool): its Python
  // value, one level further (an object whose item() returns itself ends at the cap too).
  const char* method = py::isinstance<py::array>(value)      ? "tolist"
                       : py::hasattr(value, "__fspath__")    ? "__fspath__"
                       : py::hasattr(value, "item") && py::hasattr(value, "dtype") ? "item"
                                                                                     : nullptr;
  if (method) {
    if (at.depth >= kMaxDepth)
      throw ConfigError(at.label() + ": nested deeper than " + std::to_string(kMaxDepth) +
                        " levels");
    Place same = at;
    ++same.depth;
    return value_to_json(value.attr(method)(), same);
  }
  throw ConfigError(at.label() +
                    ": expected a JSON value (dict, list, str, number, bool or None), got a " +
                    type_name(value));
}

}  // namespace

nlohmann::json to_json(const py::handle& value, const std::string& path) {
  const Place root{nullptr, &path, nullptr, 0, 0};
  return value_to_json(value, root);
}

nlohmann::json to_json(const py::kwargs& kwargs, const std::string& path) {
  return to_json(static_cast<const py::handle&>(kwargs), path);
}

py::object from_json(const nlohmann::json& value, bool non_finite_strings) {
  switch (value.type()) {
    case nlohmann::json::value_t::null:
      return py::none();
    case nlohmann::json::value_t::boolean:
      return py::bool_(value.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(value.get<int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(value.get<uint64_t>());
    case nlohmann::json::value_t::number_float:
      return py::float_(value.get<double>());
    case nlohmann::json::value_t::string: {
      const std::string& text = value.get_ref<const std::string&>();
      if (non_finite_strings && (text == "inf" || text == "-inf" || text == "nan"))
        return py::float_(text == "nan" ? NAN : text == "inf" ? INFINITY : -INFINITY);
      return py::str(text);
    }
    case nlohmann::json::value_t::array: {
      py::list out;
      for (const nlohmann::json& item : value) out.append(from_json(item, non_finite_strings));
      return std::move(out);
    }
    case nlohmann::json::value_t::object: {
      py::dict out;
      for (const auto& [key, item] : value.items())
        out[py::str(key)] = from_json(item, non_finite_strings);
      return std::move(out);
    }
    default:
      return py::none();  // binary and discarded values do not occur in the library's JSON
  }
}

}  // namespace sm::python
