// The glTF evaluator against closed forms: accessor decoding, samplers, morph targets, node
// hierarchies and skinning.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

#include "io/gltf/gltf_accessor.hpp"
#include "io/gltf/gltf_animation.hpp"
#include "io/gltf/gltf_load.hpp"
#include "support/gltf_models.hpp"
#include "support/temp_dir.hpp"

namespace sm {
namespace {

using test::ModelBuilder;
using test::require_close;
using test::TempDir;

const GltfAccessorRule kAnything{"test",
                                 {TINYGLTF_TYPE_SCALAR, TINYGLTF_TYPE_VEC2, TINYGLTF_TYPE_VEC3,
                                  TINYGLTF_TYPE_VEC4, TINYGLTF_TYPE_MAT2},
                                 {5120, 5121, 5122, 5123, 5125, 5126},
                                 {5120, 5121, 5122, 5123}};

TEST_CASE("glTF accessors decode every component type, stride, padding and sparse", "[gltf]") {
  ModelBuilder b;
  const int8_t bytes[] = {-128, -127, 0, 127};
  const int16_t shorts[] = {-32768, -32767, 16384, 32767};
  const uint16_t ushorts[] = {0, 65535, 13107};
  const uint8_t ubytes[] = {0, 51, 255};
  const uint32_t uints[] = {0, 4000000000u};
  const int a_byte_n =
      b.accessor(b.view(bytes, 4), TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_SCALAR, 4, true);
  const int a_byte =
      b.accessor(b.view(bytes, 4), TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_SCALAR, 4, false);
  const int a_short_n =
      b.accessor(b.view(shorts, 8), TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_SCALAR, 4, true);
  const int a_ushort_n = b.accessor(b.view(ushorts, 6), TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                    TINYGLTF_TYPE_SCALAR, 3, true);
  const int a_ubyte_n = b.accessor(b.view(ubytes, 3), TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                   TINYGLTF_TYPE_SCALAR, 3, true);
  const int a_uint = b.accessor(b.view(uints, 8), TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                TINYGLTF_TYPE_SCALAR, 2, false);
  // Interleaved: VEC3 floats every 16 bytes, starting 4 bytes into the view.
  const float interleaved[] = {9, 1, 2, 3, 9, 4, 5, 6, 9, 7, 8, 9};
  const int a_strided = b.accessor(b.view(interleaved, 44, TINYGLTF_TARGET_ARRAY_BUFFER, 16),
                                   TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 2, false, 4);
  // MAT2 of bytes: each column is padded to 4 bytes.
  const uint8_t mat2[] = {1, 2, 0, 0, 3, 4, 0, 0};
  const int a_mat2 =
      b.accessor(b.view(mat2, 8), TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_MAT2, 1);
  // Sparse substitution over a buffer view: [1, 2, 3, 4] with [1] = 20, [3] = 40.
  const float base[] = {1, 2, 3, 4};
  const uint16_t ids[] = {1, 3};
  const float subst[] = {20, 40};
  const int a_sparse =
      b.accessor(b.view(base, 16), TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, 4);
  tinygltf::Accessor& sp = b.m.accessors[size_t(a_sparse)];
  sp.sparse.isSparse = true;
  sp.sparse.count = 2;
  sp.sparse.indices.bufferView = b.view(ids, 4);
  sp.sparse.indices.byteOffset = 0;
  sp.sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  sp.sparse.values.bufferView = b.view(subst, 8);
  sp.sparse.values.byteOffset = 0;

  TempDir dir("gltf-accessors");
  b.save(dir / "accessors.glb", true);
  const GltfFile file = load_gltf_file(dir / "accessors.glb");
  const auto values = [&](int a) { return read_gltf_accessor(file, a, kAnything, "test").values; };
  CHECK(values(a_byte_n) == std::vector<double>{-1, -1, 0, 1});
  CHECK(values(a_byte) == std::vector<double>{-128, -127, 0, 127});
  CHECK(values(a_short_n) == std::vector<double>{-1, -1, 16384 / 32767.0, 1});
  CHECK(values(a_ushort_n) == std::vector<double>{0, 1, 13107 / 65535.0});
  CHECK(values(a_ubyte_n) == std::vector<double>{0, 0.2, 1});
  CHECK(values(a_uint) == std::vector<double>{0, 4000000000.0});
  CHECK(values(a_strided) == std::vector<double>{1, 2, 3, 4, 5, 6});
  CHECK(values(a_mat2) == std::vector<double>{1, 2, 3, 4});
  CHECK(values(a_sparse) == std::vector<double>{1, 20, 3, 40});

  CHECK(gltf_element_size(TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC3) == 3);
  CHECK(gltf_element_size(TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_MAT2) == 8);
  CHECK(gltf_element_size(TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_MAT3) == 12);
  CHECK(gltf_element_size(TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_MAT3) == 24);
  CHECK(gltf_element_size(TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4) == 64);
  CHECK(gltf_element_size(TINYGLTF_COMPONENT_TYPE_INT, TINYGLTF_TYPE_SCALAR) == 0);

  // The rule of a use rejects what the specification does not allow there.
  CHECK_THROWS_WITH(read_gltf_accessor(file, a_uint, gltf_rules::kWeights, "WEIGHTS_0"),
                    Catch::Contains("accessors[5]") && Catch::Contains("not allowed for WEIGHTS"));
}

TEST_CASE("glTF samplers: slerp, STEP, LINEAR and CUBICSPLINE with tangents scaled by the interval",
          "[gltf]") {
  // Slerp keeps a constant angular speed even for large angles (nlerp would not).
  const Eigen::Quaterniond q0 = Eigen::Quaterniond::Identity();
  const Eigen::Quaterniond q1(Eigen::AngleAxisd(170 * M_PI / 180, Eigen::Vector3d::UnitZ()));
  for (double u : {0.0, 0.1, 0.25, 0.5, 0.9, 1.0}) {
    const Eigen::Quaterniond q = slerp_shortest(q0, q1, u);
    CHECK(q.angularDistance(q0) == Approx(170 * M_PI / 180 * u).margin(1e-12));
  }
  // The shorter arc: -q1 is the same rotation, interpolation must not go the long way round.
  const Eigen::Quaterniond minus_q1(-q1.w(), -q1.x(), -q1.y(), -q1.z());
  CHECK(slerp_shortest(q0, minus_q1, 0.5).angularDistance(q0) == Approx(85 * M_PI / 180));

  GltfKeyframes keys;
  keys.times = {1, 3};
  keys.width = 1;
  keys.values = {10, 20};
  keys.interpolation = GltfInterpolation::kLinear;
  CHECK(sample_keyframes(keys, 0)[0] == 10);  // clamped before the first key
  CHECK(sample_keyframes(keys, 2)[0] == 15);
  CHECK(sample_keyframes(keys, 9)[0] == 20);  // and after the last
  keys.interpolation = GltfInterpolation::kStep;
  CHECK(sample_keyframes(keys, 2.999)[0] == 10);
  CHECK(sample_keyframes(keys, 3)[0] == 20);
  // Hermite with v0 = 10, b0 = 4 per second, v1 = 20, a1 = -2 per second, over td = 2 seconds.
  keys.interpolation = GltfInterpolation::kCubicSpline;
  keys.values = {0, 10, 4, -2, 20, 0};
  for (double t : {1.0, 1.5, 2.0, 2.7, 3.0}) {
    const double u = (t - 1) / 2, td = 2;
    const double expected = (2 * u * u * u - 3 * u * u + 1) * 10 +
                            td * (u * u * u - 2 * u * u + u) * 4 +
                            (-2 * u * u * u + 3 * u * u) * 20 + td * (u * u * u - u * u) * -2;
    CHECK(sample_keyframes(keys, t)[0] == Approx(expected).epsilon(1e-12));
  }
  // A cubic rotation is normalized.
  GltfKeyframes rot;
  rot.times = {0, 1};
  rot.width = 4;
  rot.rotation = true;
  rot.interpolation = GltfInterpolation::kCubicSpline;
  rot.values = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, /**/ 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0};
  const std::vector<double> q = sample_keyframes(rot, 0.5);
  CHECK(std::hypot(std::hypot(q[0], q[1]), std::hypot(q[2], q[3])) == Approx(1));
}

Positions morph_quad_expected(const TriMesh& rest, const test::MorphQuadOptions& o, double t) {
  const std::vector<double> w = test::morph_quad_weights(o, t);
  Positions P = rest.V;
  P(2, 2) += w[0];
  P(3, 2) += 2 * w[1];
  return P.rowwise() + Eigen::RowVector3d(1, 2, 3);
}

TEST_CASE("glTF morph-target quad matches the closed form for every interpolation", "[gltf]") {
  TempDir dir("gltf-morph");
  for (const char* interpolation : {"LINEAR", "STEP", "CUBICSPLINE"}) {
    for (bool ubyte : {false, true}) {
      for (bool binary : {true, false}) {
        test::MorphQuadOptions o;
        o.interpolation = interpolation;
        o.ubyte_weights = ubyte;
        o.sparse_target = !ubyte;
        const std::filesystem::path file = dir / (binary ? "quad.glb" : "quad.gltf");
        test::morph_quad(o).save(file, binary);
        INFO(interpolation << (ubyte ? " ubyte" : " float") << (binary ? " glb" : " gltf"));
        GltfSequence s = load_gltf_sequence({file, "", "", std::nullopt});
        CHECK(s.mesh_name == "quad");
        CHECK(s.animation_name == "take");
        CHECK(s.times == std::vector<double>{0, 1, 2});  // the keyframe times
        REQUIRE(s.rest.num_vertices() == 4);
        REQUIRE(s.rest.num_triangles() == 2);
        CHECK(s.welded_vertices == 0);
        for (int k = 0; k < s.num_frames(); ++k) {
          require_close(evaluate_gltf_frame(s, k).V,
                        morph_quad_expected(s.rest, o, s.times[size_t(k)]));
        }
        s = load_gltf_sequence({file, "0", "take", 8.0});
        REQUIRE(s.num_frames() == 17);
        for (int k = 0; k < s.num_frames(); ++k) {
          CHECK(s.times[size_t(k)] == Approx(k / 8.0));
          require_close(evaluate_gltf_frame(s, k).V,
                        morph_quad_expected(s.rest, o, s.times[size_t(k)]));
        }
      }
    }
  }
}

TEST_CASE("glTF node hierarchy: slerped rotation, cubic translation, stepped scale", "[gltf]") {
  TempDir dir("gltf-nodes");
  test::node_animated_triangle().save(dir / "nodes.glb", true);
  const GltfSequence s = load_gltf_sequence({dir / "nodes.glb", "", "", 10.0});
  CHECK(load_gltf_sequence({dir / "nodes.glb", "", "", std::nullopt}).times ==
        std::vector<double>{0, 1, 1.5, 2});
  REQUIRE(s.num_frames() == 21);
  for (int k = 0; k < s.num_frames(); ++k) {
    const double t = s.times[size_t(k)];
    const double theta = 170 * M_PI / 180 * std::min(t, 1.0);
    const double u = t / 2;  // cubic translation: v0 = 0, b0 = 3, v1 = 2, a1 = 0, td = 2
    const double x = 2 * (u * u * u - 2 * u * u + u) * 3 + (-2 * u * u * u + 3 * u * u) * 2;
    const double scale = t < 1.5 ? 1 : 2;
    const Eigen::Affine3d parent = Eigen::Translation3d(x, 0, 0) *
                                   Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()) *
                                   Eigen::Scaling(scale);
    Positions expected(3, 3);
    for (int v = 0; v < 3; ++v) {
      expected.row(v) = (parent * (s.rest.vertex(v) + Vec3(1, 0, 0))).transpose();
    }
    INFO("t = " << t);
    require_close(evaluate_gltf_frame(s, k).V, expected);
  }
}

TEST_CASE("glTF two-bone skinned strip matches linear blend skinning in closed form", "[gltf]") {
  TempDir dir("gltf-skin");
  for (bool two_sets : {false, true}) {
    INFO((two_sets ? "JOINTS_0/1, normalized byte weights" : "JOINTS_0, float weights"));
    test::skinned_strip(two_sets).save(dir / "strip.glb", true);
    const GltfSequence s = load_gltf_sequence({dir / "strip.glb", "", "", 20.0});
    CHECK(s.mesh_name == "strip");
    CHECK(s.gltf_vertices == 12);
    CHECK(s.welded_vertices == 2);  // the UV seam at x = 1
    REQUIRE(s.rest.num_vertices() == 10);
    REQUIRE(s.rest.num_triangles() == 8);
    const double seam_weight = two_sets ? 102 / 255.0 : 0.5;
    REQUIRE(s.num_frames() == 21);
    for (int k = 0; k < s.num_frames(); ++k) {
      const double theta = M_PI / 2 * std::min(s.times[size_t(k)], 1.0);
      const Eigen::Matrix2d R = Eigen::Rotation2Dd(theta).toRotationMatrix();
      Positions expected = Positions::Zero(10, 3);
      for (int v = 0; v < 10; ++v) {
        const Eigen::Vector2d p = s.rest.V.row(v).head<2>().transpose();
        const double w1 = p.x() < 1 ? 0 : p.x() > 1 ? 1 : seam_weight;
        const Eigen::Vector2d bent = Eigen::Vector2d(1, 0) + R * (p - Eigen::Vector2d(1, 0));
        expected.row(v).head<2>() = ((1 - w1) * p + w1 * bent).transpose();
      }
      const WeldedFrame f = evaluate_gltf_frame(s, k);
      CHECK(f.separated_vertices == 0);
      require_close(f.V, expected);
    }
  }
}

TEST_CASE("glTF morph weights default to the node's, else the mesh's", "[gltf]") {
  TempDir dir("gltf-default-weights");
  test::ModelBuilder b = test::morph_quad();
  b.m.animations.clear();  // no weights channel: a translation channel drives the sequence
  b.channel(0, "translation", {0, 1}, {1, 2, 3, 1, 2, 4}, "LINEAR");
  b.save(dir / "quad.glb", true);
  GltfSequence s = load_gltf_sequence({dir / "quad.glb", "", "", std::nullopt});
  Positions V = evaluate_gltf_frame(s, 1).V;
  CHECK(V(2, 2) == Approx(4.5));  // mesh weights (0.5, 0), translation z = 4
  CHECK(V(3, 2) == Approx(4));
  b.m.nodes[0].weights = {0.25, 1};
  b.save(dir / "quad.glb", true);
  s = load_gltf_sequence({dir / "quad.glb", "", "", std::nullopt});
  V = evaluate_gltf_frame(s, 1).V;
  CHECK(V(2, 2) == Approx(4.25));
  CHECK(V(3, 2) == Approx(6));
}

TEST_CASE("glTF rotation keys as normalized shorts are decoded and normalized", "[gltf]") {
  TempDir dir("gltf-short-rotation");
  test::ModelBuilder b = test::node_animated_triangle();
  const double half = 85 * M_PI / 180;
  const int16_t q[8] = {0,
                        0,
                        0,
                        32767,
                        0,
                        0,
                        int16_t(std::lround(std::sin(half) * 32767)),
                        int16_t(std::lround(std::cos(half) * 32767))};
  b.m.animations[0].samplers[0].output =
      b.accessor(b.view(q, sizeof q), TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC4, 2, true);
  b.save(dir / "nodes.glb", true);
  const GltfSequence s = load_gltf_sequence({dir / "nodes.glb", "", "", 4.0});
  const double end = 2 * std::atan2(q[6] / 32767.0, q[7] / 32767.0);  // the quantized angle
  for (int k = 0; k <= 4; ++k) {  // t in [0, 1]: translation and scale as in the float model
    const double t = s.times[size_t(k)], u = t / 2;
    const double x = 2 * (u * u * u - 2 * u * u + u) * 3 + (-2 * u * u * u + 3 * u * u) * 2;
    const Eigen::Affine3d parent =
        Eigen::Translation3d(x, 0, 0) * Eigen::AngleAxisd(end * t, Eigen::Vector3d::UnitZ());
    Positions expected(3, 3);
    for (int v = 0; v < 3; ++v)
      expected.row(v) = (parent * (s.rest.vertex(v) + Vec3(1, 0, 0))).transpose();
    require_close(evaluate_gltf_frame(s, k).V, expected);
  }
}

}  // namespace
}  // namespace sm
