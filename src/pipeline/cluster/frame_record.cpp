#include "pipeline/cluster/frame_record.hpp"

#include <sys/stat.h>

#include <cmath>
#include <limits>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/sha256.hpp"
#include "core/errors.hpp"
#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/report/report.hpp"
#include "pipeline/report/report_json.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

[[noreturn]] void bad(const std::string& key, const std::string& what) {
  throw InputError("frame record: " + key + ": " + what);
}

const json& at(const json& j, const std::string& key, const std::string& where) {
  const std::string path = where.empty() ? key : where + "." + key;
  if (!j.is_object()) bad(where.empty() ? "record" : where, "expected an object");
  const auto it = j.find(key);
  if (it == j.end()) bad(path, "missing");
  return *it;
}

double get_double(const json& j, const std::string& key, const std::string& where);

json split_json(const CorrespondenceError& e) {
  return {{"mean", json_number(e.mean)},
          {"max", json_number(e.max)},
          {"tangential_mean", json_number(e.tangential_mean)},
          {"tangential_max", json_number(e.tangential_max)},
          {"normal_mean", json_number(e.normal_mean)},
          {"normal_max", json_number(e.normal_max)}};
}

CorrespondenceError split_from_json(const json& j, const std::string& w) {
  return {get_double(j, "mean", w),          get_double(j, "max", w),
          get_double(j, "tangential_mean", w), get_double(j, "tangential_max", w),
          get_double(j, "normal_mean", w),     get_double(j, "normal_max", w)};
}

double get_double(const json& j, const std::string& key, const std::string& where) {
  const json& v = at(j, key, where);
  if (v.is_number()) return v.get<double>();
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
  }
  bad(where + "." + key, "expected a number, got " + v.dump());
}

template <class T>
T get(const json& j, const std::string& key, const std::string& where) {
  const json& v = at(j, key, where);
  try {
    return v.get<T>();
  } catch (const json::exception&) {
    bad(where.empty() ? key : where + "." + key, "wrong type: " + v.dump());
  }
}

json to_json(const DistortionSummary& d) {
  return {{"max", json_number(d.max)},
          {"mean", json_number(d.mean)},
          {"p95", json_number(d.p95)},
          {"infinite", d.infinite}};
}

DistortionSummary distortion_from_json(const json& j, const std::string& where) {
  DistortionSummary d;
  d.max = get_double(j, "max", where);
  d.mean = get_double(j, "mean", where);
  d.p95 = get_double(j, "p95", where);
  d.infinite = get<int>(j, "infinite", where);
  return d;
}

DistanceStats distance_from_json(const json& j, const std::string& where) {
  DistanceStats d;
  d.max = get_double(j, "max", where);
  d.mean = get_double(j, "mean", where);
  d.rms = get_double(j, "rms", where);
  d.max_rel = get_double(j, "max_rel", where);
  d.mean_rel = get_double(j, "mean_rel", where);
  d.rms_rel = get_double(j, "rms_rel", where);
  d.samples = get<long>(j, "samples", where);
  return d;
}

FrameStatus status_from_name(const std::string& name) {
  for (FrameStatus s : {FrameStatus::Optimized, FrameStatus::Template, FrameStatus::Failed})
    if (name == status_name(s)) return s;
  bad("summary.status", "unknown status \"" + name + "\"");
}

}  // namespace

fs::path record_file(const fs::path& output_dir, const std::string& frame_name) {
  return output_dir / "records" / fs::path(frame_name).replace_extension(".json");
}

std::string frame_config_hash(const SequenceJobOptions& config) {
  return frame_config_hash(config, version_info());
}

std::string frame_config_hash(const SequenceJobOptions& config, const json& versions) {
  json j = to_json(config);
  for (const char* key : {"threads", "frames_in_flight", "shard", "resume"}) j.erase(key);
  j["input"].erase("range");
  j["output"].erase("timings");
  j["output"].erase("dir");  // a moved output folder keeps its records
  std::string text = j.dump() + "\n" + versions.dump();
  // The weights read from massage.vertex_weights: a changed file is a changed config.
  const std::vector<double>& w = config.massage.vertex_weights;
  if (!w.empty()) text.append(reinterpret_cast<const char*>(w.data()), w.size() * sizeof(double));
  return sha256_hex(text);
}

std::string template_hash(const TriMesh& templ) {
  Sha256 hash;
  const int64_t sizes[2] = {templ.V.rows(), templ.F.rows()};
  hash.update(sizes, sizeof sizes);
  hash.update(templ.V.data(), size_t(templ.V.size()) * sizeof(double));
  hash.update(templ.F.data(), size_t(templ.F.size()) * sizeof(int));
  return hash.hex();
}

json to_json(const FrameSummary& s) {
  json j;
  j["frame"] = s.frame;
  j["file"] = s.file;
  j["time"] = s.time ? json_number(*s.time) : json(nullptr);
  j["vertices"] = s.vertices;
  j["triangles"] = s.triangles;
  j["shear_before"] = to_json(s.shear_before);
  j["shear_after"] = to_json(s.shear_after);
  j["out_to_in"] = distance_json(s.out_to_in);
  j["in_to_out"] = distance_json(s.in_to_out);
  j["iterations"] = s.iterations;
  j["seconds"] = json_number(s.seconds);
  j["status"] = status_name(s.status);
  j["failure"] = s.failure;
  j["folded_triangles"] = s.folded_triangles;
  if (s.ground_truth) {
    const GroundTruthError& g = *s.ground_truth;
    j["ground_truth"] = {{"mean_before", json_number(g.mean_before)},
                         {"max_before", json_number(g.max_before)},
                         {"mean_after", json_number(g.mean_after)},
                         {"max_after", json_number(g.max_after)},
                         {"split_before", split_json(g.split_before)},
                         {"split_after", split_json(g.split_after)}};
  } else {
    j["ground_truth"] = nullptr;
  }
  j["warnings"] = s.warnings;
  return j;
}

FrameSummary frame_summary_from_json(const json& j) {
  const std::string w = "summary";
  FrameSummary s;
  s.frame = get<int>(j, "frame", w);
  s.file = get<std::string>(j, "file", w);
  if (!at(j, "time", w).is_null()) s.time = get_double(j, "time", w);
  s.vertices = get<int>(j, "vertices", w);
  s.triangles = get<int>(j, "triangles", w);
  s.shear_before = distortion_from_json(at(j, "shear_before", w), w + ".shear_before");
  s.shear_after = distortion_from_json(at(j, "shear_after", w), w + ".shear_after");
  s.out_to_in = distance_from_json(at(j, "out_to_in", w), w + ".out_to_in");
  s.in_to_out = distance_from_json(at(j, "in_to_out", w), w + ".in_to_out");
  s.iterations = get<int>(j, "iterations", w);
  s.seconds = get_double(j, "seconds", w);
  s.status = status_from_name(get<std::string>(j, "status", w));
  s.failure = get<std::string>(j, "failure", w);
  s.folded_triangles = get<int>(j, "folded_triangles", w);
  if (const json& g = at(j, "ground_truth", w); !g.is_null()) {
    const std::string where = w + ".ground_truth";
    s.ground_truth = GroundTruthError{
        get_double(g, "mean_before", where), get_double(g, "max_before", where),
        get_double(g, "mean_after", where), get_double(g, "max_after", where), {}, {}};
    // (Records written before the split have none: they keep zeros.)
    if (g.contains("split_before"))
      s.ground_truth->split_before = split_from_json(g["split_before"], where + ".split_before");
    if (g.contains("split_after"))
      s.ground_truth->split_after = split_from_json(g["split_after"], where + ".split_after");
  }
  s.warnings = get<std::vector<std::string>>(j, "warnings", w);
  return s;
}

json to_json(const FrameRecord& r) {
  json outputs = json::array();
  for (const RecordedOutput& o : r.outputs)
    outputs.push_back({{"path", o.path}, {"size", o.size}, {"sha256", o.sha256}});
  json j = {{"format", kFrameRecordFormat},
            {"config_hash", r.config_hash},
            {"template_hash", r.template_hash},
            {"input_hash", r.input_hash},
            {"outputs", outputs},
            {"summary", to_json(r.summary)}};
  for (const std::string& key : record_row_keys()) {  // each, empty where the output is off
    const auto rows = r.record_rows.find(key);
    j[key] = rows == r.record_rows.end() ? std::string() : rows->second;
  }
  return j;
}

FrameRecord frame_record_from_json(const json& j) {
  if (get<std::string>(j, "format", "") != kFrameRecordFormat)
    bad("format", "expected \"" + std::string(kFrameRecordFormat) + "\"");
  FrameRecord r;
  r.config_hash = get<std::string>(j, "config_hash", "");
  r.template_hash = get<std::string>(j, "template_hash", "");
  r.input_hash = get<std::string>(j, "input_hash", "");
  const json& outputs = at(j, "outputs", "");
  if (!outputs.is_array()) bad("outputs", "expected an array");
  for (size_t i = 0; i < outputs.size(); ++i) {
    const std::string where = "outputs[" + std::to_string(i) + "]";
    RecordedOutput o;
    o.path = get<std::string>(outputs[i], "path", where);
    o.size = get<uint64_t>(outputs[i], "size", where);
    o.sha256 = get<std::string>(outputs[i], "sha256", where);
    r.outputs.push_back(std::move(o));
  }
  r.summary = frame_summary_from_json(at(j, "summary", ""));
  for (const std::string& key : record_row_keys()) r.record_rows[key] = get<std::string>(j, key, "");
  return r;
}

std::optional<FrameRecord> read_frame_record(const fs::path& file, std::string* problem) {
  std::error_code ec;
  if (!fs::exists(file, ec)) {
    if (problem) *problem = "no record";
    return std::nullopt;
  }
  try {
    return frame_record_from_json(json::parse(read_file(file)));
  } catch (const std::exception& e) {
    if (problem) *problem = "unreadable record " + file.filename().string() + ": " + e.what();
    return std::nullopt;
  }
}

std::string confinement_problem(const fs::path& dir, const std::string& path) {
  const fs::path p(path);
  bool outside = path.empty() || p.has_root_name() || p.has_root_directory();
  for (const fs::path& part : p) outside = outside || part == "..";
  if (outside)
    return "the record names '" + path + "', which is not a path inside the output folder";
  fs::path at = dir;
  for (const fs::path& part : p) {
    if (part == "." || part.empty()) continue;
    at /= part;
    struct stat st {};
    if (::lstat(at.c_str(), &st) != 0) return "";
    if (S_ISLNK(st.st_mode))
      return path + ": " + at.lexically_relative(dir).generic_string() +
             " is a symbolic link (an output is a file the run wrote, never a link)";
  }
  return "";
}

std::string check_recorded_outputs(const FrameRecord& record, const fs::path& output_dir,
                                   bool check_content, bool* tampered) {
  if (tampered) *tampered = false;
  for (const RecordedOutput& o : record.outputs) {
    if (std::string problem = confinement_problem(output_dir, o.path); !problem.empty()) {
      if (tampered) *tampered = true;
      return problem;
    }
    const fs::path file = output_dir / fs::path(o.path);
    std::error_code ec;
    const uintmax_t size = fs::file_size(file, ec);
    if (ec) return o.path + " is missing";
    if (size != o.size)
      return o.path + " has " + std::to_string(size) + " bytes, the record says " +
             std::to_string(o.size);
    if (check_content) {
      std::string hash;
      try {
        hash = sha256_file(file);
      } catch (const IoError& e) {
        return e.what();
      }
      if (hash != o.sha256) {
        if (tampered) *tampered = true;
        return o.path + " changed since it was written (SHA-256 differs)";
      }
    }
  }
  return "";
}

}  // namespace sm
