// Bad glTF data: non-finite accessor values (positions, morph targets, key times and values) and
// empty files are errors naming the file and the accessor.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>

#include "io/atomic_file.hpp"
#include "io/gltf/gltf_load.hpp"
#include "core/errors.hpp"
#include "support/gltf_models.hpp"
#include "support/temp_dir.hpp"

namespace sm {
namespace {

using Catch::Contains;
using test::ModelBuilder;
using test::TempDir;

GltfSequence load(const std::filesystem::path& file) {
  return load_gltf_sequence({file, "", "", std::nullopt});
}

// Overwrites component `c` of element `e` of float accessor `index` in the builder's buffer.
void set_float(ModelBuilder& b, int index, size_t e, int c, float value) {
  const tinygltf::Accessor& a = b.m.accessors[size_t(index)];
  REQUIRE(a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT);
  REQUIRE(a.bufferView >= 0);
  const tinygltf::BufferView& v = b.m.bufferViews[size_t(a.bufferView)];
  const size_t stride = v.byteStride
                            ? v.byteStride
                            : sizeof(float) * size_t(tinygltf::GetNumComponentsInType(a.type));
  const size_t at = v.byteOffset + a.byteOffset + e * stride + size_t(c) * sizeof(float);
  REQUIRE(at + sizeof(float) <= b.m.buffers[size_t(v.buffer)].data.size());
  std::memcpy(b.m.buffers[size_t(v.buffer)].data.data() + at, &value, sizeof(float));
}

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

TEST_CASE("glTF: NaN and infinite accessor values name the accessor and the element",
          "[gltf][errors]") {
  TempDir dir("gltf-nan");
  const auto path = dir / "bad.glb";
  {  // a rest position
    ModelBuilder b = test::morph_quad();
    const int position = b.m.meshes[0].primitives[0].attributes["POSITION"];
    set_float(b, position, 2, 1, kNaN);
    b.save(path, true);
    CHECK_THROWS_AS(load(path), InputError);
    CHECK_THROWS_WITH(load(path), Contains("bad.glb") &&
                                      Contains("accessors[" + std::to_string(position) + "]") &&
                                      Contains("element 2 is not a finite number"));
  }
  {  // a morph target displacement
    ModelBuilder b = test::morph_quad();
    const int target = b.m.meshes[0].primitives[0].targets[0]["POSITION"];
    set_float(b, target, 2, 2, kInf);
    b.save(path, true);
    CHECK_THROWS_WITH(load(path), Contains("accessors[" + std::to_string(target) + "]") &&
                                      Contains("not a finite number"));
  }
  {  // a key time and a key value of the animation
    ModelBuilder b = test::node_animated_triangle();
    const tinygltf::AnimationSampler& s = b.m.animations[0].samplers[0];
    const int input = s.input, output = s.output;
    set_float(b, input, 1, 0, kNaN);
    b.save(path, true);
    CHECK_THROWS_WITH(load(path), Contains("bad.glb") &&
                                      Contains("accessors[" + std::to_string(input) + "]") &&
                                      Contains("not a finite number"));
    b = test::node_animated_triangle();
    set_float(b, output, 0, 0, -kInf);
    b.save(path, true);
    CHECK_THROWS_WITH(load(path), Contains("accessors[" + std::to_string(output) + "]") &&
                                      Contains("not a finite number"));
  }
}

TEST_CASE("glTF: an empty or truncated file names the file", "[gltf][errors]") {
  TempDir dir("gltf-empty");
  const auto empty = dir / "empty.glb";
  write_file_atomic(empty, "");
  CHECK_THROWS_AS(load(empty), InputError);
  CHECK_THROWS_WITH(load(empty), Contains("empty.glb") && Contains("JSON"));
  const auto cut = dir / "cut.gltf";
  test::morph_quad().save(dir / "whole.gltf", false);
  const std::string text = read_file(dir / "whole.gltf");
  write_file_atomic(cut, text.substr(0, text.size() / 2));
  CHECK_THROWS_WITH(load(cut), Contains("cut.gltf") && Contains("not valid JSON"));
}

TEST_CASE("glTF: a node's mesh or skin index out of range is named", "[gltf][errors]") {
  // Found by fuzzing: choosing the default mesh read meshes[node.mesh] unchecked.
  TempDir dir("gltf-node-index");
  const auto path = dir / "bad.glb";
  for (const char* member : {"mesh", "skin"}) {
    ModelBuilder b = test::morph_quad();
    size_t node = 0;
    while (b.m.nodes[node].mesh < 0) ++node;
    (std::string(member) == "mesh" ? b.m.nodes[node].mesh : b.m.nodes[node].skin) = 7;
    b.save(path, true);
    CHECK_THROWS_AS(load(path), InputError);
    CHECK_THROWS_WITH(load(path), Contains("bad.glb") &&
                                      Contains("nodes[" + std::to_string(node) + "]") &&
                                      Contains(std::string(member) + " 7 does not exist"));
  }
}

}  // namespace
}  // namespace sm
