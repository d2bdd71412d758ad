// The configuration of the single-mesh jobs (remesh, crossparam, smooth): the issue's examples,
// defaults per job, every key, the dispatch by "job", and the messages of invalid configs.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "config/config.hpp"
#include "core/errors.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
using json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

const fs::path kBase = "/data/project/configs";

MeshJobOptions parse(const std::string& text) {
  return parse_mesh_job_config(parse_json_strict(text), kBase);
}

std::string config_error(const std::string& text) {
  try {
    parse_any_config(parse_json_strict(text), kBase);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

const std::string kRemesh =
    R"({ "job": "remesh", "input": { "mesh": "bunny_remesh.off", "reference": "bunny.off" }, "output": { "dir": "out" } })";
const std::string kCrossparam =
    R"({ "job": "crossparam", "input": { "mesh": "man.obj" }, "template": { "mesh": "horse.obj" }, "output": { "dir": "out" } })";
const std::string kSmooth =
    R"({ "job": "smooth", "input": { "mesh": "fandisk.obj" }, "output": { "dir": "out" } })";

// `base` with `section` replaced by `value` (JSON text).
std::string with(const std::string& base, const std::string& section, const std::string& value) {
  json j = json::parse(base);
  j[section] = json::parse(value);
  return j.dump();
}

}  // namespace

TEST_CASE("the issue's three example configs parse, paths against the config's folder") {
  const MeshJobOptions r = parse(kRemesh);
  CHECK(r.job == JobKind::Remesh);
  CHECK(r.input.mesh == fs::path("/data/project/configs/bunny_remesh.off"));
  CHECK(r.input.reference == fs::path("/data/project/configs/bunny.off"));
  CHECK(r.templ.mesh.empty());
  CHECK(r.output.dir == fs::path("/data/project/configs/out"));
  CHECK(r.output.format == MeshOutputFormat::Same);

  const MeshJobOptions c = parse(kCrossparam);
  CHECK(c.job == JobKind::Crossparam);
  CHECK(c.input.mesh == fs::path("/data/project/configs/man.obj"));
  CHECK(c.input.reference.empty());
  CHECK(c.templ.mesh == fs::path("/data/project/configs/horse.obj"));

  const MeshJobOptions s = parse(kSmooth);
  CHECK(s.job == JobKind::Smooth);
  CHECK(s.input.mesh == fs::path("/data/project/configs/fandisk.obj"));
}

TEST_CASE("defaults: MassageOptions' for remesh and crossparam, uniform weights for smooth") {
  const MassageOptions plain;
  for (const std::string& text : {kRemesh, kCrossparam}) {
    const MeshJobOptions c = parse(text);
    CHECK(c.massage.weights == WeightKind::MeanValue);
    CHECK(c.massage.iterations == plain.iterations);
    CHECK(c.massage.samples == SampleKind::Vertices);
    CHECK_FALSE(c.massage.mu);
    CHECK_FALSE(c.massage.pin_boundary);
    CHECK(c.massage.pinned.empty());
  }
  const MeshJobOptions s = parse(kSmooth);
  CHECK(s.massage.weights == WeightKind::Uniform);
  CHECK(s.massage.iterations == 60);
  CHECK(s.massage.samples == SampleKind::Edges);
  REQUIRE(s.massage.mu);
  CHECK(*s.massage.mu == 0.7);
  CHECK(s.massage.iterations == default_massage_options(JobKind::Smooth).iterations);
  CHECK_FALSE(parse(with(kSmooth, "massage", R"({"mu": "auto"})")).massage.mu);
  // Smoothing with mean value weights on request.
  CHECK(parse(with(kSmooth, "massage", R"({"weights": "mean_value"})")).massage.weights ==
        WeightKind::MeanValue);
  const MeshJobOptions d = parse(kSmooth);
  const MeasureOptions m;
  CHECK(d.measures.spacing == m.spacing);
  CHECK(d.measures.feature_angle == 30.0);
  CHECK(d.measures.shear_bins.size() == m.shear_bins.size());
  CHECK(std::isinf(d.measures.shear_bins.back()));
  CHECK(d.output.timings);
  CHECK_FALSE(d.output.per_triangle_csv);
  CHECK(d.threads == 0);
}

TEST_CASE("every key of the single-mesh jobs is settable") {
  const MeshJobOptions c = parse(R"({"job": "smooth", "input": {"mesh": "/abs/m.ply"},
    "output": {"dir": "o", "format": "off", "per_triangle_csv": true, "timings": false},
    "massage": {"weights": "mean_value", "iterations": 7, "mu": 0.3, "samples": "faces",
                "pin_boundary": true, "pinned": [3, 1]},
    "measures": {"spacing": 0.5, "feature_angle": 45, "shear_bins": [0, 0.5, 1, "inf"]},
    "threads": 2})");
  CHECK(c.input.mesh == fs::path("/abs/m.ply"));
  CHECK(c.output.format == MeshOutputFormat::Off);
  CHECK(c.output.per_triangle_csv);
  CHECK_FALSE(c.output.timings);
  CHECK(c.massage.weights == WeightKind::MeanValue);
  CHECK(c.massage.iterations == 7);
  CHECK(*c.massage.mu == 0.3);
  CHECK(c.massage.samples == SampleKind::Faces);
  CHECK(c.massage.pin_boundary);
  CHECK(c.massage.pinned == std::vector<int>{3, 1});
  CHECK(c.measures.spacing == 0.5);
  CHECK(c.measures.feature_angle == 45);
  REQUIRE(c.measures.shear_bins.size() == 4);
  CHECK(std::isinf(c.measures.shear_bins[3]));
  CHECK(c.threads == 2);
}

TEST_CASE("the massage section accepts every key the sequence job's does") {
  SequenceJobOptions sequence;
  const json keys = to_json(sequence)["massage"];
  json doc = json::parse(kRemesh);
  doc["massage"] = keys;
  const MeshJobOptions c = parse_mesh_job_config(doc, kBase);
  CHECK(to_json(c)["massage"] == keys);
}

TEST_CASE("the resolved single-mesh config round-trips through to_json") {
  for (const std::string& text :
       {kRemesh, kCrossparam, kSmooth,
        with(kSmooth, "measures", R"({"shear_bins": [0, 1, "inf"], "feature_angle": 20})")}) {
    const MeshJobOptions c = parse(text);
    const json resolved = to_json(c);
    CHECK(to_json(parse_mesh_job_config(resolved, "/elsewhere")) == resolved);
  }
  CHECK(to_json(parse(kRemesh))["input"]["reference"] == "/data/project/configs/bunny.off");
  CHECK(to_json(parse(kCrossparam))["template"]["mesh"] == "/data/project/configs/horse.obj");
  CHECK_FALSE(to_json(parse(kSmooth)).contains("template"));
  CHECK(to_json(parse(kSmooth))["measures"]["shear_bins"].back() == "inf");
}

TEST_CASE("parse_any_config dispatches on the job kind") {
  const AnyJobOptions seq = parse_any_config(
      json::parse(R"({"job": "sequence", "input": {"frames": "f"}, "output": {"dir": "o"}})"),
      kBase);
  CHECK(std::holds_alternative<SequenceJobOptions>(seq));
  const AnyJobOptions mesh = parse_any_config(json::parse(kSmooth), kBase);
  REQUIRE(std::holds_alternative<MeshJobOptions>(mesh));
  CHECK(std::get<MeshJobOptions>(mesh).job == JobKind::Smooth);
  CHECK(job_name(JobKind::Crossparam) == "crossparam");

  const test::TempDir temp("mesh_job_config");
  const fs::path& dir = temp.path();
  fs::create_directories(dir);
  std::ofstream(dir / "job.json") << kRemesh;
  const AnyJobOptions loaded = load_any_config(dir / "job.json");
  REQUIRE(std::holds_alternative<MeshJobOptions>(loaded));
  CHECK(std::get<MeshJobOptions>(loaded).input.reference == dir / "bunny.off");
}

TEST_CASE("bad single-mesh configs name the key") {
  CHECK(config_error(R"({"job": "smoth", "input": {"mesh": "m.obj"}, "output": {"dir": "o"}})") ==
        "job: expected \"sequence\", \"remesh\", \"crossparam\", \"smooth\", or \"track\", got "
        "\"smoth\" (did you mean \"smooth\"?)");
  CHECK(config_error(R"({"input": {"mesh": "m.obj"}, "output": {"dir": "o"}})") ==
        "job: missing (the kind of job: \"sequence\", \"remesh\", \"crossparam\", \"smooth\", or "
        "\"track\")");
  CHECK(config_error(R"({"job": "remesh", "input": {"mesh": "m.off"}, "output": {"dir": "o"}})") ==
        "input.reference: missing (the source surface the remesh approximates (.obj, .off or "
        ".ply))");
  CHECK(config_error(with(kRemesh, "input", R"({"mesh": "m.off", "refrence": "n.off"})")) ==
        "input.refrence: unknown key (did you mean \"reference\"?)");
  CHECK(config_error(with(kSmooth, "input", R"({"mesh": "m.off", "reference": "n.off"})")) ==
        "input.reference: only for \"job\": \"remesh\"; the smooth job keeps the mesh close to "
        "itself as loaded");
  CHECK(config_error(with(kSmooth, "input", R"({"frames": "f"})")) ==
        "input.frames: only for \"job\": \"sequence\"; the smooth job reads one mesh file from "
        "\"input.mesh\"");
  CHECK(config_error(with(kSmooth, "input", R"({"gltf": "take.glb", "mesh": 0})")) ==
        "input.gltf: only for \"job\": \"sequence\"; the smooth job reads one mesh file from "
        "\"input.mesh\"");
  CHECK(config_error(with(kSmooth, "input", R"({"mesh": 3})")) ==
        "input.mesh: expected a path (a non-empty string), got 3");
  CHECK(config_error(with(kSmooth, "input", R"({})")) ==
        "input.mesh: missing (the mesh file to optimize (.obj, .off or .ply))");
  CHECK(config_error(R"({"job": "smooth", "output": {"dir": "o"}})") ==
        "input: missing (\"mesh\": the mesh file to optimize)");
  CHECK(config_error(
            R"({"job": "crossparam", "input": {"mesh": "m.obj"}, "output": {"dir": "o"}})") ==
        "template: missing (an object with \"mesh\": the source mesh whose triangle shapes are "
        "copied)");
  CHECK(config_error(with(kCrossparam, "template", R"({"frame": 0})")) ==
        "template.frame: only for \"job\": \"sequence\"; the crossparam template is a \"mesh\" "
        "file");
  CHECK(config_error(with(kCrossparam, "template", R"({"mseh": "h.obj"})")) ==
        "template.mseh: unknown key (did you mean \"mesh\"?)");
  CHECK(config_error(with(kRemesh, "template", R"({"mesh": "t.obj"})")) ==
        "template: not used by the remesh job (the remesh is its own template)");
  CHECK(config_error(with(kSmooth, "template", R"({"mesh": "t.obj"})"))
            .rfind("template: not used by the smooth job", 0) == 0);
  CHECK(config_error(with(kSmooth, "output", R"({"dir": "o", "format": "stl"})")) ==
        "output.format: expected \"same\", \"obj\", \"off\", or \"ply\", got \"stl\"");
  CHECK(config_error(with(kSmooth, "output", R"({"dir": "o", "format": "pyl"})")) ==
        "output.format: expected \"same\", \"obj\", \"off\", or \"ply\", got \"pyl\" (did you "
        "mean \"ply\"?)");
  CHECK(config_error(with(kSmooth, "output", R"({"format": "obj"})")) ==
        "output.dir: missing (the folder the results are written to)");
  CHECK(config_error(with(kSmooth, "massage", R"({"iteratons": 10})")) ==
        "massage.iteratons: unknown key (did you mean \"iterations\"?)");
  CHECK(config_error(with(kSmooth, "massage", R"({"pinned": [0, "a"]})")) ==
        "massage.pinned[1]: expected an integer >= 0, got \"a\"");
  CHECK(config_error(with(kSmooth, "measures", R"({"spacing": 0})")) ==
        "measures.spacing: expected a number > 0, got 0");
  CHECK(config_error(with(kSmooth, "measures", R"({"feature_angle": 180})")) ==
        "measures.feature_angle: expected a number in (0, 180), got 180");
  CHECK(config_error(with(kSmooth, "measures", R"({"shear_bins": [0, 1, 1]})")) ==
        "measures.shear_bins[2]: bin edges must increase, got 1 after 1");
  CHECK(config_error(with(kSmooth, "measures", R"({"shear_bins": [0]})")) ==
        "measures.shear_bins: expected an array of at least two increasing bin edges, got an "
        "array");
  CHECK(config_error(with(kSmooth, "measures", R"({"shear_bins": [0, "infinity"]})")) ==
        "measures.shear_bins[1]: expected a number or \"inf\", got \"infinity\"");
  CHECK(config_error(with(kSmooth, "measures", R"({"featur_angle": 10})")) ==
        "measures.featur_angle: unknown key (did you mean \"feature_angle\"?)");
  CHECK(config_error(with(kSmooth, "frames_in_flight", "2")) ==
        "frames_in_flight: unknown key (known keys: \"job\", \"input\", \"template\", "
        "\"output\", \"massage\", \"measures\", or \"threads\")");
  CHECK(config_error(with(kSmooth, "threads", "5000")) ==
        "threads: expected an integer in [0, 4096], got 5000");
}
