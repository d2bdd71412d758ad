#include "core/options_table.hpp"

#include <sstream>

#include "core/errors.hpp"

namespace sm {
namespace {

std::string number_text(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

}  // namespace

std::string interval_text(const ValueSpec& s, bool integer) {
  if (integer) {
    const auto text = [](double x) { return std::to_string(static_cast<long long>(x)); };
    if (std::isinf(s.hi)) return ">= " + text(s.lo);
    return "[" + text(s.lo) + ", " + text(s.hi) + "]";
  }
  if (std::isinf(s.hi)) return (s.lo_open ? "> " : ">= ") + number_text(s.lo);
  return (s.lo_open ? "(" : "[") + number_text(s.lo) + ", " + number_text(s.hi) +
         (s.hi_open ? ")" : "]");
}

std::string describe_integers(double lo, double hi) {
  const ValueSpec s = closed(lo, hi);
  return std::string(std::isinf(hi) ? "an integer " : "an integer in ") + interval_text(s, true);
}

std::string describe_numbers(const ValueSpec& s) {
  return std::string(std::isinf(s.hi) ? "a number " : "a number in ") + interval_text(s, false);
}

std::string number_reason(const ValueSpec& spec, double x) {
  return "expected " + describe_numbers(spec) + ", got " + number_text(x);
}

ConfigError number_error(const std::string& path, const ValueSpec& spec, double x) {
  return ConfigError(path + ": " + number_reason(spec, x));
}

namespace {

void check_entries(const Entries& entries, const std::string& prefix) {
  for (const Entry& e : entries) {
    const ValueSpec& spec = e.info->spec;
    const std::string key = prefix.empty() ? std::string(e.info->key)
                                           : prefix + "." + std::string(e.info->key);
    const auto check_integer = [&](int v) {  // bounds by key: checked where the keys are read
      if (spec.lo_key.empty() && spec.hi_key.empty() && !spec.contains(v))
        throw OptionError(key, "expected " + describe_integers(spec.lo, spec.hi) + ", got " +
                                   std::to_string(v));
    };
    const auto check_number = [&](double v) {
      if (!spec.contains(v)) throw OptionError(key, number_reason(spec, v));
    };
    if (auto* i = std::get_if<int*>(&e.value)) check_integer(**i);
    if (auto* i = std::get_if<std::optional<int>*>(&e.value); i && **i) check_integer(***i);
    if (auto* x = std::get_if<double*>(&e.value)) check_number(**x);
    if (auto* x = std::get_if<std::optional<double>*>(&e.value); x && **x) check_number(***x);
    if (auto* o = std::get_if<ObjectRef>(&e.value); o && o->present(o->target))
      check_entries(o->entries(o->target), o->mode == ObjectRef::Mode::Inline ? prefix : key);
  }
}

}  // namespace

void check_option_ranges(const Entries& entries) { check_entries(entries, ""); }

}  // namespace sm
