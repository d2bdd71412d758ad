// The glTF writer: round trips through the reader, materials and textures kept, normals that turn
// with the surface, long sequences split over meshes, and the Khronos validator.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "io/gltf/gltf_accessor.hpp"
#include "io/gltf/gltf_load.hpp"
#include "io/gltf/gltf_write.hpp"
#include "support/gltf_models.hpp"
#include "support/temp_dir.hpp"

namespace sm {
namespace {

using nlohmann::json;
using test::require_close;
using test::TempDir;

std::vector<Positions> evaluated_frames(const GltfSequence& s) {
  std::vector<Positions> frames;
  for (int k = 0; k < s.num_frames(); ++k) frames.push_back(evaluate_gltf_frame(s, k).V);
  return frames;
}

TEST_CASE("glTF writer round trip keeps positions, times, materials, textures and UVs", "[gltf]") {
  TempDir dir("gltf-write");
  test::skinned_strip().save(dir / "strip.glb", true);
  const GltfSequence s = load_gltf_sequence({dir / "strip.glb", "", "", 20.0});
  std::vector<Positions> corrected = evaluated_frames(s);
  for (int k = 0; k < s.num_frames(); ++k) {  // something the source does not contain
    corrected[size_t(k)].col(2).array() += 0.01 * k * corrected[size_t(k)].col(0).array();
  }
  const auto out = dir / "out" / "sequence.glb";
  const GltfWriteReport report = write_gltf_sequence(out, s, corrected);
  CHECK(report.frames == 21);
  CHECK(report.meshes == 1);
  CHECK(report.bytes == std::filesystem::file_size(out));
  test::require_valid_gltf(out);

  const GltfSequence r = load_gltf_sequence({out, "", "", std::nullopt});
  REQUIRE(r.num_frames() == s.num_frames());
  for (int k = 0; k < r.num_frames(); ++k)
    CHECK(float(r.times[size_t(k)]) == float(s.times[size_t(k)]));
  CHECK(r.gltf_vertices == 12);
  CHECK(r.welded_vertices == 2);
  CHECK(r.rest.F == s.rest.F);
  for (int k = 0; k < r.num_frames(); ++k) {
    INFO("frame " << k);
    const WeldedFrame f = evaluate_gltf_frame(r, k);
    CHECK(f.separated_vertices == 0);  // corrected positions went to every split copy
    require_close(f.V, corrected[size_t(k)]);
  }

  const GltfFile src = load_gltf_file(dir / "strip.glb");
  const GltfFile written = load_gltf_file(out);
  for (const char* key : {"materials", "textures", "samplers"})
    CHECK(written.json[key] == src.json[key]);
  REQUIRE(written.model.images.size() == 1);
  CHECK(written.model.images[0].image == src.model.images[0].image);
  CHECK(written.json["images"][0]["mimeType"] == "image/png");
  const json& prim = written.json["meshes"][0]["primitives"][0];
  CHECK(prim["material"] == 0);
  CHECK_FALSE(prim["attributes"].contains("JOINTS_0"));
  CHECK_FALSE(prim["attributes"].contains("WEIGHTS_0"));
  const GltfAccessorRule uv{"TEXCOORD", {TINYGLTF_TYPE_VEC2}, {TINYGLTF_COMPONENT_TYPE_FLOAT}, {}};
  CHECK(read_gltf_accessor(written, prim["attributes"]["TEXCOORD_0"], uv, "out").values ==
        read_gltf_accessor(src, src.model.meshes[0].primitives[0].attributes.at("TEXCOORD_0"), uv,
                           "in")
            .values);
  CHECK(written.json["asset"]["generator"] == "seqmassage");
  CHECK(written.json["animations"][0]["samplers"][0]["interpolation"] == "STEP");
}

TEST_CASE("glTF writer turns normals and tangents with the corrected surface", "[gltf]") {
  TempDir dir("gltf-normals");
  test::morph_quad().save(dir / "quad.glb", true);
  const GltfSequence s = load_gltf_sequence({dir / "quad.glb", "", "", 2.0});
  REQUIRE(s.num_frames() == 5);
  std::vector<Eigen::Matrix3d> turn;
  std::vector<Positions> corrected;
  for (int k = 0; k < s.num_frames(); ++k) {  // rigid rotations about y
    turn.push_back(Eigen::AngleAxisd(0.3 * k, Vec3::UnitY()).toRotationMatrix());
    corrected.push_back(s.rest.V * turn.back().transpose());
  }
  const auto out = dir / "quad-out.glb";
  write_gltf_sequence(out, s, corrected);
  test::require_valid_gltf(out);

  const GltfFile written = load_gltf_file(out);
  const json& prim = written.json["meshes"][0]["primitives"][0];
  const auto values = [&](const json& accessor, const GltfAccessorRule& rule) {
    return read_gltf_accessor(written, accessor.get<int>(), rule, "out").values;
  };
  const std::vector<double> n0 = values(prim["attributes"]["NORMAL"], gltf_rules::kNormal);
  const std::vector<double> t0 = values(prim["attributes"]["TANGENT"], gltf_rules::kTangent);
  for (int k = 0; k < s.num_frames(); ++k) {
    const std::vector<double> dn =
        values(prim["targets"][size_t(k)]["NORMAL"], gltf_rules::kNormal);
    const std::vector<double> dt =
        values(prim["targets"][size_t(k)]["TANGENT"], gltf_rules::kNormal);
    const Vec3 n = turn[size_t(k)] * Vec3::UnitZ(), t = turn[size_t(k)] * Vec3::UnitX();
    for (int v = 0; v < 4; ++v) {
      for (int c = 0; c < 3; ++c) {
        CHECK(n0[size_t(3 * v + c)] + dn[size_t(3 * v + c)] == Approx(n[c]).margin(1e-6));
        CHECK(t0[size_t(4 * v + c)] + dt[size_t(3 * v + c)] == Approx(t[c]).margin(1e-6));
      }
      CHECK(t0[size_t(4 * v + 3)] == 1);  // handedness kept
    }
  }

  GltfWriteOptions flat;
  flat.normals = false;
  write_gltf_sequence(out, s, corrected, flat);
  const json attributes = load_gltf_file(out).json["meshes"][0]["primitives"][0]["attributes"];
  CHECK_FALSE(attributes.contains("NORMAL"));
  CHECK_FALSE(attributes.contains("TANGENT"));
  test::require_valid_gltf(out);
}

TEST_CASE("glTF writer splits long sequences over meshes shown in turn", "[gltf]") {
  TempDir dir("gltf-chunks");
  test::node_animated_triangle().save(dir / "nodes.glb", true);
  const GltfSequence s = load_gltf_sequence({dir / "nodes.glb", "", "", 10.0});
  REQUIRE(s.num_frames() == 21);
  const std::vector<Positions> corrected = evaluated_frames(s);
  GltfWriteOptions options;
  options.frames_per_mesh = 4;
  const auto out = dir / "chunks.glb";
  const GltfWriteReport report = write_gltf_sequence(out, s, corrected, options);
  CHECK(report.meshes == 6);
  test::require_valid_gltf(out);

  const json doc = load_gltf_file(out).json;
  CHECK(doc["nodes"].size() == 6);
  CHECK(doc["animations"][0]["channels"].size() == 12);
  for (int c = 0; c < 6; ++c) {
    const GltfSequence r = load_gltf_sequence({out, std::to_string(c), "", std::nullopt});
    REQUIRE(r.num_frames() == 21);
    for (int k = 0; k < 21; ++k) {
      INFO("mesh " << c << " frame " << k);
      const Positions V = evaluate_gltf_frame(r, k).V;
      if (k / 4 == c) {
        require_close(V, corrected[size_t(k)]);
      } else {
        CHECK(V.isZero());  // hidden: scale 0
      }
    }
  }
}

}  // namespace
}  // namespace sm
