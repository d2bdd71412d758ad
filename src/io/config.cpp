#include "io/config.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "io/atomic_file.hpp"
#include "mesh/errors.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// ---------------------------------------------------------------------------------------------
// Strict JSON: a SAX handler that builds the document, refuses duplicate keys and turns parse
// errors into a message instead of an exception.

class StrictBuilder {
 public:
  using number_integer_t = json::number_integer_t;
  using number_unsigned_t = json::number_unsigned_t;
  using number_float_t = json::number_float_t;
  using string_t = json::string_t;
  using binary_t = json::binary_t;

  explicit StrictBuilder(std::string_view text) : text_(text) {}

  bool null() { return put(json(nullptr)); }
  bool boolean(bool value) { return put(json(value)); }
  bool number_integer(number_integer_t value) { return put(json(value)); }
  bool number_unsigned(number_unsigned_t value) { return put(json(value)); }
  bool number_float(number_float_t value, const string_t&) { return put(json(value)); }
  bool string(string_t& value) { return put(json(value)); }
  bool binary(binary_t& value) { return put(json::binary(value)); }

  bool start_object(std::size_t) { return open(json::object()); }
  bool end_object() { return close(); }
  bool start_array(std::size_t) { return open(json::array()); }
  bool end_array() { return close(); }

  bool key(string_t& key) {
    Frame& top = stack_.back();
    if (top.value->contains(key)) {
      error_ = child_path(top, key) + ": duplicate key (each key may appear once)";
      return false;
    }
    top.key = key;
    return true;
  }

  bool parse_error(std::size_t position, const std::string& last_token,
                   const nlohmann::detail::exception& ex) {
    position_ = position;
    if (!last_token.empty() && last_token.back() == '/' && position < text_.size() &&
        (text_[position] == '/' || text_[position] == '*')) {
      error_ = "comments are not allowed in JSON";
      return false;
    }
    // "[json.exception.parse_error.101] parse error at line 3, column 5: <reason>" -> "<reason>",
    // "[json.exception.out_of_range.406] number overflow parsing '1e999'" -> "number overflow ..."
    std::string what = ex.what();
    const size_t column = what.find("column ");
    const size_t colon = column == std::string::npos ? std::string::npos : what.find(": ", column);
    if (colon != std::string::npos) {
      what = what.substr(colon + 2);
    } else if (what.rfind("[json.exception.", 0) == 0 && what.find("] ") != std::string::npos) {
      what = what.substr(what.find("] ") + 2);
    }
    error_ = what;
    return false;
  }

  json& root() { return root_; }
  const std::string& error() const { return error_; }
  std::optional<size_t> position() const { return position_; }

 private:
  struct Frame {
    json* value;
    std::string path;
    std::string key;
  };

  static std::string child_path(const Frame& frame, const std::string& key) {
    return frame.path.empty() ? key : frame.path + "." + key;
  }

  // Inserts `value` where the parser is, returning its slot and JSON path.
  std::pair<json*, std::string> insert(json value) {
    if (stack_.empty()) {
      root_ = std::move(value);
      return {&root_, ""};
    }
    Frame& top = stack_.back();
    if (top.value->is_array()) {
      top.value->push_back(std::move(value));
      return {&top.value->back(), top.path + "[" + std::to_string(top.value->size() - 1) + "]"};
    }
    json& slot = (*top.value)[top.key];
    slot = std::move(value);
    return {&slot, child_path(top, top.key)};
  }
  bool put(json value) {
    insert(std::move(value));
    return true;
  }
  bool open(json container) {
    auto [slot, path] = insert(std::move(container));
    stack_.push_back({slot, std::move(path), {}});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }

  std::string_view text_;
  json root_;
  std::vector<Frame> stack_;
  std::string error_;
  std::optional<size_t> position_;
};

// ---------------------------------------------------------------------------------------------
// Typed access to config values, every message naming the key by its JSON path.

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw ConfigError((path.empty() ? std::string("config") : path) + ": " + what);
}

std::string describe(const json& value) {
  if (value.is_object()) return "an object";
  if (value.is_array()) return "an array";
  std::string text = value.dump();
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? (names.size() > 2 ? ", or " : " or ") : ", ";
    out += "\"" + names[i] + "\"";
  }
  return out;
}

std::string lowercase(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

// The candidate nearest to `word`, if it is near enough to be a plausible typo.
std::optional<std::string> nearest(std::string_view word, const std::vector<std::string>& options) {
  std::optional<std::string> best;
  int best_distance = INT_MAX;
  for (const std::string& option : options) {
    const int d = edit_distance(lowercase(word), lowercase(option));
    if (d < best_distance) {
      best_distance = d;
      best = option;
    }
  }
  const int limit = word.size() <= 3 ? 1 : word.size() <= 8 ? 2 : 3;
  if (best && best_distance <= limit) return best;
  return std::nullopt;
}

// One JSON object of the config: checks its type and its keys on construction.
class Section {
 public:
  Section(const json* value, std::string where, std::vector<std::string> known)
      : value_(value), path_(std::move(where)), known_(std::move(known)) {
    if (!value_) return;  // absent: every key takes its default
    if (!value_->is_object()) fail(path_, "expected an object, got " + describe(*value_));
    for (const auto& item : value_->items()) {
      if (std::find(known_.begin(), known_.end(), item.key()) != known_.end()) continue;
      std::string message = "unknown key";
      if (auto guess = nearest(item.key(), known_))
        message += " (did you mean \"" + *guess + "\"?)";
      else
        message += " (known keys: " + quoted_list(known_) + ")";
      fail(path(item.key()), message);
    }
  }

  const json* get(const std::string& key) const {
    if (!value_) return nullptr;
    auto it = value_->find(key);
    return it == value_->end() ? nullptr : &*it;
  }
  bool has(const std::string& key) const { return get(key) != nullptr; }
  std::string path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::string& path() const { return path_; }
  const json& require(const std::string& key, const std::string& what) const {
    const json* v = get(key);
    if (!v) fail(path(key), "missing (" + what + ")");
    return *v;
  }

 private:
  const json* value_;
  std::string path_;
  std::vector<std::string> known_;
};

std::optional<int64_t> as_integer(const json& v) {
  if (v.is_number_integer() && !v.is_number_unsigned()) return v.get<int64_t>();
  if (v.is_number_unsigned() && v.get<uint64_t>() <= static_cast<uint64_t>(INT64_MAX))
    return static_cast<int64_t>(v.get<uint64_t>());
  return std::nullopt;
}

std::string int_range(int64_t lo, int64_t hi) {
  if (hi == INT_MAX) return "an integer >= " + std::to_string(lo);
  return "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

int to_int(const json& v, const std::string& path, int64_t lo, int64_t hi = INT_MAX) {
  const auto i = as_integer(v);
  if (!i || *i < lo || *i > hi)
    fail(path, "expected " + int_range(lo, hi) + ", got " + describe(v));
  return static_cast<int>(*i);
}

void read(const Section& s, const std::string& key, int& out, int64_t lo, int64_t hi = INT_MAX) {
  if (const json* v = s.get(key)) out = to_int(*v, s.path(key), lo, hi);
}

// A closed or open interval for numbers; infinite bounds are left out of the description.
struct Interval {
  double lo = -INFINITY;
  bool lo_open = false;
  double hi = INFINITY;
  bool hi_open = false;
  bool contains(double x) const {
    return std::isfinite(x) && (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  }
  std::string describe() const {
    auto num = [](double x) {
      std::ostringstream s;
      s << x;
      return s.str();
    };
    if (std::isinf(hi)) return "a number " + std::string(lo_open ? "> " : ">= ") + num(lo);
    return "a number in " + std::string(lo_open ? "(" : "[") + num(lo) + ", " + num(hi) +
           (hi_open ? ")" : "]");
  }
};

void read(const Section& s, const std::string& key, double& out, Interval range) {
  const json* v = s.get(key);
  if (!v) return;
  if (!v->is_number() || !range.contains(v->get<double>()))
    fail(s.path(key), "expected " + range.describe() + ", got " + describe(*v));
  out = v->get<double>();
}

void read(const Section& s, const std::string& key, bool& out) {
  const json* v = s.get(key);
  if (!v) return;
  if (!v->is_boolean()) fail(s.path(key), "expected true or false, got " + describe(*v));
  out = v->get<bool>();
}

template <class Enum>
using Names = std::vector<std::pair<std::string, Enum>>;

template <class Enum>
std::vector<std::string> keys_of(const Names<Enum>& names) {
  std::vector<std::string> keys;
  for (const auto& [name, value] : names) keys.push_back(name);
  return keys;
}

template <class Enum>
void read(const Section& s, const std::string& key, Enum& out, const Names<Enum>& names) {
  const json* v = s.get(key);
  if (!v) return;
  if (v->is_string())
    for (const auto& [name, value] : names)
      if (name == v->get<std::string>()) {
        out = value;
        return;
      }
  std::string message = "expected " + quoted_list(keys_of(names)) + ", got " + describe(*v);
  if (v->is_string())
    if (auto guess = nearest(v->get<std::string>(), keys_of(names)))
      message += " (did you mean \"" + *guess + "\"?)";
  fail(s.path(key), message);
}

template <class Enum>
std::string name_of(Enum value, const Names<Enum>& names) {
  for (const auto& [name, v] : names)
    if (v == value) return name;
  return "";
}

fs::path read_path(const Section& s, const std::string& key, const fs::path& base) {
  const json* v = s.get(key);
  if (!v) return {};
  if (!v->is_string() || v->get<std::string>().empty())
    fail(s.path(key), "expected a path (a non-empty string), got " + describe(*v));
  const fs::path p = v->get<std::string>();
  return (p.is_absolute() ? p : base / p).lexically_normal();
}

const Names<JobKind> kJobs = {{"sequence", JobKind::Sequence}};
const Names<WeightKind> kWeights = {{"mean_value", WeightKind::MeanValue},
                                    {"uniform", WeightKind::Uniform}};
const Names<BoundaryWeights> kBoundary = {{"curve", BoundaryWeights::Curve},
                                          {"one_sided", BoundaryWeights::OneSided}};
const Names<SampleKind> kSamples = {
    {"vertices", SampleKind::Vertices}, {"edges", SampleKind::Edges}, {"faces", SampleKind::Faces}};
const Names<ShapeTargetKind> kShapeTargets = {{"zero", ShapeTargetKind::Zero},
                                              {"template", ShapeTargetKind::Template}};
const Names<SolverKind> kSolvers = {{"iterative", SolverKind::Iterative},
                                    {"direct", SolverKind::Direct}};
const Names<ClosestPointMode> kClosest = {{"local", ClosestPointMode::Local},
                                          {"exact", ClosestPointMode::Exact}};
const Names<OutputFormat> kFormats = {{"obj", OutputFormat::Obj}, {"gltf", OutputFormat::Gltf}};
const Names<OnFailure> kOnFailure = {{"copy_input", OnFailure::CopyInput},
                                     {"skip", OnFailure::Skip}};
const std::vector<std::string> kShapes = {"bending_tube"};

// Keys of the "massage" section, the same for every job (a test checks that every job accepts
// every key to_json writes).
const std::vector<std::string> kMassageKeys = {"weights",
                                               "boundary_weights",
                                               "shape_target",
                                               "iterations",
                                               "mu",
                                               "samples",
                                               "tolerance",
                                               "lawson",
                                               "lawson_floor",
                                               "solver",
                                               "solver_tolerance",
                                               "solver_max_iterations",
                                               "closest_points",
                                               "walk_max_steps",
                                               "pin_boundary",
                                               "pinned"};

void read_massage(const Section& s, MassageOptions& o) {
  read(s, "weights", o.weights, kWeights);
  read(s, "boundary_weights", o.boundary_weights, kBoundary);
  read(s, "shape_target", o.shape_target, kShapeTargets);
  read(s, "iterations", o.iterations, 1);
  if (const json* v = s.get("mu")) {
    const Interval range{0.0, false, 1.0, true};
    if (v->is_string() && v->get<std::string>() == "auto")
      o.mu.reset();
    else if (v->is_number() && range.contains(v->get<double>()))
      o.mu = v->get<double>();
    else
      fail(s.path("mu"), "expected \"auto\" or " + range.describe() + ", got " + describe(*v));
  }
  read(s, "samples", o.samples, kSamples);
  read(s, "tolerance", o.tolerance, Interval{0.0, false});
  read(s, "lawson", o.lawson);
  read(s, "lawson_floor", o.lawson_floor, Interval{0.0, true, 1.0, true});
  read(s, "solver", o.solver, kSolvers);
  read(s, "solver_tolerance", o.solver_tolerance, Interval{0.0, true, 1.0, true});
  read(s, "solver_max_iterations", o.solver_max_iterations, 1);
  read(s, "closest_points", o.closest_points, kClosest);
  read(s, "walk_max_steps", o.walk_max_steps, 0);
  read(s, "pin_boundary", o.pin_boundary);
  if (const json* v = s.get("pinned")) {
    if (!v->is_array())
      fail(s.path("pinned"), "expected an array of vertex indices, got " + describe(*v));
    o.pinned.clear();
    for (size_t i = 0; i < v->size(); ++i)
      o.pinned.push_back(to_int((*v)[i], s.path("pinned") + "[" + std::to_string(i) + "]", 0));
  }
}

void read_synthetic(const Section& s, SyntheticConfig& c) {
  if (const json* v = s.get("shape")) {
    if (!v->is_string() || v->get<std::string>() != kShapes[0])
      fail(s.path("shape"), "expected " + quoted_list(kShapes) + ", got " + describe(*v));
    c.shape = v->get<std::string>();
  }
  read(s, "frames", c.frames, 2, 100000);
  read(s, "segments", c.segments, 3, 100000);
  read(s, "rings", c.rings, 1, 100000);
  read(s, "radius", c.radius, Interval{0.0, true});
  read(s, "length", c.length, Interval{0.0, true});
  read(s, "bend", c.bend, Interval{0.0, false, 300.0, false});
  read(s, "drift", c.drift, Interval{0.0, false, 2.0, false});
  read(s, "seed", c.seed, 0);
  if (c.bend * M_PI / 180.0 * c.radius >= c.length)
    fail(s.path("bend"),
         "the tube would fold onto itself: bend (in radians) times radius must stay "
         "below length");
}

// A glTF element chosen by name (a non-empty string) or by index (an integer >= 0); null or
// absent keeps the default.
void read_gltf_selector(const Section& s, const std::string& key, std::string& name,
                        std::optional<int>& index) {
  const json* v = s.get(key);
  if (!v || v->is_null()) return;
  if (v->is_string() && !v->get<std::string>().empty()) {
    name = v->get<std::string>();
    return;
  }
  if (const auto i = as_integer(*v); i && *i >= 0 && *i <= INT_MAX) {
    index = static_cast<int>(*i);
    return;
  }
  fail(s.path(key),
       "expected a name (a non-empty string) or an index (an integer >= 0), got " + describe(*v));
}

// "input" of the sequence job: exactly one of "frames", "synthetic" and "gltf" (with "mesh",
// "animation" and "fps", which only a glTF input takes), and "range".
void read_sequence_input(const Section& input, const fs::path& base, InputConfig& in) {
  in.frames = read_path(input, "frames", base);
  if (input.has("synthetic")) {
    in.synthetic.emplace();
    read_synthetic(Section(input.get("synthetic"), "input.synthetic",
                           {"shape", "frames", "segments", "rings", "radius", "length", "bend",
                            "drift", "seed"}),
                   *in.synthetic);
  }
  if (input.has("gltf")) {
    GltfInputOptions& g = in.gltf.emplace();
    g.file = read_path(input, "gltf", base);
    read_gltf_selector(input, "mesh", g.mesh, g.mesh_index);
    read_gltf_selector(input, "animation", g.animation, g.animation_index);
    if (const json* fps = input.get("fps"); fps && !fps->is_null()) {
      g.fps.emplace();
      read(input, "fps", *g.fps, Interval{0.0, true, 1e6, false});
    }
  } else {
    for (const char* key : {"mesh", "animation", "fps"})
      if (input.has(key))
        fail(input.path(key),
             "only applies to a glTF input (\"gltf\": a .gltf or .glb animation file)");
  }
  const int given = int(input.has("frames")) + int(input.has("synthetic")) + int(input.has("gltf"));
  if (given == 0)
    fail("input",
         "missing \"frames\" (a folder of OBJ frames), \"synthetic\" (a generated sequence) or "
         "\"gltf\" (a glTF animation)");
  if (given > 1) fail("input", "give only one of \"frames\", \"synthetic\" and \"gltf\"");
  const Section range(input.get("range"), "input.range", {"start", "stop", "step"});
  read(range, "start", in.range.start, 0);
  if (const json* stop = range.get("stop"); stop && !stop->is_null())
    in.range.stop = to_int(*stop, range.path("stop"), in.range.start);
  read(range, "step", in.range.step, 1);
}

// "measures" of the sequence job.
void read_sequence_measures(const Section& s, DistanceOptions& m) {
  read(s, "spacing", m.spacing, Interval{0.0, true});
  read(s, "sample_edges", m.sample_edges);
  read(s, "sample_faces", m.sample_faces);
  read(s, "adaptive", m.adaptive);
  read(s, "refine_above", m.refine_above, Interval{0.0, false, 1.0, false});
}

// "checks", "shard" and "resume" of the sequence job.
void read_run_controls(const Section& root, JobConfig& c) {
  const Section checks(root.get("checks"), "checks",
                       {"max_folded_triangles", "max_folded_fraction"});
  if (const json* v = checks.get("max_folded_triangles")) {
    if (v->is_null())
      c.checks.max_folded_triangles.reset();
    else
      c.checks.max_folded_triangles = to_int(*v, checks.path("max_folded_triangles"), 0);
  }
  if (const json* v = checks.get("max_folded_fraction")) {
    if (v->is_null()) {
      c.checks.max_folded_fraction.reset();
    } else {
      c.checks.max_folded_fraction.emplace();
      read(checks, "max_folded_fraction", *c.checks.max_folded_fraction,
           Interval{0.0, false, 1.0, false});
    }
  }
  const Section shard(root.get("shard"), "shard", {"index", "count"});
  read(shard, "count", c.shard.count, 1, 100000);
  if (const json* v = shard.get("index"))
    c.shard.index = to_int(*v, shard.path("index"), 0, c.shard.count - 1);
  read(root, "resume", c.resume);
}

// ---------------------------------------------------------------------------------------------
// The optional visual outputs of the sequence job: output.colored, output.checker and
// output.iterations (see io/output_options.hpp).

const Names<ShearColorMode> kColorModes = {{"faces", ShearColorMode::Faces},
                                           {"vertices", ShearColorMode::Vertices}};
const Names<CheckerUvSource> kUvSources = {{"auto", CheckerUvSource::Auto},
                                           {"charts", CheckerUvSource::Charts}};

// "all", an array of frame indices, or a range "A:B[:STEP]".
void read(const Section& s, const std::string& key, FrameSelection& out) {
  const json* v = s.get(key);
  if (!v) return;
  const std::string path = s.path(key);
  const std::string expected =
      "expected \"all\", an array of frame indices or a range \"A:B[:STEP]\", got ";
  if (v->is_string()) {
    const std::string text = v->get<std::string>();
    if (text == "all") {
      out = FrameSelection{};
      return;
    }
    if (text.find(':') == std::string::npos) fail(path, expected + describe(*v));
    const FrameRange range = parse_frame_range(text, path);
    out = FrameSelection{FrameSelection::Kind::Range, {}, range.start, range.stop, range.step};
    return;
  }
  if (!v->is_array()) fail(path, expected + describe(*v));
  FrameSelection selection = FrameSelection::none();
  for (size_t i = 0; i < v->size(); ++i)
    selection.list.push_back(to_int((*v)[i], path + "[" + std::to_string(i) + "]", 0));
  std::sort(selection.list.begin(), selection.list.end());
  selection.list.erase(std::unique(selection.list.begin(), selection.list.end()),
                       selection.list.end());
  out = std::move(selection);
}

json to_json(const FrameSelection& s) {
  switch (s.kind) {
    case FrameSelection::Kind::All:
      return "all";
    case FrameSelection::Kind::List:
      return s.list;
    case FrameSelection::Kind::Range:
      return format_frame_range(FrameRange{s.start, s.stop, s.step});
  }
  return nullptr;
}

// An optional output: `true` (every default), `false` (off) or an object of the `known` keys,
// which `parse` reads.
template <class Parse>
void read_optional_output(const Section& output, const std::string& key, bool& enabled,
                          std::vector<std::string> known, Parse parse) {
  const json* v = output.get(key);
  if (!v) return;
  if (v->is_boolean()) {
    enabled = v->get<bool>();
    return;
  }
  if (!v->is_object())
    fail(output.path(key), "expected true, false or an object with the keys " + quoted_list(known) +
                               ", got " + describe(*v));
  enabled = true;
  parse(Section(v, output.path(key), std::move(known)));
}

void read_visual_outputs(const Section& output, OutputConfig& o) {
  read_optional_output(output, "colored", o.colored.enabled, {"frames", "max", "colors"},
                       [&](const Section& s) {
                         read(s, "frames", o.colored.frames);
                         read(s, "max", o.colored.max, Interval{0.0, true, 1e6, false});
                         read(s, "colors", o.colored.colors, kColorModes);
                       });
  read_optional_output(output, "checker", o.checker.enabled, {"frames", "uv", "cells", "cell_size"},
                       [&](const Section& s) {
                         read(s, "frames", o.checker.frames);
                         read(s, "uv", o.checker.uv, kUvSources);
                         read(s, "cells", o.checker.cells, 1, 64);
                         read(s, "cell_size", o.checker.cell_size, Interval{0.0, true, 1e6, false});
                       });
  read_optional_output(output, "iterations", o.iterations.enabled, {"frames", "shear_frames"},
                       [&](const Section& s) {
                         read(s, "frames", o.iterations.frames);
                         read(s, "shear_frames", o.iterations.shear_frames);
                       });
}

void visual_outputs_to_json(const OutputConfig& o, json& j) {
  j["colored"] = o.colored.enabled ? json{{"frames", to_json(o.colored.frames)},
                                          {"max", o.colored.max},
                                          {"colors", name_of(o.colored.colors, kColorModes)}}
                                   : json(false);
  j["checker"] = o.checker.enabled ? json{{"frames", to_json(o.checker.frames)},
                                          {"uv", name_of(o.checker.uv, kUvSources)},
                                          {"cells", o.checker.cells},
                                          {"cell_size", o.checker.cell_size}}
                                   : json(false);
  j["iterations"] = o.iterations.enabled
                        ? json{{"frames", to_json(o.iterations.frames)},
                               {"shear_frames", to_json(o.iterations.shear_frames)}}
                        : json(false);
}

}  // namespace

// -----------------------------------------------------------------------------------------------

int edit_distance(std::string_view a, std::string_view b) {
  // Optimal string alignment: insertions, deletions, substitutions and adjacent transpositions.
  const size_t w = b.size() + 1;
  std::vector<int> d((a.size() + 1) * w);
  for (size_t i = 0; i <= a.size(); ++i) d[i * w] = static_cast<int>(i);
  for (size_t j = 0; j <= b.size(); ++j) d[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      int best = std::min({d[(i - 1) * w + j] + 1, d[i * w + j - 1] + 1,
                           d[(i - 1) * w + j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        best = std::min(best, d[(i - 2) * w + j - 2] + 1);
      d[i * w + j] = best;
    }
  return d[a.size() * w + b.size()];
}

json parse_json_strict(std::string_view text) {
  StrictBuilder builder(text);
  if (json::sax_parse(text, &builder, json::input_format_t::json, true, false))
    return std::move(builder.root());
  std::string where;
  if (auto position = builder.position()) {
    const size_t end = std::min(*position, text.size());
    const std::string_view before = text.substr(0, end > 0 ? end - 1 : 0);
    const size_t line = 1 + std::count(before.begin(), before.end(), '\n');
    const size_t line_start = before.rfind('\n');
    const size_t column =
        before.size() - (line_start == std::string_view::npos ? 0 : line_start + 1) + 1;
    where = "line " + std::to_string(line) + ", column " + std::to_string(column) + ": ";
  }
  throw ConfigError(where + builder.error());
}

JobConfig load_config(const fs::path& path) {
  const std::string text = read_file(path);
  return parse_config(parse_json_strict(text), fs::absolute(path).parent_path());
}

JobConfig parse_config(const json& document, const fs::path& base_dir) {
  const fs::path base = fs::absolute(base_dir).lexically_normal();
  JobConfig c;
  const Section root(&document, "",
                     {"job", "input", "template", "output", "massage", "measures", "threads",
                      "frames_in_flight", "checks", "shard", "resume"});
  root.require("job", "the kind of job: \"sequence\"");
  read(root, "job", c.job, kJobs);

  read_sequence_input(
      Section(&root.require("input",
                            "\"frames\": a folder of OBJ frames, \"synthetic\" or "
                            "\"gltf\": a glTF animation"),
              "input", {"frames", "synthetic", "gltf", "mesh", "animation", "fps", "range"}),
      base, c.input);

  const Section templ(root.get("template"), "template", {"frame", "mesh", "optimize"});
  read(templ, "frame", c.templ.frame, 0);
  c.templ.mesh = read_path(templ, "mesh", base);
  read(templ, "optimize", c.templ.optimize);
  if (templ.has("frame") && templ.has("mesh"))
    fail("template", "give \"frame\" or \"mesh\", not both");
  if (templ.has("mesh") && c.templ.optimize)
    fail("template.optimize",
         "only applies to a template \"frame\" (with a rest \"mesh\", every "
         "frame is optimized)");
  if (c.input.synthetic) {
    if (templ.has("mesh")) fail("template.mesh", "not available with input.synthetic");
    if (c.templ.frame >= c.input.synthetic->frames)
      fail("template.frame", std::to_string(c.templ.frame) + " is out of range (input.synthetic." +
                                 "frames is " + std::to_string(c.input.synthetic->frames) + ")");
  }

  const Section output(&root.require("output", "an object with \"dir\", the output folder"),
                       "output",
                       {"dir", "format", "gltf", "per_triangle_csv", "timings", "colored",
                        "checker", "iterations", "on_failure"});
  output.require("dir", "the folder the results are written to");
  c.output.dir = read_path(output, "dir", base);
  read(output, "format", c.output.format, kFormats);
  read(output, "per_triangle_csv", c.output.per_triangle_csv);
  read(output, "timings", c.output.timings);
  read_visual_outputs(output, c.output);
  read(output, "on_failure", c.output.on_failure, kOnFailure);
  if (c.output.format == OutputFormat::Gltf && !c.input.gltf)
    fail(output.path("format"),
         "\"gltf\" needs a glTF input (input.gltf), whose mesh, materials and textures the "
         "output keeps; use \"obj\" for OBJ frames");
  if (output.has("gltf")) {
    if (c.output.format != OutputFormat::Gltf)
      fail(output.path("gltf"), "only applies to output.format \"gltf\"");
    const Section gltf(output.get("gltf"), "output.gltf", {"frames_per_mesh", "normals"});
    read(gltf, "frames_per_mesh", c.output.gltf.frames_per_mesh, 1, 100000);
    read(gltf, "normals", c.output.gltf.normals);
  }

  read_massage(Section(root.get("massage"), "massage", kMassageKeys), c.massage);
  read_sequence_measures(
      Section(root.get("measures"), "measures",
              {"spacing", "sample_edges", "sample_faces", "adaptive", "refine_above"}),
      c.measures);
  read(root, "threads", c.threads, 0, 4096);
  read(root, "frames_in_flight", c.frames_in_flight, 0, 1000000);
  read_run_controls(root, c);
  return c;
}

json to_json(const JobConfig& c) {
  json j;
  j["job"] = name_of(c.job, kJobs);
  json input;
  if (c.input.synthetic) {
    const SyntheticConfig& s = *c.input.synthetic;
    input["synthetic"] = {{"shape", s.shape}, {"frames", s.frames}, {"segments", s.segments},
                          {"rings", s.rings}, {"radius", s.radius}, {"length", s.length},
                          {"bend", s.bend},   {"drift", s.drift},   {"seed", s.seed}};
  } else if (c.input.gltf) {
    const GltfInputOptions& g = *c.input.gltf;
    const auto selector = [](const std::string& name, const std::optional<int>& index) {
      return index ? json(*index) : name.empty() ? json(nullptr) : json(name);
    };
    input["gltf"] = g.file.string();
    input["mesh"] = selector(g.mesh, g.mesh_index);
    input["animation"] = selector(g.animation, g.animation_index);
    input["fps"] = g.fps ? json(*g.fps) : json(nullptr);
  } else {
    input["frames"] = c.input.frames.string();
  }
  input["range"] = {{"start", c.input.range.start},
                    {"stop", c.input.range.stop ? json(*c.input.range.stop) : json(nullptr)},
                    {"step", c.input.range.step}};
  j["input"] = input;
  if (c.templ.mesh.empty())
    j["template"] = {{"frame", c.templ.frame}, {"optimize", c.templ.optimize}};
  else
    j["template"] = {{"mesh", c.templ.mesh.string()}, {"optimize", false}};
  j["output"] = {{"dir", c.output.dir.string()},
                 {"format", name_of(c.output.format, kFormats)},
                 {"per_triangle_csv", c.output.per_triangle_csv},
                 {"timings", c.output.timings},
                 {"on_failure", name_of(c.output.on_failure, kOnFailure)}};
  visual_outputs_to_json(c.output, j["output"]);
  if (c.output.format == OutputFormat::Gltf)
    j["output"]["gltf"] = {{"frames_per_mesh", c.output.gltf.frames_per_mesh},
                           {"normals", c.output.gltf.normals}};
  const MassageOptions& m = c.massage;
  j["massage"] = {{"weights", name_of(m.weights, kWeights)},
                  {"boundary_weights", name_of(m.boundary_weights, kBoundary)},
                  {"shape_target", name_of(m.shape_target, kShapeTargets)},
                  {"iterations", m.iterations},
                  {"mu", m.mu ? json(*m.mu) : json("auto")},
                  {"samples", name_of(m.samples, kSamples)},
                  {"tolerance", m.tolerance},
                  {"lawson", m.lawson},
                  {"lawson_floor", m.lawson_floor},
                  {"solver", name_of(m.solver, kSolvers)},
                  {"solver_tolerance", m.solver_tolerance},
                  {"solver_max_iterations", m.solver_max_iterations},
                  {"closest_points", name_of(m.closest_points, kClosest)},
                  {"walk_max_steps", m.walk_max_steps},
                  {"pin_boundary", m.pin_boundary},
                  {"pinned", m.pinned}};
  j["measures"] = {{"spacing", c.measures.spacing},
                   {"sample_edges", c.measures.sample_edges},
                   {"sample_faces", c.measures.sample_faces},
                   {"adaptive", c.measures.adaptive},
                   {"refine_above", c.measures.refine_above}};
  j["threads"] = c.threads;
  j["frames_in_flight"] = c.frames_in_flight;
  const FrameChecks& checks = c.checks;
  j["checks"] = {{"max_folded_triangles",
                  checks.max_folded_triangles ? json(*checks.max_folded_triangles) : json(nullptr)},
                 {"max_folded_fraction",
                  checks.max_folded_fraction ? json(*checks.max_folded_fraction) : json(nullptr)}};
  j["shard"] = {{"index", c.shard.index}, {"count", c.shard.count}};
  j["resume"] = c.resume;
  return j;
}

FrameRange parse_frame_range(std::string_view text, std::string_view what) {
  const std::string name(what);
  auto bad = [&]() {
    fail(name,
         "expected A:B[:STEP] (frame indices from A to before B, by STEP; B may be empty), "
         "got \"" +
             std::string(text) + "\"");
  };
  std::vector<std::string> parts;
  size_t begin = 0;
  while (true) {
    const size_t colon = text.find(':', begin);
    parts.emplace_back(text.substr(begin, colon == std::string_view::npos ? colon : colon - begin));
    if (colon == std::string_view::npos) break;
    begin = colon + 1;
  }
  if (parts.size() > 3) bad();
  auto number = [&](const std::string& s) {
    if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) bad();
    return std::stoi(s);
  };
  FrameRange r;
  if (parts.size() == 1) {  // a single frame
    r.start = number(parts[0]);
    r.stop = r.start + 1;
    return r;
  }
  r.start = parts[0].empty() ? 0 : number(parts[0]);
  if (!parts[1].empty()) r.stop = number(parts[1]);
  if (parts.size() == 3) r.step = number(parts[2]);
  if (r.step < 1) fail(name, "STEP must be >= 1, got \"" + std::string(text) + "\"");
  if (r.stop && *r.stop < r.start) fail(name, "B must be >= A, got \"" + std::string(text) + "\"");
  return r;
}

ShardConfig parse_shard(std::string_view text, std::string_view what) {
  const std::string name(what);
  const auto bad = [&](const std::string& why) {
    fail(name, why + ", got \"" + std::string(text) + "\"");
  };
  const size_t slash = text.find('/');
  const auto number = [&](std::string_view s) {
    if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string_view::npos)
      bad("expected I/N: shard I (0-based) of N, e.g. 0/4");
    return std::stoi(std::string(s));
  };
  if (slash == std::string_view::npos) bad("expected I/N: shard I (0-based) of N, e.g. 0/4");
  ShardConfig shard;
  shard.index = number(text.substr(0, slash));
  shard.count = number(text.substr(slash + 1));
  if (shard.count < 1 || shard.count > 100000) bad("N must be in [1, 100000]");
  if (shard.index >= shard.count)
    bad("I is 0-based and must be below N (like a Slurm array task id or a Kubernetes "
        "JOB_COMPLETION_INDEX)");
  return shard;
}

std::string format_shard(const ShardConfig& shard) {
  return std::to_string(shard.index) + "/" + std::to_string(shard.count);
}

std::string format_frame_range(const FrameRange& range) {
  return std::to_string(range.start) + ":" + (range.stop ? std::to_string(*range.stop) : "") + ":" +
         std::to_string(range.step);
}

// -----------------------------------------------------------------------------------------------
// The single-mesh jobs ("remesh", "crossparam", "smooth"): their own sections, parsed here so the
// sequence job's parsing above stays as it is. "input" means something else per job kind.

namespace {

const Names<JobKind> kAllJobs = {{"sequence", JobKind::Sequence},
                                 {"remesh", JobKind::Remesh},
                                 {"crossparam", JobKind::Crossparam},
                                 {"smooth", JobKind::Smooth}};
const Names<MeshOutputFormat> kMeshFormats = {{"same", MeshOutputFormat::Same},
                                              {"obj", MeshOutputFormat::Obj},
                                              {"off", MeshOutputFormat::Off},
                                              {"ply", MeshOutputFormat::Ply}};
// Keys that only the sequence job's "input" knows (including its glTF input), refused with a note.
const std::vector<std::string> kSequenceInputKeys = {"frames", "synthetic", "range",
                                                     "gltf",   "animation", "fps"};

void read_mesh_input(const Section& s, JobKind job, const fs::path& base, MeshJobInput& in) {
  for (const std::string& key : kSequenceInputKeys)
    if (s.has(key))
      fail(s.path(key), "only for \"job\": \"sequence\"; the " + job_name(job) +
                            " job reads one mesh file from \"input.mesh\"");
  s.require("mesh", "the mesh file to optimize (.obj, .off or .ply)");
  in.mesh = read_path(s, "mesh", base);
  if (job == JobKind::Remesh) {
    s.require("reference", "the source surface the remesh approximates (.obj, .off or .ply)");
    in.reference = read_path(s, "reference", base);
  } else if (s.has("reference")) {
    fail(s.path("reference"), "only for \"job\": \"remesh\"; the " + job_name(job) +
                                  " job keeps the mesh close to itself as loaded");
  }
}

void read_measures(const Section& s, MeasureOptions& m) {
  read(s, "spacing", m.spacing, Interval{0.0, true});
  read(s, "feature_angle", m.feature_angle, Interval{0.0, true, 180.0, true});
  if (const json* v = s.get("shear_bins")) {
    const std::string path = s.path("shear_bins");
    if (!v->is_array() || v->size() < 2)
      fail(path, "expected an array of at least two increasing bin edges, got " + describe(*v));
    std::vector<double> edges;
    for (size_t i = 0; i < v->size(); ++i) {
      const json& e = (*v)[i];
      const std::string where = path + "[" + std::to_string(i) + "]";
      double x = 0.0;
      if (e.is_string() && e.get<std::string>() == "inf")
        x = INFINITY;
      else if (e.is_number() && std::isfinite(e.get<double>()))
        x = e.get<double>();
      else
        fail(where, "expected a number or \"inf\", got " + describe(e));
      if (!edges.empty() && !(x > edges.back()))
        fail(where,
             "bin edges must increase, got " + describe(e) + " after " + describe((*v)[i - 1]));
      edges.push_back(x);
    }
    m.shear_bins = std::move(edges);
  }
}

}  // namespace

DistanceOptions default_sequence_measures() {
  DistanceOptions o;  // the sampling's defaults, but adaptive (README, "Performance")
  o.adaptive = true;
  o.spacing = 0.125;
  o.corresponding_triangles = true;
  return o;
}

MassageOptions default_massage_options(JobKind job) {
  MassageOptions o;
  if (job == JobKind::Smooth) {
    // Uniform weights equalize the triangles (§4). Every vertex is tied to its current closest
    // point, so the tangential relaxation advances only so far per iteration: on the paper's
    // fandisk, 15 iterations reach a mean radius ratio of 0.937, 60 reach 0.947. Edge samples keep
    // the distance low; with them the automatic μ climbs to 0.75-0.78 (‖B‖ grows with the samples
    // and with Lawson's weights) and a few sharp edges get cut, which μ = 0.7 avoids. README,
    // "Reproducing the paper", has the numbers.
    o.weights = WeightKind::Uniform;
    // T is M itself, so the rotated template target would keep M's shapes exactly: smoothing
    // needs the paper's zero target.
    o.shape_target = ShapeTargetKind::Zero;
    o.iterations = 60;
    o.samples = SampleKind::Edges;
    o.mu = 0.7;
  }
  return o;
}

std::string job_name(JobKind job) {
  return name_of(job, kAllJobs);
}

JobKind parse_job_kind(const json& document) {
  if (!document.is_object()) fail("", "expected an object, got " + describe(document));
  const auto it = document.find("job");
  if (it == document.end())
    fail("job", "missing (the kind of job: " + quoted_list(keys_of(kAllJobs)) + ")");
  JobKind job = JobKind::Sequence;
  const json only_job = {{"job", *it}};  // the other keys are checked by the job's parser
  read(Section(&only_job, "", {"job"}), "job", job, kAllJobs);
  return job;
}

MeshJobConfig parse_mesh_job_config(const json& document, const fs::path& base_dir) {
  const fs::path base = fs::absolute(base_dir).lexically_normal();
  MeshJobConfig c;
  c.job = parse_job_kind(document);
  if (c.job == JobKind::Sequence)
    fail("job", "\"sequence\" is not a single-mesh job (use parse_config)");
  const Section root(&document, "",
                     {"job", "input", "template", "output", "massage", "measures", "threads"});

  const std::string what_input = c.job == JobKind::Remesh
                                     ? "\"mesh\": the remesh, and \"reference\": its source"
                                     : "\"mesh\": the mesh file to optimize";
  read_mesh_input(Section(&root.require("input", what_input), "input",
                          [&] {
                            std::vector<std::string> keys = {"mesh", "reference"};
                            keys.insert(keys.end(), kSequenceInputKeys.begin(),
                                        kSequenceInputKeys.end());
                            return keys;
                          }()),
                  c.job, base, c.input);

  if (c.job == JobKind::Crossparam) {
    const Section templ(&root.require("template",
                                      "an object with \"mesh\": the source mesh whose "
                                      "triangle shapes are copied"),
                        "template", {"mesh", "frame", "optimize"});
    if (templ.has("frame") || templ.has("optimize"))
      fail(templ.path(templ.has("frame") ? "frame" : "optimize"),
           "only for \"job\": \"sequence\"; the crossparam template is a \"mesh\" file");
    templ.require("mesh", "the source mesh, with the input's connectivity");
    c.template_mesh = read_path(templ, "mesh", base);
  } else if (root.has("template")) {
    fail("template", c.job == JobKind::Remesh
                         ? "not used by the remesh job (the remesh is its own template)"
                         : "not used by the smooth job (it uses uniform or mean value weights of "
                           "the mesh itself)");
  }

  const Section output(&root.require("output", "an object with \"dir\", the output folder"),
                       "output", {"dir", "format", "per_triangle_csv", "timings"});
  output.require("dir", "the folder the results are written to");
  c.output.dir = read_path(output, "dir", base);
  read(output, "format", c.output.format, kMeshFormats);
  read(output, "per_triangle_csv", c.output.per_triangle_csv);
  read(output, "timings", c.output.timings);

  c.massage = default_massage_options(c.job);
  read_massage(Section(root.get("massage"), "massage", kMassageKeys), c.massage);
  read_measures(
      Section(root.get("measures"), "measures", {"spacing", "feature_angle", "shear_bins"}),
      c.measures);
  read(root, "threads", c.threads, 0, 4096);
  return c;
}

json to_json(const MeshJobConfig& c) {
  json j;
  j["job"] = job_name(c.job);
  j["input"] = {{"mesh", c.input.mesh.string()}};
  if (c.job == JobKind::Remesh) j["input"]["reference"] = c.input.reference.string();
  if (c.job == JobKind::Crossparam) j["template"] = {{"mesh", c.template_mesh.string()}};
  j["output"] = {{"dir", c.output.dir.string()},
                 {"format", name_of(c.output.format, kMeshFormats)},
                 {"per_triangle_csv", c.output.per_triangle_csv},
                 {"timings", c.output.timings}};
  JobConfig sequence;  // the "massage" section is written the same way for every job
  sequence.massage = c.massage;
  j["massage"] = to_json(sequence)["massage"];
  json bins = json::array();
  for (double e : c.measures.shear_bins) bins.push_back(std::isfinite(e) ? json(e) : json("inf"));
  j["measures"] = {{"spacing", c.measures.spacing},
                   {"feature_angle", c.measures.feature_angle},
                   {"shear_bins", bins}};
  j["threads"] = c.threads;
  return j;
}

AnyJobConfig parse_any_config(const json& document, const fs::path& base_dir) {
  if (parse_job_kind(document) == JobKind::Sequence) return parse_config(document, base_dir);
  return parse_mesh_job_config(document, base_dir);
}

AnyJobConfig load_any_config(const fs::path& path) {
  const std::string text = read_file(path);
  return parse_any_config(parse_json_strict(text), fs::absolute(path).parent_path());
}

}  // namespace sm
