// Sampling density bounded by the input (issue 24.6): the subdivisions of an edge are computed in
// floating point (a spacing of 1e-30 overflowed the conversion to an integer and sampled the
// vertices only), and a spacing whose sample count exceeds the budget is a config error before
// any sample is taken. The count is checked against the samples the sampler really takes.
#include <catch2/catch.hpp>

#include <cmath>
#include <utility>

#include "geometry/distance.hpp"
#include "geometry/sample_budget.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"
#include "support/error_of.hpp"

using namespace sm;
using sm::test::error_of;

namespace {

TriMesh raised(TriMesh mesh, double dz) {
  mesh.V.col(2).array() += dz;
  return mesh;
}

// Interior points of the barycentric lattice of n divisions.
double lattice(double n) {
  return (n - 1) * (n - 2) / 2;
}

}  // namespace

TEST_CASE("an edge's divisions are computed in floating point and clamped", "[distance]") {
  CHECK(sample_divisions(1.0, 0.3, 100) == 4);
  CHECK(sample_divisions(1.0, 0.25, 100) == 4);
  CHECK(sample_divisions(0.0, 0.25, 100) == 1);
  CHECK(sample_divisions(1.0, 0.0, 100) == 1);
  CHECK(sample_divisions(1.0, -1.0, 100) == 1);
  CHECK(sample_divisions(1.0, 1e-30, kMaxEdgeSegments) == kMaxEdgeSegments);  // 1e30: the cap
  CHECK(sample_divisions(1e300, 1e-300, kMaxEdgeSegments) == kMaxEdgeSegments);  // inf
  CHECK(sample_divisions(NAN, 1.0, 100) == 1);
}

TEST_CASE("a spacing of 1e-30 samples every edge at the cap, not the vertices only",
          "[distance]") {
  TriMesh one;
  one.V.resize(3, 3);
  one.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  one.F.resize(1, 3);
  one.F << 0, 1, 2;
  DistanceOptions o;
  o.spacing = 1e-30;
  o.sample_faces = false;  // edges only: 3 × (2^20 − 1) interior points and the 3 corners
  const DistanceStats d = one_sided_distance(one, TriangleBvh(raised(one, 0.5)), o);
  CHECK(d.samples == 3 + 3 * (kMaxEdgeSegments - 1));
  CHECK(d.max == Approx(0.5));
}

TEST_CASE("the sample count is the number of samples taken", "[distance]") {
  const TriMesh a = make_grid(5, 3, 2.0, 1.5);
  const TriMesh b = raised(a, 0.25);  // every sample 0.25 away: every triangle refined
  const TriangleBvh bvh(b);
  const DistanceLayout layout(a.F, a.num_vertices());
  for (const double spacing : {0.25, 0.1, 0.013}) {
    for (const bool adaptive : {false, true}) {
      const std::pair<bool, bool> kinds[] = {{true, true}, {true, false}, {false, true}};
      for (const auto& [edges, faces] : kinds) {
        DistanceOptions o;
        o.spacing = spacing;
        o.adaptive = adaptive;
        o.refine_above = 0.0;  // adaptive: every triangle with a distance, at both levels
        o.sample_edges = edges;
        o.sample_faces = faces;
        INFO("spacing " << spacing << ", adaptive " << adaptive << ", edges " << edges
                        << ", faces " << faces);
        const DistanceStats d = one_sided_distance(a, bvh, o);
        CHECK(distance_sample_count(a, layout, o) == double(d.samples));
        if (adaptive) CHECK(d.refined == a.num_triangles());
      }
    }
  }
}

TEST_CASE("a spacing beyond the sample budget is a config error naming the key and count",
          "[distance]") {
  // 2 × 2 cells: 9 vertices, 8 triangles, 16 edges (12 of length 1, 4 diagonals). At a spacing of
  // 1e-9 mean edge lengths every edge is split 2^20 times and every triangle's lattice has 2^12
  // divisions (the caps).
  const TriMesh a = make_grid(2, 2, 2.0, 2.0);
  const TriangleBvh bvh(raised(a, 1.0));
  DistanceOptions o;
  o.spacing = 1e-9;
  const double edge = double(kMaxEdgeSegments - 1), face = lattice(kMaxFaceDivisions);
  const double uniform = 9 + 16 * edge + 8 * face;
  REQUIRE(uniform == 83836929.0);
  CHECK(error_of<OptionError>([&] { one_sided_distance(a, bvh, o); }) ==
        "spacing: 1e-09 would take 83836929 samples on the sampled mesh (8 triangles), "
        "more than the budget of 50000000 (50 million, or 100 per triangle); choose a larger "
        "spacing");
  // Adaptive: the vertices and centroids, then both levels on every triangle at most.
  o.adaptive = true;
  const double adaptive = 9 + 8 + 2 * 8 * (3 * edge + face);
  REQUIRE(adaptive == 184451057.0);
  CHECK(error_of<OptionError>([&] { one_sided_distance(a, bvh, o); }) ==
        "spacing: 1e-09 would take up to 184451057 samples on the sampled mesh (8 "
        "triangles), more than the budget of 50000000 (50 million, or 100 per triangle); choose "
        "a larger spacing");
  // The budget grows with the mesh beyond 500,000 triangles.
  CHECK(distance_sample_budget(8) == 50e6);
  CHECK(distance_sample_budget(2'000'000) == 200e6);
}

TEST_CASE("the budget refuses exactly the spacings whose count exceeds it", "[distance]") {
  // A grid with one corner pulled far out (two long needles among small triangles), so that a
  // bound from the longest edge and the exact count disagree over a range of spacings: the
  // refusal must follow the exact count, on both sides of the budget.
  TriMesh a = make_grid(20, 20, 1.0, 1.0);
  a.V.row(0) = Eigen::RowVector3d(-300.0, -200.0, 0.0);
  const TriangleBvh bvh(raised(a, 0.5));
  const DistanceLayout layout(a.F, a.num_vertices());
  for (const bool adaptive : {false, true}) {
    int refused = 0, accepted = 0;
    for (double spacing = 1.0; spacing > 1e-6; spacing *= 0.8) {
      DistanceOptions o;
      o.adaptive = adaptive;
      o.spacing = spacing;
      const double count = distance_sample_count(a, layout, o);
      const bool over = count > distance_sample_budget(a.num_triangles());
      CAPTURE(adaptive, spacing, count);
      bool threw = false;
      try {
        check_distance_samples(a, layout, o, "the sampled mesh");
      } catch (const OptionError&) {
        threw = true;
      }
      CHECK(threw == over);
      (over ? refused : accepted) += 1;
    }
    CHECK(refused > 0);
    CHECK(accepted > 0);
  }
}
