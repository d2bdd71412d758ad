// The JSON job configuration: defaults, every key, paths, and the messages of invalid configs.
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

SequenceJobOptions parse(const std::string& text) {
  return parse_config(parse_json_strict(text), kBase);
}

// The message of the ConfigError that parsing `text` throws ("" if none).
std::string config_error(const std::string& text) {
  try {
    parse(text);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

const std::string kMinimal =
    R"({"job": "sequence", "input": {"frames": "take1"}, "output": {"dir": "out"}})";

// kMinimal with `section` replaced by `value` (a JSON object text).
std::string with(const std::string& section, const std::string& value) {
  json j = json::parse(kMinimal);
  j[section] = json::parse(value);
  return j.dump();
}

}  // namespace

TEST_CASE("a minimal config takes every default") {
  const SequenceJobOptions c = parse(kMinimal);
  const MassageOptions defaults;
  CHECK(c.job == JobKind::Sequence);
  CHECK(c.input.frames == fs::path("/data/project/configs/take1"));
  CHECK_FALSE(c.input.synthetic);
  CHECK(c.input.range.start == 0);
  CHECK_FALSE(c.input.range.stop);
  CHECK(c.input.range.step == 1);
  CHECK(c.templ.frame == 0);
  CHECK(c.templ.mesh.empty());
  CHECK_FALSE(c.templ.optimize);
  CHECK(c.output.dir == fs::path("/data/project/configs/out"));
  CHECK(c.output.format == OutputFormat::Obj);
  CHECK_FALSE(c.output.per_triangle_csv);
  CHECK(c.output.timings);
  CHECK(c.massage.iterations == defaults.iterations);
  CHECK_FALSE(c.massage.mu);
  CHECK(c.threads == 0);
  CHECK(c.frames_in_flight == 0);
}

TEST_CASE("the issue's example config parses, paths resolve against the config's folder") {
  const SequenceJobOptions c = parse(R"({ "job": "sequence",
    "input":    { "frames": "captures/take1" },
    "template": { "frame": 0 },
    "output":   { "dir": "../out/take1", "format": "obj", "per_triangle_csv": true },
    "massage":  { "weights": "mean_value", "iterations": 15, "mu": "auto", "samples": "vertices" },
    "threads": 0 })");
  CHECK(c.input.frames == fs::path("/data/project/configs/captures/take1"));
  CHECK(c.output.dir == fs::path("/data/project/out/take1"));
  CHECK(c.output.per_triangle_csv);
  CHECK(c.massage.weights == WeightKind::MeanValue);
  CHECK(c.massage.samples == SampleKind::Vertices);
  const SequenceJobOptions abs = parse(R"({"job": "sequence", "input": {"frames": "/abs/take"},
                                  "template": {"mesh": "rest.obj"}, "output": {"dir": "/o"}})");
  CHECK(abs.input.frames == fs::path("/abs/take"));
  CHECK(abs.templ.mesh == fs::path("/data/project/configs/rest.obj"));
}

TEST_CASE("every MassageOptions key is settable under massage") {
  const SequenceJobOptions c = parse(with("massage", R"({
    "weights": "uniform", "boundary_weights": "one_sided", "iterations": 7, "mu": 0.25, "samples": "faces", "tolerance": 0.01,
    "lawson": false, "lawson_floor": 1e-6, "solver": "direct", "solver_tolerance": 1e-8,
    "solver_max_iterations": 50, "closest_points": "exact", "walk_max_steps": 3,
    "pin_boundary": true, "pinned": [4, 2, 9]})"));
  const MassageOptions& m = c.massage;
  CHECK(m.weights == WeightKind::Uniform);
  CHECK(m.boundary_weights == BoundaryWeights::OneSided);
  CHECK(m.iterations == 7);
  REQUIRE(m.mu);
  CHECK(*m.mu == 0.25);
  CHECK(m.samples == SampleKind::Faces);
  CHECK(m.tolerance == 0.01);
  CHECK_FALSE(m.lawson);
  CHECK(m.lawson_floor == 1e-6);
  CHECK(m.solver == SolverKind::Direct);
  CHECK(m.solver_tolerance == 1e-8);
  CHECK(m.solver_max_iterations == 50);
  CHECK(m.closest_points == ClosestPointMode::Exact);
  CHECK(m.walk_max_steps == 3);
  CHECK(m.pin_boundary);
  CHECK(m.pinned == std::vector<int>{4, 2, 9});
}

TEST_CASE("measures: the sampling of summary.csv's distances, every DistanceOptions key") {
  const SequenceJobOptions defaults = parse(kMinimal);
  CHECK(defaults.measures.spacing == 0.125);
  CHECK(defaults.measures.sample_edges);
  CHECK(defaults.measures.sample_faces);
  CHECK(defaults.measures.adaptive);
  CHECK(defaults.measures.refine_above == 0.4);
  CHECK(defaults.measures.corresponding_triangles);  // set by the job, not a key
  const SequenceJobOptions c = parse(with("measures", R"({"spacing": 0.25, "sample_edges": false,
      "sample_faces": false, "adaptive": false, "refine_above": 0.75})"));
  CHECK(c.measures.spacing == 0.25);
  CHECK_FALSE(c.measures.sample_edges);
  CHECK_FALSE(c.measures.sample_faces);
  CHECK_FALSE(c.measures.adaptive);
  CHECK(c.measures.refine_above == 0.75);
  CHECK(c.measures.corresponding_triangles);
  const json resolved = to_json(c);
  CHECK(resolved["measures"] == json{{"spacing", 0.25},
                                     {"sample_edges", false},
                                     {"sample_faces", false},
                                     {"adaptive", false},
                                     {"refine_above", 0.75}});
  CHECK(to_json(parse_config(resolved, "/elsewhere")) == resolved);

  CHECK(config_error(with("measures", R"({"spacing": 0})")) ==
        "measures.spacing: expected a number > 0, got 0");
  CHECK(config_error(with("measures", R"({"spacing": "fine"})")) ==
        "measures.spacing: expected a number > 0, got \"fine\"");
  CHECK(config_error(with("measures", R"({"sample_edges": 1})")) ==
        "measures.sample_edges: expected true or false, got 1");
  CHECK(config_error(with("measures", R"({"refine_above": 1.5})"))
            .rfind("measures.refine_above: expected a number", 0) == 0);
  CHECK(config_error(with("measures", R"({"adaptive": "yes"})")) ==
        "measures.adaptive: expected true or false, got \"yes\"");
  CHECK(config_error(with("measures", R"({"spacng": 0.5})")) ==
        "measures.spacng: unknown key (did you mean \"spacing\"?)");
  CHECK(config_error(with("measures", R"({"feature_angle": 30})"))
            .rfind("measures.feature_angle: unknown key", 0) == 0);
  CHECK(config_error(with("measures", "0.5")) == "measures: expected an object, got 0.5");
}

TEST_CASE("the resolved config round-trips through to_json") {
  const SequenceJobOptions c = parse(R"({"job": "sequence",
    "input": {"synthetic": {"frames": 5, "bend": 45, "seed": 3}, "range": {"start": 1, "stop": 4, "step": 2}},
    "template": {"frame": 2, "optimize": true},
    "output": {"dir": "o", "per_triangle_csv": true, "timings": false},
    "massage": {"mu": 0.5, "pinned": [1], "solver": "direct"},
    "threads": 3, "frames_in_flight": 5})");
  const json resolved = to_json(c);
  CHECK(resolved["input"]["synthetic"]["frames"] == 5);
  CHECK(resolved["input"]["synthetic"]["shape"] == "bending_tube");
  CHECK(resolved["massage"]["mu"] == 0.5);
  CHECK(resolved["massage"]["iterations"] == 15);
  CHECK(resolved["output"]["dir"] == "/data/project/configs/o");
  const SequenceJobOptions again = parse_config(resolved, "/elsewhere");
  CHECK(to_json(again) == resolved);
  CHECK(to_json(parse(kMinimal))["massage"]["mu"] == "auto");
  CHECK(to_json(parse(kMinimal))["input"]["range"]["stop"].is_null());
}

TEST_CASE("unknown keys are named by their JSON path, with the nearest valid key") {
  CHECK(config_error(with("massage", R"({"iteratons": 10})")) ==
        "massage.iteratons: unknown key (did you mean \"iterations\"?)");
  CHECK(config_error(with("output", R"({"dir": "o", "per_triangle_cvs": true})")) ==
        "output.per_triangle_cvs: unknown key (did you mean \"per_triangle_csv\"?)");
  CHECK(config_error(with("Threads", "2")) == "Threads: unknown key (did you mean \"threads\"?)");
  const std::string far = config_error(with("massage", R"({"zzzzzzzz": 1})"));
  CHECK(far.rfind("massage.zzzzzzzz: unknown key (known keys: \"weights\", ", 0) == 0);
  CHECK(config_error(with("input", R"({"frames": "f", "range": {"strat": 2}})")) ==
        "input.range.strat: unknown key (did you mean \"start\"?)");
  CHECK(config_error(with("input", R"({"frames": "f", "range": {"begin": 2}})")) ==
        "input.range.begin: unknown key (known keys: \"start\", \"stop\", or \"step\")");
}

TEST_CASE("wrong types and out-of-range values name the key and the value") {
  CHECK(config_error(with("massage", R"({"iterations": "ten"})")) ==
        "massage.iterations: expected an integer >= 1, got \"ten\"");
  CHECK(config_error(with("massage", R"({"iterations": 0})")) ==
        "massage.iterations: expected an integer >= 1, got 0");
  CHECK(config_error(with("massage", R"({"iterations": 2.5})")) ==
        "massage.iterations: expected an integer >= 1, got 2.5");
  CHECK(config_error(with("massage", R"({"mu": 1.5})")) ==
        "massage.mu: expected \"auto\" or a number in [0, 1), got 1.5");
  CHECK(config_error(with("massage", R"({"mu": "automatic"})")) ==
        "massage.mu: expected \"auto\" or a number in [0, 1), got \"automatic\"");
  CHECK(config_error(with("massage", R"({"weights": "mean-value"})")) ==
        "massage.weights: expected \"mean_value\" or \"uniform\", got \"mean-value\" (did you mean "
        "\"mean_value\"?)");
  CHECK(config_error(with("massage", R"({"samples": 3})")) ==
        "massage.samples: expected \"vertices\", \"edges\", or \"faces\", got 3");
  CHECK(config_error(with("massage", R"({"lawson": "yes"})")) ==
        "massage.lawson: expected true or false, got \"yes\"");
  CHECK(config_error(with("massage", R"({"tolerance": -1})")) ==
        "massage.tolerance: expected a number >= 0, got -1");
  CHECK(config_error(with("massage", R"({"solver_tolerance": 0})")) ==
        "massage.solver_tolerance: expected a number in (0, 1), got 0");
  CHECK(config_error(with("massage", R"({"pinned": [1, -3]})")) ==
        "massage.pinned[1]: expected an integer >= 0, got -3");
  CHECK(config_error(with("massage", R"({"pinned": 4})")) ==
        "massage.pinned: expected an array of vertex indices, got 4");
  CHECK(config_error(with("massage", "[]")) == "massage: expected an object, got an array");
  CHECK(config_error(with("threads", "-1")) == "threads: expected an integer in [0, 4096], got -1");
  CHECK(config_error(with("output", R"({"dir": ""})")) ==
        "output.dir: expected a path (a non-empty string), got \"\"");
  CHECK(config_error(with("output", R"({"dir": "o", "format": "glft"})")) ==
        "output.format: expected \"obj\", \"gltf\", \"pc2\", or \"mdd\", got \"glft\" (did you "
        "mean \"gltf\"?)");
  CHECK(config_error(with("job", R"("remesh")")) == "job: expected \"sequence\", got \"remesh\"");
  CHECK(config_error("[1, 2]") == "config: expected an object, got an array");
}

TEST_CASE("a path with a NUL character is refused, naming the key") {
  json j = json::parse(kMinimal);
  j["input"]["frames"] = std::string("take1\0/x", 8);
  CHECK(config_error(j.dump()) == "input.frames: path contains a NUL character");
  j = json::parse(kMinimal);
  j["template"] = {{"mesh", std::string("rest\0.obj", 9)}};
  CHECK(config_error(j.dump()) == "template.mesh: path contains a NUL character");
}

TEST_CASE("missing and conflicting keys") {
  CHECK(config_error(R"({"input": {"frames": "f"}, "output": {"dir": "o"}})") ==
        "job: missing (the kind of job: \"sequence\")");
  CHECK(config_error(R"({"job": "sequence", "output": {"dir": "o"}})") ==
        "input: missing (one of \"frames\" (a folder of OBJ frames), \"synthetic\" (a "
        "generated sequence), \"gltf\" (a glTF animation), \"pc2\" (a PC2 point cache, with its "
        "\"mesh\") or \"mdd\" (an MDD point cache, with its \"mesh\"))");
  CHECK(config_error(R"({"job": "sequence", "input": {"frames": "f"}, "output": {}})") ==
        "output.dir: missing (the folder the results are written to)");
  CHECK(config_error(with("input", R"({})")) ==
        "input: missing (one of \"frames\" (a folder of OBJ frames), \"synthetic\" (a "
        "generated sequence), \"gltf\" (a glTF animation), \"pc2\" (a PC2 point cache, with its "
        "\"mesh\") or \"mdd\" (an MDD point cache, with its \"mesh\"))");
  CHECK(config_error(with("input", R"({"frames": "f", "synthetic": {}})")) ==
        "input: give only one of \"frames\", \"synthetic\", \"gltf\", \"pc2\" and \"mdd\"");
  CHECK(config_error(with("input", R"({"frames": "f", "gltf": "take.glb"})")) ==
        "input: give only one of \"frames\", \"synthetic\", \"gltf\", \"pc2\" and \"mdd\"");
  CHECK(config_error(with("template", R"({"frame": 1, "mesh": "rest.obj"})")) ==
        "template: give \"frame\" or \"mesh\", not both");
  CHECK(config_error(with("template", R"({"mesh": "rest.obj", "optimize": true})"))
            .rfind("template.optimize: only applies to a template \"frame\"", 0) == 0);
  CHECK(config_error(R"({"job": "sequence", "input": {"synthetic": {"frames": 4}},
                         "template": {"frame": 4}, "output": {"dir": "o"}})") ==
        "template.frame: 4 is out of range (input.synthetic.frames is 4)");
  CHECK(config_error(with("input", R"({"frames": "f", "range": {"start": 5, "stop": 2}})")) ==
        "input.range.stop: expected an integer >= 5, got 2");
  CHECK(config_error(with("input", R"({"synthetic": {"drift": 3}})")) ==
        "input.synthetic.drift: expected a number in [0, 2], got 3");
  CHECK(config_error(with("input", R"({"synthetic": {"shape": "sphere"}})")) ==
        "input.synthetic.shape: expected \"bending_tube\" or \"rolled_sheet\", got \"sphere\"");
}

TEST_CASE("glTF input keys: file, mesh and animation by name or index, fps; GLB output") {
  SequenceJobOptions c = parse(R"({"job": "sequence", "input": {"gltf": "takes/walk.glb"},
                          "output": {"dir": "out", "format": "gltf"}})");
  REQUIRE(c.input.gltf);
  CHECK(c.input.gltf->file == fs::path("/data/project/configs/takes/walk.glb"));
  CHECK(c.input.gltf->mesh.empty());
  CHECK_FALSE(c.input.gltf->mesh_index);
  CHECK(c.input.gltf->animation.empty());
  CHECK_FALSE(c.input.gltf->animation_index);
  CHECK_FALSE(c.input.gltf->fps);
  CHECK(c.input.frames.empty());
  CHECK(c.output.format == OutputFormat::Gltf);
  CHECK(c.output.gltf.frames_per_mesh == GltfWriteOptions{}.frames_per_mesh);
  CHECK(c.output.gltf.normals);

  c = parse(R"({"job": "sequence",
                "input": {"gltf": "/abs/a.gltf", "mesh": "body", "animation": 2, "fps": 24},
                "output": {"dir": "out", "format": "gltf",
                           "gltf": {"frames_per_mesh": 64, "normals": false}}})");
  CHECK(c.input.gltf->file == fs::path("/abs/a.gltf"));
  CHECK(c.input.gltf->mesh == "body");
  CHECK_FALSE(c.input.gltf->mesh_index);
  CHECK(c.input.gltf->animation.empty());
  CHECK(c.input.gltf->animation_index == 2);
  CHECK(c.input.gltf->fps == 24.0);
  CHECK(c.output.gltf.frames_per_mesh == 64);
  CHECK_FALSE(c.output.gltf.normals);
  // Round trip: the index stays an index, the name a name.
  const json resolved = to_json(c);
  CHECK(resolved["input"]["mesh"] == "body");
  CHECK(resolved["input"]["animation"] == 2);
  CHECK(resolved["output"]["gltf"]["frames_per_mesh"] == 64);
  CHECK(to_json(parse_config(resolved, "/elsewhere")) == resolved);
  const json defaults = to_json(parse(R"({"job": "sequence", "input": {"gltf": "a.glb"},
                                          "output": {"dir": "o"}})"));
  CHECK(defaults["input"]["mesh"].is_null());
  CHECK(defaults["input"]["fps"].is_null());
  CHECK_FALSE(defaults["output"].contains("gltf"));
  CHECK(to_json(parse_config(defaults, "/elsewhere")) == defaults);

  const std::string glb =
      R"({"job": "sequence", "output": {"dir": "o"}, "input": {"gltf": "a.glb", )";
  CHECK(config_error(glb + R"("fps": 0}})") == "input.fps: expected a number in (0, 1e+06], got 0");
  CHECK(config_error(glb + R"("fps": "30"}})") ==
        "input.fps: expected a number in (0, 1e+06], got \"30\"");
  CHECK(config_error(glb + R"("mesh": -1}})") ==
        "input.mesh: expected a name (a non-empty string) or an index (an integer >= 0), got -1");
  CHECK(config_error(glb + R"("animation": ""}})") ==
        "input.animation: expected a name (a non-empty string) or an index (an integer >= 0), "
        "got \"\"");
  CHECK(config_error(glb + R"("animaton": 1}})") ==
        "input.animaton: unknown key (did you mean \"animation\"?)");
  CHECK(config_error(with("input", R"({"frames": "f", "fps": 30})")) ==
        "input.fps: only applies to a glTF input (\"gltf\": a .gltf or .glb animation file)");
  CHECK(config_error(with("input", R"({"frames": "f", "mesh": 0})")) ==
        "input.mesh: only applies to a glTF input (\"gltf\": a .gltf or .glb animation file); or "
        "the mesh of a \"pc2\" or \"mdd\" cache");
  CHECK(config_error(with("output", R"({"dir": "o", "format": "gltf"})")) ==
        "output.format: \"gltf\" needs a glTF input (input.gltf), whose mesh, materials and "
        "textures the output keeps; use \"obj\" for OBJ frames");
  const std::string with_glb = R"({"job": "sequence", "input": {"gltf": "a.glb"}, )";
  CHECK(config_error(with_glb + R"("output": {"dir": "o", "gltf": {"normals": false}}})") ==
        "output.gltf: only applies to output.format \"gltf\"");
  CHECK(config_error(with_glb + R"("output": {"dir": "o", "format": "gltf",
                                              "gltf": {"frames_per_mesh": 0}}})") ==
        "output.gltf.frames_per_mesh: expected an integer in [1, 100000], got 0");
}

TEST_CASE("strict JSON: comments, duplicate keys and syntax errors are refused") {
  auto error = [](const std::string& text) {
    try {
      parse_json_strict(text);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(error("{\n  // a comment\n  \"job\": 1\n}") ==
        "line 2, column 3: comments are not allowed in JSON");
  CHECK(error("{\"job\": 1 /* c */}") == "line 1, column 11: comments are not allowed in JSON");
  CHECK(error(R"({"massage": {"iterations": 3, "iterations": 4}})") ==
        "massage.iterations: duplicate key (each key may appear once)");
  CHECK(error(R"({"job": 1, "job": 2})") == "job: duplicate key (each key may appear once)");
  CHECK(error(R"({"a": [{"b": 1, "b": 2}]})") ==
        "a[0].b: duplicate key (each key may appear once)");
  const std::string trailing = error("{\"job\": 1} x");
  CHECK(trailing.rfind("line 1, column 12: ", 0) == 0);
  const std::string comma = error("{\"job\": 1,}");
  CHECK(comma.rfind("line 1, column 11: syntax error", 0) == 0);
  CHECK(parse_json_strict(R"({"a": [1, {"b": null}], "c": "d"})") ==
        json::parse(R"({"a": [1, {"b": null}], "c": "d"})"));
}

TEST_CASE("load_config reads a file and resolves paths against its folder") {
  const test::TempDir temp("config");
  const fs::path& dir = temp.path();
  fs::create_directories(dir / "sub");
  std::ofstream(dir / "sub" / "job.json") << kMinimal;
  const SequenceJobOptions c = load_config(dir / "sub" / "job.json");
  CHECK(c.input.frames == dir / "sub" / "take1");
  CHECK(c.output.dir == dir / "sub" / "out");
  CHECK_THROWS_AS(load_config(dir / "missing.json"), IoError);
  std::ofstream(dir / "bad.json") << "{\"job\": \"sequence\",, }";
  CHECK_THROWS_AS(load_config(dir / "bad.json"), ConfigError);
}

TEST_CASE("frame ranges A:B[:STEP]") {
  FrameRange r = parse_frame_range("2:10:3", "--frames");
  CHECK(r.start == 2);
  CHECK(*r.stop == 10);
  CHECK(r.step == 3);
  r = parse_frame_range("5:", "--frames");
  CHECK(r.start == 5);
  CHECK_FALSE(r.stop);
  r = parse_frame_range(":4", "--frames");
  CHECK(r.start == 0);
  CHECK(*r.stop == 4);
  r = parse_frame_range("7", "--frames");
  CHECK(r.start == 7);
  CHECK(*r.stop == 8);
  CHECK(format_frame_range(parse_frame_range("3::2", "x")) == "3::2");
  CHECK_THROWS_WITH(parse_frame_range("a:b", "--frames"),
                    "--frames: expected A:B[:STEP] (frame indices from A to before B, by STEP; B "
                    "may be empty), got \"a:b\"");
  CHECK_THROWS_WITH(parse_frame_range("1:2:0", "--frames"),
                    "--frames: STEP must be >= 1, got \"1:2:0\"");
  CHECK_THROWS_WITH(parse_frame_range("5:2", "--frames"), "--frames: B must be >= A, got \"5:2\"");
  CHECK_THROWS_AS(parse_frame_range("1:2:3:4", "--frames"), ConfigError);
  CHECK_THROWS_AS(parse_frame_range("-1:2", "--frames"), ConfigError);
}

TEST_CASE("every example config in configs/ parses") {
  const fs::path configs = fs::path(SEQMASSAGE_TEST_DIR).parent_path() / "configs";
  int parsed = 0;
  for (const auto& entry : fs::directory_iterator(configs)) {
    if (entry.path().extension() != ".json") continue;
    INFO(entry.path().string());
    const AnyJobOptions any = load_any_config(entry.path());
    const fs::path dir = std::visit([](const auto& job) { return job.output.dir; }, any);
    CHECK(dir.is_absolute());
    ++parsed;
  }
  CHECK(parsed >= 7);  // demo, the crane folder, CesiumMan glTF, the single-mesh jobs
  const SequenceJobOptions man = load_config(configs / "gltf_cesiumman.json");
  REQUIRE(man.input.gltf);
  CHECK(man.input.gltf->file ==
        (configs / "../../shared/data/gltf/skinned/CesiumMan/glTF-Binary/CesiumMan.glb")
            .lexically_normal());
  CHECK(man.output.format == OutputFormat::Gltf);
}
