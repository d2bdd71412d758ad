// Welding glTF vertices split at seams, triangle strips and fans, non-indexed primitives.
#include <catch2/catch.hpp>
#include <cstring>

#include "io/gltf/gltf_load.hpp"
#include "io/gltf/gltf_weld.hpp"
#include "mesh/topology.hpp"
#include "support/gltf_models.hpp"
#include "support/temp_dir.hpp"

namespace sm {
namespace {

using test::ModelBuilder;
using test::TempDir;

/// A unit square as two non-indexed primitives (one triangle each, 6 glTF vertices), or as one
/// primitive of the given mode over the corners (0,0), (1,0), (0,1), (1,1) (strip order) or
/// (0,0), (1,0), (1,1), (0,1) (fan order); animated by a translation channel.
ModelBuilder square(int mode) {
  ModelBuilder b;
  b.m.meshes.emplace_back();
  tinygltf::Mesh& mesh = b.m.meshes[0];
  const auto add = [&](const std::vector<float>& pos, int m) {
    tinygltf::Primitive prim;
    prim.mode = m;
    prim.attributes["POSITION"] = b.floats(pos, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER);
    mesh.primitives.push_back(prim);
  };
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    add({0, 0, 0, 1, 0, 0, 1, 1, 0}, mode);
    add({0, 0, 0, 1, 1, 0, -0.0f, 1, 0}, mode);  // -0 welds with +0
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    add({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, mode);
  } else {
    add({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, mode);
  }
  const int n = b.node("square");
  b.m.nodes[size_t(n)].mesh = 0;
  b.m.scenes[0].nodes = {n};
  b.channel(n, "translation", {0, 1}, {0, 0, 0, 0, 0, 1}, "LINEAR");
  return b;
}

TEST_CASE("glTF welding joins non-indexed primitives into one connectivity", "[gltf]") {
  TempDir dir("gltf-weld");
  square(TINYGLTF_MODE_TRIANGLES).save(dir / "square.glb", true);
  const GltfSequence s = load_gltf_sequence({dir / "square.glb", "", "", std::nullopt});
  CHECK(s.gltf_vertices == 6);
  CHECK(s.welded_vertices == 2);
  CHECK(s.weld_map == std::vector<int>{0, 1, 2, 0, 2, 3});
  REQUIRE(s.rest.num_vertices() == 4);
  REQUIRE(s.rest.num_triangles() == 2);
  const Topology topo = build_topology(s.rest);
  CHECK(topo.is_manifold());
  CHECK(topo.boundary_loops.size() == 1);
  CHECK(topo.num_edges == 5);
  const WeldedFrame f = evaluate_gltf_frame(s, 1);
  CHECK(f.separated_vertices == 0);
  CHECK(f.V(3, 2) == 1.0);
}

TEST_CASE("glTF triangle strips and fans become counter-clockwise triangles", "[gltf]") {
  TempDir dir("gltf-strip");
  for (int mode : {TINYGLTF_MODE_TRIANGLE_STRIP, TINYGLTF_MODE_TRIANGLE_FAN}) {
    square(mode).save(dir / "square.glb", true);
    const GltfSequence s = load_gltf_sequence({dir / "square.glb", "", "", std::nullopt});
    REQUIRE(s.rest.num_triangles() == 2);
    for (int t = 0; t < 2; ++t) {
      const Vec3 a = s.rest.vertex(s.rest.F(t, 0)), b = s.rest.vertex(s.rest.F(t, 1)),
                 c = s.rest.vertex(s.rest.F(t, 2));
      CHECK((b - a).cross(c - a).z() > 0);
    }
    CHECK(build_topology(s.rest).is_manifold());
  }
}

TEST_CASE("glTF weld map: unreferenced vertices, collapsed triangles, mean of copies", "[gltf]") {
  Positions V(6, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0, 5, 5, 5, 0, 0, 0;
  Triangles F(3, 3);
  F << 0, 1, 2, 3, 2, 5, 0, 5, 1;  // the last collapses: 0 and 5 are the same point
  const GltfWeld w = weld_by_position(V, F);
  CHECK(w.map == std::vector<int>{0, 1, 2, 1, -1, 0});
  CHECK(w.merged == 2);
  CHECK(w.unreferenced == 1);
  CHECK(w.dropped_triangles == 1);
  REQUIRE(w.mesh.num_triangles() == 2);

  Positions P = V;
  P(3, 0) += 0.5;  // the copies of welded vertex 1 separate
  const WeldedFrame f = weld_frame(w.map, 3, P, 0.1);
  CHECK(f.separated_vertices == 1);
  CHECK(f.max_separation == Approx(0.25));
  CHECK(f.V(1, 0) == Approx(1.25));
  const Positions back = unweld_frame(w.map, f.V, V);
  CHECK(back(3, 0) == Approx(1.25));
  CHECK(back.row(4) == V.row(4));
}

TEST_CASE("glTF copies whose skin weights differ are counted, not fatal", "[gltf]") {
  TempDir dir("gltf-separate");
  ModelBuilder b = test::skinned_strip(false);
  // Give the copy at x = 1, y = 1 (glTF vertex 7) bone weights (0.2, 0.8) instead of (0.5, 0.5).
  const tinygltf::Accessor& a =
      b.m.accessors[size_t(b.m.meshes[0].primitives[0].attributes.at("WEIGHTS_0"))];
  const tinygltf::BufferView& v = b.m.bufferViews[size_t(a.bufferView)];
  const float w[2] = {0.2f, 0.8f};
  std::memcpy(b.m.buffers[0].data.data() + v.byteOffset + 7 * 16, w, 8);
  b.save(dir / "strip.glb", true);
  const GltfSequence s = load_gltf_sequence({dir / "strip.glb", "", "", std::nullopt});
  CHECK(s.welded_vertices == 2);
  CHECK(evaluate_gltf_frame(s, 0).separated_vertices == 0);  // no rotation yet
  const WeldedFrame f = evaluate_gltf_frame(s, 1);
  CHECK(f.separated_vertices == 1);
  CHECK(f.max_separation > 0.1);
}

}  // namespace
}  // namespace sm
