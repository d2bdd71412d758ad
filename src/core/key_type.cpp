#include "core/key_type.hpp"

#include <variant>

namespace sm {
namespace {

std::string code(const std::string& text) {
  return "`" + text + "`";
}

std::string quoted_names(const ValueSpec& spec, bool markdown) {
  std::string out;
  for (const auto& [name, value] : spec.names) {
    const std::string quoted = "\"" + std::string(name) + "\"";
    out += (out.empty() ? "" : ", ") + (markdown ? code(quoted) : quoted);
  }
  return out;
}

// An integer key's interval in the reference: bounds given by sibling keys are named.
std::string integer_cell(const ValueSpec& s) {
  if (!s.lo_key.empty()) return ">= " + code(std::string(s.lo_key));
  if (!s.hi_key.empty()) return "[0, " + code(std::string(s.hi_key)) + " − 1]";
  return interval_text(s, true);
}

template <class T>
bool holds(const ValueRef& v) {
  return std::holds_alternative<T>(v);
}

}  // namespace

KeyType key_type(const Entry& e) {
  const ValueSpec& s = e.info->spec;
  const ValueRef& v = e.value;
  const std::string numbers = describe_numbers(s);
  if (holds<bool*>(v)) return {"boolean", "boolean", false, false, "true or false", ""};
  if (holds<int*>(v))
    return {"integer", "integer", true, false, describe_integers(s.lo, s.hi), integer_cell(s)};
  if (holds<double*>(v)) return {"number", "number", true, false, numbers, interval_text(s, false)};
  if (holds<std::optional<int>*>(v))
    return {"integer_or_none", "integer or null", true, true, describe_integers(s.lo, s.hi),
            integer_cell(s) + ", or `null`"};
  if (holds<std::optional<double>*>(v) && s.auto_word)
    return {"number_or_auto", "string or number", true, false, "\"auto\" or " + numbers,
            "`\"auto\"`, or " + numbers};
  if (holds<std::optional<double>*>(v))
    return {"number_or_none", "number or null", true, true, numbers,
            interval_text(s, false) + ", or `null`"};
  if (holds<std::filesystem::path*>(v)) return {"path", "path", false, false, "a path", ""};
  if (holds<std::vector<int>*>(v))
    return {"integer_list", "array", true, false, "a list of " + std::string(s.items),
            std::string(s.items) + " " + integer_cell(s)};
  if (holds<std::vector<double>*>(v))
    return {"number_list", "array", false, false,
            "at least two increasing numbers; the last may be \"inf\"",
            "at least two increasing numbers; the last may be `\"inf\"`"};
  if (holds<FrameSelection*>(v))
    return {"frames", "string or array", false, false,
            "\"all\", a list of frame indices >= 0, or a range \"A:B[:STEP]\"",
            "`\"all\"`, an array of frame indices >= 0, or a range `\"A:B[:STEP]\"` (B may be "
            "empty: to the end)"};
  if (holds<ChoiceRef>(v))
    return {"choice", "string", false, false, quoted_names(s, false), quoted_names(s, true)};
  if (holds<SelectorRef>(v))
    return {"selector", "string, integer or null", false, true,
            "a name (a non-empty string) or an index >= 0",
            "a name (a non-empty string), an index >= 0, or `null`"};
  if (std::get<ObjectRef>(v).mode == ObjectRef::Mode::Toggle)
    return {"toggle", "boolean or object", false, false, "true, false or an object",
            "`true` (every default), `false`, or an object of the keys below"};
  return {"object", "object", false, false, "an object", "the keys below"};
}

}  // namespace sm
