#include "python/convert.hpp"

#include <climits>
#include <cmath>
#include <cstring>

#include "mesh/errors.hpp"

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

}  // namespace

Positions to_positions(const DoubleArray& array, const char* what) {
  check_rows_of_three(array, what, "n");
  Positions V(array.size() / 3, 3);
  if (V.size() > 0) std::memcpy(V.data(), array.data(), sizeof(double) * V.size());
  return V;
}

Triangles to_triangles(const py::handle& object, const char* what) {
  py::array a = py::array::ensure(object);
  if (!a) throw InputError(std::string(what) + ": expected an integer array of shape (m, 3)");
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
  const auto wide = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
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
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b')
    throw ConfigError(path + ": expected an array of numbers, got dtype " +
                      py::str(a.dtype()).cast<std::string>());
  if (a.ndim() != 1)
    throw ConfigError(path + ": expected a 1-D array (one number per vertex), got shape " +
                      shape_text(a));
  const auto doubles = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
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

nlohmann::json to_json(const py::handle& value, const std::string& path) {
  using nlohmann::json;
  if (value.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) {
    try {
      return value.cast<int64_t>();
    } catch (const py::cast_error&) {
      throw ConfigError(path + ": the integer " + py::str(value).cast<std::string>() +
                        " is too large");
    }
  }
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) {
    json out = json::object();
    for (const auto& [key, item] : value.cast<py::dict>()) {
      if (!py::isinstance<py::str>(key))
        throw ConfigError(path + ": keys must be strings, got a " + type_name(key));
      const std::string name = key.cast<std::string>();
      out[name] = to_json(item, path.empty() ? name : path + "." + name);
    }
    return out;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    json out = json::array();
    size_t i = 0;
    for (const py::handle item : value)
      out.push_back(to_json(item, path + "[" + std::to_string(i++) + "]"));
    return out;
  }
  if (py::isinstance<py::array>(value)) return to_json(value.attr("tolist")(), path);
  if (py::hasattr(value, "__fspath__")) return to_json(value.attr("__fspath__")(), path);
  // numpy scalars (numpy.int64 is no int, numpy.bool_ no bool): their Python value.
  if (py::hasattr(value, "item") && py::hasattr(value, "dtype"))
    return to_json(value.attr("item")(), path);
  throw ConfigError((path.empty() ? std::string("config") : path) +
                    ": expected a JSON value (dict, list, str, number, bool or None), got a " +
                    type_name(value));
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
