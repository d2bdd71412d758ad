// The point cache keys: "input": {"pc2" | "mdd", "mesh"} (the mesh is the template unless
// "template" says otherwise), "output.format": "pc2" | "mdd" with "output.point_cache", their
// cross-key rules and the resolved config's round trip.
#include <catch2/catch.hpp>

#include "config/config.hpp"
#include "core/errors.hpp"

using namespace sm;
using json = nlohmann::json;

namespace {

SequenceJobOptions parse(const std::string& rest) {
  const std::string text = R"({"job": "sequence", )" + rest + "}";
  return parse_config(parse_json_strict(text), "/data/project");
}

std::string error_of(const std::string& rest) {
  try {
    parse(rest);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a PC2 or MDD input names its cache and mesh; the mesh is the default template") {
  const SequenceJobOptions c =
      parse(R"("input": {"pc2": "take.pc2", "mesh": "rest.obj"}, "output": {"dir": "o"})");
  REQUIRE(c.input.pc2);
  CHECK_FALSE(c.input.mdd);
  CHECK_FALSE(c.input.gltf);
  CHECK(c.input.pc2->file == "/data/project/take.pc2");
  CHECK(c.input.pc2->mesh == "/data/project/rest.obj");
  CHECK(c.templ.mesh == "/data/project/rest.obj");
  const json resolved = to_json(c);
  CHECK(resolved["input"] == json::parse(R"({"pc2": "/data/project/take.pc2",
      "mesh": "/data/project/rest.obj", "range": {"start": 0, "stop": null, "step": 1}})"));
  CHECK(resolved["template"]["mesh"] == "/data/project/rest.obj");
  CHECK(to_json(parse_config(resolved, "/elsewhere")) == resolved);  // reads back the same

  const SequenceJobOptions m = parse(
      R"("input": {"mdd": "take.mdd", "mesh": "rest.ply"}, "template": {"frame": 3},)"
      R"( "output": {"dir": "o", "format": "mdd", "point_cache": {"fps": 30}})");
  REQUIRE(m.input.mdd);
  CHECK(m.input.point_cache()->format == PointCacheFormat::Mdd);
  CHECK(m.templ.mesh.empty());  // "template" says otherwise
  CHECK(m.templ.frame == 3);
  CHECK(m.output.format == OutputFormat::Mdd);
  CHECK(m.output.point_cache.fps == 30);
  CHECK(to_json(m)["output"]["point_cache"] == json::parse(R"({"fps": 30.0})"));
  CHECK_FALSE(to_json(parse(R"("input": {"frames": "f"}, "output": {"dir": "o"})"))["output"]
                  .contains("point_cache"));
}

TEST_CASE("point cache keys are checked across keys, by JSON path") {
  CHECK(error_of(R"("input": {"pc2": "take.pc2"}, "output": {"dir": "o"})") ==
        "input.mesh: missing (the mesh the \"pc2\" cache's points belong to: a .obj, .ply or "
        ".off with its vertex count)");
  CHECK(error_of(R"("input": {"pc2": "a.pc2", "mdd": "b.mdd", "mesh": "m.obj"},)"
                 R"( "output": {"dir": "o"})") ==
        "input: give only one of \"frames\", \"synthetic\", \"gltf\", \"pc2\" and \"mdd\"");
  CHECK(error_of(R"("input": {"frames": "f", "mesh": "m.obj"}, "output": {"dir": "o"})") ==
        "input.mesh: only applies to a glTF input (\"gltf\": a .gltf or .glb animation file); or "
        "the mesh of a \"pc2\" or \"mdd\" cache");
  CHECK(error_of(R"("input": {"pc2": "a.pc2", "mesh": "m.obj", "animation": 1},)"
                 R"( "output": {"dir": "o"})") ==
        "input.animation: only applies to a glTF input (\"gltf\": a .gltf or .glb animation "
        "file)");
  CHECK(error_of(R"("input": {"pc2": "a.pc2", "mesh": "m.obj"}, "template": {"optimize": true},)"
                 R"( "output": {"dir": "o"})") ==
        "template.optimize: only applies to a template \"frame\" (with a rest \"mesh\", every "
        "frame is optimized)");
  CHECK(error_of(R"("input": {"pc2": "a.pc2", "mesh": 3}, "output": {"dir": "o"})") ==
        "input.mesh: expected a path (a non-empty string), got 3");
  CHECK(error_of(R"("input": {"frames": "f"}, "output": {"dir": "o", "point_cache": {}})") ==
        "output.point_cache: only applies to output.format \"pc2\" or \"mdd\"");
  CHECK(error_of(R"("input": {"frames": "f"}, "output": {"dir": "o", "format": "pc2",)"
                 R"( "on_failure": "skip"})")
            .rfind("output.on_failure: \"skip\" cannot go with output.format \"pc2\"", 0) == 0);
  CHECK(error_of(R"("input": {"frames": "f"}, "output": {"dir": "o", "format": "mdd",)"
                 R"( "on_failure": "skip"})") == "");
  CHECK(error_of(R"("input": {"frames": "f"}, "output": {"dir": "o", "format": "pc3"})") ==
        "output.format: expected \"obj\", \"gltf\", \"pc2\", or \"mdd\", got \"pc3\" (did you "
        "mean \"pc2\"?)");
  CHECK(error_of(R"("input": {"frames": "f"}, "output": {"dir": "o", "format": "mdd",)"
                 R"( "point_cache": {"fps": 0}})") ==
        "output.point_cache.fps: expected a number in (0, 1e+06], got 0");
}

TEST_CASE("a single-mesh job refuses the point cache keys") {
  try {
    parse_mesh_job_config(
        json::parse(R"({"job": "smooth", "input": {"mesh": "a.obj", "pc2": "a.pc2"},
                        "output": {"dir": "o"}})"),
        "/d");
    FAIL("no error");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).rfind("input.pc2: only for \"job\": \"sequence\"", 0) == 0);
  }
}
