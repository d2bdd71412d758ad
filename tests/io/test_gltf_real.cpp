// Every real glTF model of ../shared/data/gltf: loads, welds to a closed or documented-boundary
// mesh, keeps welded copies together in every frame, writes a valid GLB that reads back.
#include <catch2/catch.hpp>
#include <cmath>

#include "io/gltf/gltf_load.hpp"
#include "io/gltf/gltf_write.hpp"
#include "core/errors.hpp"
#include "mesh/topology.hpp"
#include "support/gltf_models.hpp"
#include "support/temp_dir.hpp"

namespace sm {
namespace {

namespace fs = std::filesystem;

const fs::path kGltfDir = test::shared_gltf_dir();

TEST_CASE("real glTF models load, weld, write valid GLB and read back", "[gltf][data]") {
  if (!test::have_shared_gltf()) return;
  test::TempDir dir("gltf-real");
  for (const test::SharedGltfModel& model : test::kSharedGltfModels) {
    INFO(model.file);
    const GltfSequence s = load_gltf_sequence({kGltfDir / model.file, "", "", std::nullopt});
    CHECK(s.gltf_vertices == model.gltf_vertices);
    CHECK(s.rest.num_vertices() == model.welded_vertices);
    CHECK(s.welded_vertices == model.gltf_vertices - model.welded_vertices);
    CHECK(s.unreferenced_vertices == 0);
    CHECK(s.rest.num_triangles() == model.triangles);
    REQUIRE(s.num_frames() == model.frames);
    const Topology topo = build_topology(s.rest);
    CHECK(topo.is_manifold());
    CHECK(topo.num_isolated_vertices == 0);
    CHECK(int(topo.boundary_loops.size()) == model.boundary_loops);

    std::vector<Positions> frames;
    for (int k = 0; k < s.num_frames(); ++k) {
      const WeldedFrame f = evaluate_gltf_frame(s, k);
      CHECK(f.separated_vertices == 0);
      REQUIRE(f.V.allFinite());
      frames.push_back(f.V);
    }
    const fs::path out = dir / (fs::path(model.file).stem().string() + ".glb");
    const GltfWriteOptions options;
    const GltfWriteReport report = write_gltf_sequence(out, s, frames, options);
    CHECK(report.meshes == (model.frames + options.frames_per_mesh - 1) / options.frames_per_mesh);
    test::require_valid_gltf(out);

    // Each output mesh plays its frames; they read back to float precision.
    for (int c = 0; c < report.meshes; ++c) {
      const GltfSequence r = load_gltf_sequence({out, std::to_string(c), "", std::nullopt});
      REQUIRE(r.num_frames() == s.num_frames());
      CHECK(r.rest.F == s.rest.F);
      const int first = c * options.frames_per_mesh;
      const int last = std::min(first + options.frames_per_mesh, s.num_frames());
      for (int k = first; k < last; ++k) {
        INFO("output mesh " << c << ", frame " << k);
        test::require_close(evaluate_gltf_frame(r, k).V, frames[size_t(k)]);
      }
    }
  }
}

TEST_CASE("real glTF models: animation choice and fps sampling", "[gltf][data]") {
  if (!test::have_shared_gltf()) return;
  const fs::path fox = kGltfDir / "skinned/Fox/glTF-Binary/Fox.glb";
  CHECK(load_gltf_sequence({fox, "", "Walk", std::nullopt}).num_frames() == 18);
  const GltfSequence run = load_gltf_sequence({fox, "fox1", "2", std::nullopt});
  CHECK(run.animation_name == "Run");
  CHECK(run.num_frames() == 25);
  const fs::path man = kGltfDir / "skinned/CesiumMan/glTF-Binary/CesiumMan.glb";
  const GltfSequence s = load_gltf_sequence({man, "", "", 30.0});
  const double span = s.times.back() - s.times.front();
  CHECK(s.num_frames() == int(std::floor(span * 30 + 1e-9)) + 1);
  CHECK(s.times[1] - s.times[0] == Approx(1 / 30.0));
}

TEST_CASE("static glTF models are a clear 'no animation' error", "[gltf][data]") {
  if (!test::have_shared_gltf()) return;
  for (const char* file : test::kStaticGltfModels) {
    INFO(file);
    CHECK_THROWS_AS(load_gltf_sequence({kGltfDir / file, "", "", std::nullopt}), InputError);
    CHECK_THROWS_WITH(load_gltf_sequence({kGltfDir / file, "", "", std::nullopt}),
                      Catch::Contains(file) && Catch::Contains("no animation"));
  }
}

}  // namespace
}  // namespace sm
