#include "config/reference.hpp"

#include <sstream>
#include <vector>

#include "config/config.hpp"

namespace sm {
namespace {

std::string code(const std::string& text) {
  return "`" + text + "`";
}

std::string quoted_names(const ValueSpec& spec) {
  std::string out;
  for (const auto& [name, value] : spec.names)
    out += (out.empty() ? "" : ", ") + code("\"" + std::string(name) + "\"");
  return out;
}

// "[0, 4096]", ">= 1", "> 0", "(0, 1)": the range without "an integer" / "a number" (in).
std::string range(const std::string& described) {
  for (const char* lead : {"an integer in ", "an integer ", "a number in ", "a number "})
    if (described.rfind(lead, 0) == 0) return described.substr(std::string(lead).size());
  return described;
}

std::string integers(const ValueSpec& s) {
  if (!s.lo_key.empty()) return ">= " + code(std::string(s.lo_key));
  if (!s.hi_key.empty()) return "[0, " + code(std::string(s.hi_key)) + " − 1]";
  return range(describe_integers(s.lo, s.hi));
}

template <class T>
bool holds(const ValueRef& v) {
  return std::holds_alternative<T>(v);
}

// The "type" and "allowed" cells of a key.
std::pair<std::string, std::string> type_and_allowed(const Entry& e) {
  const ValueSpec& s = e.info->spec;
  const ValueRef& v = e.value;
  if (holds<bool*>(v)) return {"boolean", ""};
  if (holds<int*>(v)) return {"integer", integers(s)};
  if (holds<double*>(v)) return {"number", range(describe_numbers(s))};
  if (holds<std::optional<int>*>(v)) return {"integer or null", integers(s) + ", or `null`"};
  if (holds<std::optional<double>*>(v) && s.auto_word)
    return {"string or number", "`\"auto\"`, or " + describe_numbers(s)};
  if (holds<std::optional<double>*>(v))
    return {"number or null", range(describe_numbers(s)) + ", or `null`"};
  if (holds<std::filesystem::path*>(v)) return {"path", ""};
  if (holds<std::vector<int>*>(v)) return {"array", std::string(s.items) + " " + integers(s)};
  if (holds<std::vector<double>*>(v))
    return {"array", "at least two increasing numbers; the last may be `\"inf\"`"};
  if (holds<FrameSelection*>(v))
    return {"string or array",
            "`\"all\"`, an array of frame indices >= 0, or a range `\"A:B[:STEP]\"` (B may be "
            "empty: to the end)"};
  if (holds<ChoiceRef>(v)) return {"string", quoted_names(s)};
  if (holds<SelectorRef>(v))
    return {"string, integer or null", "a name (a non-empty string), an index >= 0, or `null`"};
  if (std::get<ObjectRef>(v).mode == ObjectRef::Mode::Toggle)
    return {"boolean or object", "`true` (every default), `false`, or an object of the keys below"};
  return {"object", "the keys below"};
}

std::string default_cell(const Entry& e) {
  if (!e.info->required.empty()) return "required";
  if (const auto* o = std::get_if<ObjectRef>(&e.value); o && o->mode != ObjectRef::Mode::Toggle)
    return o->present(o->target) ? "" : "—";
  const std::optional<nlohmann::json> value = write_value(e);
  return value ? code(value->dump()) : "—";
}

std::string escaped(std::string_view text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

// One row per key of `columns[0]` (depth first, `path` its object's), a default cell per column
// (the same table, another instance); the keys in `shared` get a row but not their keys.
void rows(std::ostream& out, const std::string& path, const std::vector<Entries>& columns,
          const std::vector<std::string>& shared) {
  for (size_t i = 0; i < columns[0].size(); ++i) {
    const Entry& e = columns[0][i];
    const auto* o = std::get_if<ObjectRef>(&e.value);
    const auto nested = [&](const Entry& c) {
      const ObjectRef& r = std::get<ObjectRef>(c.value);
      return r.present(r.target) ? r.entries(r.target) : r.defaults();
    };
    std::vector<Entries> inner;
    if (o)
      for (const Entries& c : columns) inner.push_back(nested(c[i]));
    if (o && o->mode == ObjectRef::Mode::Inline) {
      rows(out, path, inner, shared);
      continue;
    }
    const std::string key = join_path(path, e.info->key);
    const bool is_shared = std::find(shared.begin(), shared.end(), key) != shared.end();
    auto [type, allowed] = type_and_allowed(e);
    if (is_shared) allowed = "the keys of [`" + key + "`](#" + key + "-every-job)";
    out << "| " << code(key) << " | " << type;
    for (const Entries& c : columns) out << " | " << default_cell(c[i]);
    out << " | " << allowed << " | " << escaped(e.info->doc) << " |\n";
    if (o && !is_shared) rows(out, key, inner, shared);
  }
}

void table(std::ostream& out, const std::string& path,
           const std::vector<std::string>& default_headers, const std::vector<Entries>& columns,
           const std::vector<std::string>& shared) {
  out << "| key | type";
  for (const std::string& h : default_headers) out << " | " << h;
  out << " | allowed | meaning |\n|---|---";
  for (size_t i = 0; i < default_headers.size(); ++i) out << "|---";
  out << "|---|---|\n";
  rows(out, path, columns, shared);
}

constexpr const char* kIntroduction = R"(# Configuration reference

<!-- Generated by `seqmassage config --reference` from the options tables beside the options
structs in src/ (fields_of); tests/config/test_reference.cpp checks that this file is current. -->

A job is one JSON file, `seqmassage CONFIG.json`; its `"job"` key chooses the job. The reader is
strict, and nothing runs until the config and every input have been checked:

- plain JSON: no comments, no duplicate keys, no trailing content;
- an unknown key, a wrong type, an out-of-range value or a missing required key is an error that
  names the key by its JSON path and suggests the nearest key or value for a typo
  (`massage.iteratons: unknown key (did you mean "iterations"?)`); exit status 2;
- paths are relative to the config file's folder (absolute paths are kept);
- a key left out takes its default; `report.json` holds the resolved config, every key with its
  value and the paths made absolute, which is itself a valid config.

`seqmassage --dry-run CONFIG.json` checks a config and all its inputs and prints what would be
done, writing nothing. Keys are listed by their full JSON path.

## `"job": "sequence"`

Corrects the texture swimming of a mesh sequence (paper §3.1): every frame M is optimized towards
the template's triangle shapes T while staying close to its own input surface N. A minimal config:

```json
{ "job": "sequence", "input": { "frames": "captures/take1" }, "output": { "dir": "out/take1" } }
```

)";

constexpr const char* kMeshJobs = R"(
## `"job": "remesh"`, `"crossparam"` and `"smooth"`

One mesh in, one mesh out. Minimal configs:

```json
{ "job": "remesh",     "input": { "mesh": "bunny_remesh.off", "reference": "bunny.off" }, "output": { "dir": "out" } }
{ "job": "crossparam", "input": { "mesh": "man.obj" }, "template": { "mesh": "horse.obj" }, "output": { "dir": "out" } }
{ "job": "smooth",     "input": { "mesh": "fandisk.obj" }, "output": { "dir": "out" } }
```

The sequence job's other `input` and `template` keys are refused with a note (`input.frames: only
for "job": "sequence"; ...`), as are `input.reference` except for remesh and `template` except
for crossparam; its other keys are unknown keys here.

)";

constexpr const char* kTrack = R"(
## `"job": "track"`

Tracks one template through a folder of raw frames of any connectivity (an untracked capture:
every frame its own vertices and triangles) and writes the template's connectivity on every
frame through the sequence job's outputs; see [tracking](tracking.md). A minimal config:

```json
{ "job": "track", "input": { "frames": "capture/take1" }, "template": { "frame": 0 }, "output": { "dir": "out/take1" } }
```

)";

constexpr const char* kMassage = R"(
## `massage` (every job)

The optimizer (paper §2): per outer iteration, closest points both ways, the combined solve
K v = μδ + (1−μ)c with K = μA + (1−μ)B (eq. 7), then Lawson's update of the distance weights
(eq. 5). The keys are the same for every job; the smooth job's defaults differ.

)";

}  // namespace

std::string config_reference() {
  std::ostringstream out;
  SequenceJobOptions sequence;
  MeshJobOptions mesh;
  MassageOptions massage;
  MassageOptions smooth = default_massage_options(JobKind::Smooth);
  out << kIntroduction;
  table(out, "", {"default"}, {entries_of(sequence)}, {"massage"});
  out << kMeshJobs;
  table(out, "", {"default"}, {entries_of(mesh)}, {"massage"});
  TrackJobOptions track;
  out << kTrack;
  table(out, "", {"default"}, {entries_of(track)}, {"massage"});
  out << kMassage;
  table(out, "massage", {"default (sequence, remesh, crossparam)", "default (smooth)"},
        {entries_of(massage), entries_of(smooth)}, {});
  return out.str();
}

}  // namespace sm
