#include "io/options_json.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <optional>

#include "core/errors.hpp"
#include "core/frame_selection.hpp"
#include "core/spelling.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::optional<int64_t> as_integer(const json& v) {
  if (v.is_number_integer() && !v.is_number_unsigned()) return v.get<int64_t>();
  if (v.is_number_unsigned() && v.get<uint64_t>() <= static_cast<uint64_t>(INT64_MAX))
    return static_cast<int64_t>(v.get<uint64_t>());
  return std::nullopt;
}

int sibling_integer(const Entries& siblings, std::string_view key) {
  for (const Entry& e : siblings)
    if (e.info->key == key)
      if (int* const* i = std::get_if<int*>(&e.value)) return **i;
  throw std::logic_error("options table: no integer key \"" + std::string(key) + "\"");
}

int read_integer(const json& v, const std::string& path, const ValueSpec& spec,
                 const Entries& siblings) {
  const double lo = spec.lo_key.empty() ? spec.lo : sibling_integer(siblings, spec.lo_key);
  const double hi = spec.hi_key.empty() ? spec.hi : sibling_integer(siblings, spec.hi_key) - 1.0;
  const auto i = as_integer(v);
  if (!i || *i < lo || *i > std::min<double>(hi, INT_MAX))
    fail_at(path, "expected " + describe_integers(lo, hi) + ", got " + describe(v));
  return static_cast<int>(*i);
}

// The items of the array `v`, each an integer of `spec`.
std::vector<int> read_integers(const json& v, const std::string& path, const ValueSpec& spec,
                               const Entries& siblings) {
  std::vector<int> out;
  for (size_t i = 0; i < v.size(); ++i)
    out.push_back(read_integer(v[i], path + "[" + std::to_string(i) + "]", spec, siblings));
  return out;
}

double read_number(const json& v, const std::string& path, const ValueSpec& spec) {
  if (!v.is_number() || !spec.contains(v.get<double>()))
    fail_at(path, "expected " + std::string(spec.auto_word ? "\"auto\" or " : "") +
                      describe_numbers(spec) + ", got " + describe(v));
  return v.get<double>();
}

std::vector<std::string> names_of(const ValueSpec& spec) {
  std::vector<std::string> names;
  for (const auto& [name, value] : spec.names) names.emplace_back(name);
  return names;
}

int read_choice(const json& v, const std::string& path, const ValueSpec& spec) {
  if (v.is_string())
    for (const auto& [name, value] : spec.names)
      if (name == v.get<std::string>()) return value;
  fail_at(path, "expected " + quoted_list(names_of(spec)) + ", got " + describe(v) +
                    (v.is_string() ? did_you_mean(v.get<std::string>(), names_of(spec)) : ""));
}

fs::path read_path(const json& v, const std::string& path, const fs::path& base) {
  if (!v.is_string() || v.get<std::string>().empty())
    fail_at(path, "expected a path (a non-empty string), got " + describe(v));
  if (v.get<std::string>().find('\0') != std::string::npos)
    fail_at(path, "path contains a NUL character");
  const fs::path p = v.get<std::string>();
  return (p.is_absolute() ? p : base / p).lexically_normal();
}

std::vector<double> read_bin_edges(const json& v, const std::string& path) {
  if (!v.is_array() || v.size() < 2)
    fail_at(path, "expected an array of at least two increasing bin edges, got " + describe(v));
  std::vector<double> edges;
  for (size_t i = 0; i < v.size(); ++i) {
    const json& e = v[i];
    const std::string where = path + "[" + std::to_string(i) + "]";
    double x = INFINITY;
    if (e.is_number() && std::isfinite(e.get<double>()))
      x = e.get<double>();
    else if (!e.is_string() || e.get<std::string>() != "inf")
      fail_at(where, "expected a number or \"inf\", got " + describe(e));
    if (!edges.empty() && !(x > edges.back()))
      fail_at(where,
              "bin edges must increase, got " + describe(e) + " after " + describe(v[i - 1]));
    edges.push_back(x);
  }
  return edges;
}

// "all", an array of frame indices, or a range "A:B[:STEP]".
FrameSelection read_frames(const json& v, const std::string& path) {
  const std::string expected =
      "expected \"all\", an array of frame indices or a range \"A:B[:STEP]\", got ";
  if (v.is_string() && v.get<std::string>() == "all") return FrameSelection{};
  if (v.is_string() && v.get<std::string>().find(':') != std::string::npos) {
    const FrameRange r = parse_frame_range(v.get<std::string>(), path);
    return FrameSelection{FrameSelection::Kind::Range, {}, r.start, r.stop, r.step};
  }
  if (!v.is_array()) fail_at(path, expected + describe(v));
  FrameSelection s = FrameSelection::none();
  s.list = read_integers(v, path, at_least(0), {});
  std::sort(s.list.begin(), s.list.end());
  s.list.erase(std::unique(s.list.begin(), s.list.end()), s.list.end());
  return s;
}

// A glTF element by name (a non-empty string) or by index (an integer >= 0); null keeps both.
void read_selector(const json& v, const std::string& path, const SelectorRef& r) {
  if (v.is_null()) return;
  if (v.is_string() && !v.get<std::string>().empty()) {
    *r.name = v.get<std::string>();
  } else if (const auto i = as_integer(v); i && *i >= 0 && *i <= INT_MAX) {
    *r.index = static_cast<int>(*i);
  } else {
    fail_at(path, "expected a name (a non-empty string) or an index (an integer >= 0), got " +
                      describe(v));
  }
}

void read_nested(const json& v, const std::string& path, const ObjectRef& o, const fs::path& base) {
  if (o.mode == ObjectRef::Mode::Toggle && v.is_boolean())
    return o.set_present(o.target, v.get<bool>());
  if (o.mode == ObjectRef::Mode::Toggle && !v.is_object())
    fail_at(path, "expected true, false or an object with the keys " +
                      quoted_list(keys_of(o.defaults())) + ", got " + describe(v));
  if (!v.is_object()) fail_at(path, "expected an object, got " + describe(v));
  o.set_present(o.target, true);
  read_object(v, path, o.entries(o.target), base);
}

}  // namespace

[[noreturn]] void fail_at(const std::string& path, const std::string& what) {
  throw ConfigError((path.empty() ? std::string("config") : path) + ": " + what);
}

std::string describe(const json& value) {
  if (value.is_object()) return "an object";
  if (value.is_array()) return "an array";
  std::string text = value.dump();
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

std::string join_path(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::vector<std::string> keys_of(const Entries& entries) {
  std::vector<std::string> keys;
  for (const Entry& e : entries) {
    const auto* o = std::get_if<ObjectRef>(&e.value);
    if (o && o->mode == ObjectRef::Mode::Inline) {
      for (const std::string& key : keys_of(o->defaults())) keys.push_back(key);
    } else {
      keys.emplace_back(e.info->key);
    }
  }
  return keys;
}

void check_keys(const json& value, const std::string& path, const std::vector<std::string>& known) {
  if (!value.is_object()) fail_at(path, "expected an object, got " + describe(value));
  for (const auto& item : value.items()) {
    if (std::find(known.begin(), known.end(), item.key()) != known.end()) continue;
    const std::string guess = did_you_mean(item.key(), known);
    fail_at(join_path(path, item.key()),
            "unknown key" + (guess.empty() ? " (known keys: " + quoted_list(known) + ")" : guess));
  }
}

void read_value(const json& v, const std::string& path, const Entry& e, const Entries& siblings,
                const fs::path& base) {
  const ValueSpec& spec = e.info->spec;
  std::visit(Overloaded{
                 [&](bool* out) {
                   if (!v.is_boolean()) fail_at(path, "expected true or false, got " + describe(v));
                   *out = v.get<bool>();
                 },
                 [&](int* out) { *out = read_integer(v, path, spec, siblings); },
                 [&](double* out) { *out = read_number(v, path, spec); },
                 [&](std::optional<int>* out) {
                   out->reset();
                   if (!v.is_null()) *out = read_integer(v, path, spec, siblings);
                 },
                 [&](std::optional<double>* out) {
                   out->reset();
                   if (!(spec.auto_word ? v == "auto" : v.is_null()))
                     *out = read_number(v, path, spec);
                 },
                 [&](fs::path* out) { *out = read_path(v, path, base); },
                 [&](std::vector<int>* out) {
                   if (!v.is_array())
                     fail_at(path, "expected an array of " + std::string(spec.items) + ", got " +
                                       describe(v));
                   *out = read_integers(v, path, spec, siblings);
                 },
                 [&](std::vector<double>* out) { *out = read_bin_edges(v, path); },
                 [&](FrameSelection* out) { *out = read_frames(v, path); },
                 [&](const ChoiceRef& c) { c.set(c.value, read_choice(v, path, spec)); },
                 [&](const SelectorRef& s) { read_selector(v, path, s); },
                 [&](const ObjectRef& o) { read_nested(v, path, o, base); },
             },
             e.value);
}

void read_object(const json& value, const std::string& path, const Entries& entries,
                 const fs::path& base) {
  check_keys(value, path, keys_of(entries));
  for (const Entry& e : entries) {
    const auto* o = std::get_if<ObjectRef>(&e.value);
    if (o && o->mode == ObjectRef::Mode::Inline) {  // present when its first key is
      if (!value.contains(std::string(o->defaults().front().info->key))) continue;
      o->set_present(o->target, true);
      const Entries inner = o->entries(o->target);
      for (const Entry& i : inner)
        if (const auto it = value.find(std::string(i.info->key)); it != value.end())
          read_value(*it, join_path(path, i.info->key), i, inner, base);
      continue;
    }
    const std::string where = join_path(path, e.info->key);
    const auto it = value.find(std::string(e.info->key));
    if (it != value.end())
      read_value(*it, where, e, entries, base);
    else if (!e.info->required.empty())
      fail_at(where, "missing (" + std::string(e.info->required) + ")");
  }
}

std::optional<json> write_value(const Entry& e) {
  const ValueSpec& spec = e.info->spec;
  const json left_out(json::value_t::discarded);
  const json v = std::visit(
      Overloaded{
          [](const std::optional<int>* v) { return *v ? json(**v) : json(); },
          [&](const std::optional<double>* v) {
            return *v ? json(**v) : spec.auto_word ? json("auto") : json();
          },
          [&](const fs::path* v) { return v->empty() ? left_out : json(v->string()); },
          [](const std::vector<double>* v) {
            json bins = json::array();
            for (double x : *v) bins.push_back(std::isfinite(x) ? json(x) : json("inf"));
            return bins;
          },
          [](const FrameSelection* s) {
            if (s->kind == FrameSelection::Kind::All) return json("all");
            if (s->kind == FrameSelection::Kind::List) return json(s->list);
            return json(format_frame_range(FrameRange{s->start, s->stop, s->step}));
          },
          [&](const ChoiceRef& c) {
            for (const auto& [name, value] : spec.names)
              if (value == c.get(c.value)) return json(std::string(name));
            return json();
          },
          [](const SelectorRef& s) {
            return *s.index ? json(**s.index) : s.name->empty() ? json() : json(*s.name);
          },
          [&](const ObjectRef& o) {
            if (!o.present(o.target))
              return o.mode == ObjectRef::Mode::Toggle ? json(false) : left_out;
            json object = write_object(o.entries(o.target));
            return object.empty() ? left_out : object;
          },
          [](const auto* v) { return json(*v); },  // bool, int, double, a list of integers
      },
      e.value);
  return v.is_discarded() ? std::nullopt : std::optional<json>(v);
}

json write_object(const Entries& entries) {
  json out = json::object();
  for (const Entry& e : entries) {
    if (!e.written) continue;
    const auto* o = std::get_if<ObjectRef>(&e.value);
    if (o && o->mode == ObjectRef::Mode::Inline) {
      if (o->present(o->target)) out.update(write_object(o->entries(o->target)));
    } else if (std::optional<json> v = write_value(e)) {
      out[std::string(e.info->key)] = std::move(*v);
    }
  }
  return out;
}

}  // namespace sm
