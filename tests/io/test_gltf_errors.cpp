// Bad glTF input is an error that names the file and the glTF element; nothing is written.
#include <catch2/catch.hpp>
#include <fstream>

#include "io/atomic_file.hpp"
#include "io/gltf/gltf_load.hpp"
#include "io/gltf/gltf_write.hpp"
#include "core/errors.hpp"
#include "support/gltf_models.hpp"
#include "support/temp_dir.hpp"

namespace sm {
namespace {

using Catch::Contains;
using test::ModelBuilder;
using test::TempDir;

GltfSequence load(const std::filesystem::path& file, const std::string& mesh = "",
                  const std::string& animation = "") {
  return load_gltf_sequence({file, mesh, animation, std::nullopt});
}

TEST_CASE("glTF: truncated or malformed GLB and JSON", "[gltf]") {
  TempDir dir("gltf-bad-container");
  const auto path = dir / "quad.glb";
  test::morph_quad().save(path, true);
  const std::string bytes = read_file(path);

  write_file_atomic(path, bytes.substr(0, bytes.size() - 40));
  CHECK_THROWS_AS(load(path), InputError);
  CHECK_THROWS_WITH(load(path), Contains("quad.glb") && Contains("GLB") && Contains("truncated"));
  write_file_atomic(path, bytes.substr(0, 10));
  CHECK_THROWS_WITH(load(path), Contains("quad.glb") && Contains("GLB header"));
  std::string wrong_version = bytes;
  wrong_version[4] = 1;
  write_file_atomic(path, wrong_version);
  CHECK_THROWS_WITH(load(path), Contains("GLB header") && Contains("version 1"));

  const auto json = dir / "broken.gltf";
  write_file_atomic(json, "{\"asset\": {\"version\": \"2.0\"}, ");
  CHECK_THROWS_WITH(load(json), Contains("broken.gltf") && Contains("JSON"));
  write_file_atomic(json,
                    R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 4, "uri": )"
                    R"("data:application/octet-stream;base64,AAAAAA=="}], "bufferViews": )"
                    R"([{"buffer": 0, "byteLength": "four"}], "images": [{"bufferView": 0}]})");
  CHECK_THROWS_AS(load(json), InputError);
  CHECK_THROWS_WITH(load(json), Contains("broken.gltf") && Contains("JSON"));
  CHECK_THROWS_AS(load(dir / "missing.glb"), IoError);
}

TEST_CASE("glTF: missing buffer or image file", "[gltf]") {
  TempDir dir("gltf-bad-buffer");
  const auto path = dir / "quad.gltf";
  test::morph_quad().save(path, false);
  REQUIRE(std::filesystem::exists(dir / "quad.bin"));
  CHECK_NOTHROW(load(path));
  std::filesystem::remove(dir / "quad.bin");
  CHECK_THROWS_AS(load(path), InputError);
  CHECK_THROWS_WITH(load(path), Contains("quad.gltf") && Contains("buffers[0]") &&
                                    Contains("quad.bin") && Contains("not found"));

  // The second of two buffer files is missing.
  ModelBuilder b = test::morph_quad();
  b.m.buffers.emplace_back();
  b.m.buffers[1].data = {1, 2, 3, 4};
  b.m.buffers[1].uri = "extra.bin";
  b.save(dir / "two.gltf", false);
  std::filesystem::remove(dir / "extra.bin");
  CHECK_THROWS_WITH(load(dir / "two.gltf"), Contains("buffers[1]") && Contains("extra.bin"));
}

TEST_CASE("glTF: out-of-range index, accessor, node, non-triangle primitive", "[gltf]") {
  TempDir dir("gltf-bad-elements");
  const auto path = dir / "bad.glb";
  {
    ModelBuilder b = test::morph_quad();
    const tinygltf::Accessor& idx = b.m.accessors[size_t(b.m.meshes[0].primitives[0].indices)];
    const tinygltf::BufferView& v = b.m.bufferViews[size_t(idx.bufferView)];
    b.m.buffers[0].data[v.byteOffset + 2] = 7;  // second index: 7 for a 4-vertex quad
    b.save(path, true);
    CHECK_THROWS_WITH(
        load(path),
        Contains("bad.glb") &&
            Contains("accessors[" + std::to_string(b.m.meshes[0].primitives[0].indices) + "]") &&
            Contains("index 7") && Contains("out of range"));
  }
  {
    ModelBuilder b = test::morph_quad();
    b.m.meshes[0].primitives[0].attributes["POSITION"] = 99;
    b.save(path, true);
    CHECK_THROWS_WITH(load(path), Contains("meshes[0].primitives[0].attributes.POSITION") &&
                                      Contains("accessor 99 does not exist"));
  }
  {
    ModelBuilder b = test::morph_quad();
    b.m.accessors[size_t(b.m.meshes[0].primitives[0].attributes["POSITION"])].count = 400;
    b.save(path, true);
    CHECK_THROWS_WITH(load(path), Contains("bufferViews[") && Contains("accessors["));
  }
  {
    ModelBuilder b = test::morph_quad();
    b.m.meshes[0].primitives[0].mode = TINYGLTF_MODE_LINE;
    b.save(path, true);
    CHECK_THROWS_WITH(load(path), Contains("meshes[0].primitives[0]") &&
                                      Contains("mode 1 (LINES)") &&
                                      Contains("not a triangle primitive"));
  }
  {
    ModelBuilder b = test::morph_quad();
    b.m.animations[0].channels[0].target_node = 5;
    b.save(path, true);
    CHECK_THROWS_WITH(load(path),
                      Contains("animations[0].channels[0]") && Contains("target node 5"));
  }
  {
    ModelBuilder b = test::node_animated_triangle();
    b.m.nodes[1].children = {0};  // parent -> child -> parent
    b.save(path, true);
    CHECK_THROWS_WITH(load(path), Contains("bad.glb") && Contains("cycle"));
  }
  {
    ModelBuilder b = test::skinned_strip();
    b.m.skins[0].joints = {1, 42};
    b.save(path, true);
    CHECK_THROWS_WITH(load(path), Contains("skins[0]") && Contains("joint node 42"));
  }
  {
    ModelBuilder b = test::morph_quad();
    b.m.extensionsRequired = {"KHR_draco_mesh_compression"};
    b.m.extensionsUsed = {"KHR_draco_mesh_compression"};
    b.save(path, true);
    CHECK_THROWS_WITH(load(path),
                      Contains("extensionsRequired") && Contains("KHR_draco_mesh_compression"));
  }
}

TEST_CASE("glTF: no animation, unknown mesh or animation, bad fps", "[gltf]") {
  TempDir dir("gltf-bad-choice");
  const auto path = dir / "quad.glb";
  ModelBuilder b = test::morph_quad();
  b.save(path, true);
  CHECK_THROWS_WITH(load(path, "nope"),
                    Contains("meshes") && Contains("'nope'") && Contains("0 'quad'"));
  CHECK_THROWS_WITH(load(path, "", "walk"),
                    Contains("animations") && Contains("'walk'") && Contains("0 'take'"));
  CHECK_THROWS_WITH(load(path, "3"), Contains("no mesh named or numbered '3'"));
  CHECK_THROWS_AS(load_gltf_sequence({path, "", "", 0.0}), ConfigError);
  CHECK_THROWS_AS(load_gltf_sequence({path, "", "", -30.0}), ConfigError);
  b.m.animations.clear();
  b.save(path, true);
  CHECK_THROWS_AS(load(path), InputError);
  CHECK_THROWS_WITH(load(path),
                    Contains("quad.glb") && Contains("animations") && Contains("no animation"));
}

TEST_CASE("glTF writer: a bad corrected frame is an error and nothing is written", "[gltf]") {
  TempDir dir("gltf-bad-write");
  test::morph_quad().save(dir / "quad.glb", true);
  const GltfSequence s = load(dir / "quad.glb");
  std::vector<Positions> frames(size_t(s.num_frames()), s.rest.V);
  const auto out = dir / "out" / "sequence.glb";
  frames[1] = Positions::Zero(3, 3);
  CHECK_THROWS_WITH(write_gltf_sequence(out, s, frames),
                    Contains("sequence.glb") && Contains("frame 1") && Contains("3 vertices"));
  frames[1] = s.rest.V;
  frames[2](0, 0) = std::nan("");
  CHECK_THROWS_WITH(write_gltf_sequence(out, s, frames),
                    Contains("frame 2") && Contains("not finite"));
  frames.pop_back();
  CHECK_THROWS_WITH(write_gltf_sequence(out, s, frames), Contains("2 corrected frames"));
  CHECK_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace sm
