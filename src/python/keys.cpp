/// massage_keys() and measure_keys(): the options tables (core/options_table.hpp) as data, for
/// user interfaces built from them (the Blender add-on's panel): every key's name, type, default,
/// range and doc, in table order.
#include <cmath>
#include <string>
#include <variant>

#include "io/options_json.hpp"
#include "massage/massage.hpp"
#include "core/key_type.hpp"
#include "massage/massage_keys.hpp"
#include "geometry/measure_keys.hpp"
#include "geometry/measures.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"

namespace sm::python {
namespace {

py::object bound(double x) {
  return std::isfinite(x) ? py::object(py::float_(x)) : py::object(py::none());
}

py::list keys_as_data(const Entries& entries) {
  py::list out;
  for (const Entry& e : entries) {
    const ValueSpec& s = e.info->spec;
    const KeyType type = key_type(e);
    py::dict d;
    d["name"] = std::string(e.info->key);
    d["type"] = std::string(type.name);
    const std::optional<nlohmann::json> value = write_value(e);
    d["default"] = value ? from_json(*value) : py::object(py::none());
    py::list choices;
    for (const auto& [name, index] : s.names) choices.append(std::string(name));
    d["choices"] = s.names.empty() ? py::object(py::none()) : py::object(choices);
    d["min"] = type.bounded ? bound(s.lo) : py::object(py::none());
    d["max"] = type.bounded ? bound(s.hi) : py::object(py::none());
    d["min_exclusive"] = type.bounded && s.lo_open;
    d["max_exclusive"] = type.bounded && s.hi_open;
    d["range"] = type.accepts + (type.nullable ? " or None" : "");
    d["doc"] = std::string(e.info->doc);
    out.append(d);
  }
  return out;
}

std::string type_names() {
  std::string out;
  for (std::string_view name : kKeyTypeNames) out += (out.empty() ? "" : ", ") + std::string(name);
  return out;
}

}  // namespace

void bind_keys(py::module_& m) {
  m.def(
      "massage_keys",
      [] {
        MassageOptions defaults;
        return keys_as_data(entries_of(defaults));
      },
      ("The keys of Massager(**massage) and of the config's \"massage\" object, in table order: "
       "a list of dicts with name, type (one of " + type_names() + "), default, choices (choice: "
       "the names, else None), min, max (None: unbounded), min_exclusive, max_exclusive (the "
       "interval of a number, an integer or each item of an integer list; None and False for "
       "other types), range (what it accepts, as the error messages say it) and doc (one line, "
       "Markdown).").c_str());
  m.def(
      "measure_keys",
      [] {
        MeasureOptions defaults;
        return keys_as_data(entries_of(defaults));
      },
      "The keys of distances(**measures) (the single-mesh jobs' \"measures\" object), as "
      "massage_keys() lists them.");
}

}  // namespace sm::python
