/// massage_keys() and measure_keys(): the options tables (core/options_table.hpp) as data, for
/// user interfaces built from them (the Blender add-on's panel): every key's name, type, default,
/// range and doc, in table order.
#include <cmath>
#include <string>
#include <variant>

#include "io/options_json.hpp"
#include "massage/massage.hpp"
#include "massage/massage_keys.hpp"
#include "pipeline/mesh_jobs/measures.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"

namespace sm::python {
namespace {

py::object bound(double x) {
  return std::isfinite(x) ? py::object(py::float_(x)) : py::object(py::none());
}

// The type of a key, one word, and what it accepts, as the messages say it.
std::pair<const char*, std::string> type_and_range(const Entry& e) {
  const ValueSpec& s = e.info->spec;
  const ValueRef& v = e.value;
  if (std::holds_alternative<bool*>(v)) return {"boolean", "true or false"};
  if (std::holds_alternative<int*>(v)) return {"integer", describe_integers(s.lo, s.hi)};
  if (std::holds_alternative<double*>(v)) return {"number", describe_numbers(s)};
  if (std::holds_alternative<std::optional<double>*>(v) && s.auto_word)
    return {"number_or_auto", "\"auto\" or " + describe_numbers(s)};
  if (std::holds_alternative<std::optional<double>*>(v))
    return {"number_or_none", describe_numbers(s) + " or None"};
  if (std::holds_alternative<std::optional<int>*>(v))
    return {"integer_or_none", describe_integers(s.lo, s.hi) + " or None"};
  if (std::holds_alternative<std::vector<int>*>(v))
    return {"integer_list", "a list of " + std::string(s.items)};
  if (std::holds_alternative<std::vector<double>*>(v))
    return {"number_list", "at least two increasing numbers; the last may be \"inf\""};
  if (std::holds_alternative<ChoiceRef>(v)) {
    std::string names;
    for (const auto& [name, value] : s.names)
      names += (names.empty() ? "\"" : ", \"") + std::string(name) + "\"";
    return {"choice", names};
  }
  if (std::holds_alternative<std::filesystem::path*>(v)) return {"path", "a path"};
  return {"other", ""};
}

py::list keys_as_data(const Entries& entries) {
  py::list out;
  for (const Entry& e : entries) {
    const ValueSpec& s = e.info->spec;
    const auto [type, range] = type_and_range(e);
    py::dict d;
    d["name"] = std::string(e.info->key);
    d["type"] = type;
    const std::optional<nlohmann::json> value = write_value(e);
    d["default"] = value ? from_json(*value) : py::object(py::none());
    py::list choices;
    for (const auto& [name, index] : s.names) choices.append(std::string(name));
    d["choices"] = s.names.empty() ? py::object(py::none()) : py::object(choices);
    const bool numeric = type == std::string("integer") || type == std::string("number") ||
                         type == std::string("number_or_auto") ||
                         type == std::string("integer_list");
    d["min"] = numeric ? bound(s.lo) : py::object(py::none());
    d["max"] = numeric ? bound(s.hi) : py::object(py::none());
    d["min_exclusive"] = numeric && s.lo_open;
    d["max_exclusive"] = numeric && s.hi_open;
    d["range"] = range;
    d["doc"] = std::string(e.info->doc);
    out.append(d);
  }
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
      "The keys of Massager(**massage) and of the config's \"massage\" object, in table order: "
      "a list of dicts with name, type (boolean, integer, number, number_or_auto, choice, "
      "integer_list), default, choices (choice: the names, else None), min, max (None: "
      "unbounded), min_exclusive, max_exclusive, range (as the error messages say it) and doc "
      "(one line, Markdown).");
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
