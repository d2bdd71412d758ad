#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "geometry/bvh.hpp"
#include "geometry/closest_point.hpp"
#include "geometry/distance.hpp"
#include "geometry/surface_walk.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"
#include "mesh/topology.hpp"
#include "support/brute_force_closest.hpp"

using namespace sm;

namespace {

std::vector<TriMesh> test_meshes() {
  return {make_icosphere(3, 1.0), make_torus(40, 20, 2.0, 0.6), make_box(6, 1.0, 2.0, 0.5),
          make_cylinder(24, 8, 1.0, 2.0), make_grid(20, 20, 2.0, 1.0)};
}

// Half of the queries lie near the surface (a random surface point moved by up to `near` along
// a random direction), half anywhere in the bounding box grown by its diagonal.
std::vector<Vec3> queries(const Positions& V, const Triangles& F, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0), u11(-1.0, 1.0);
  std::uniform_int_distribution<int> tri(0, static_cast<int>(F.rows()) - 1);
  const Vec3 lo = V.colwise().minCoeff().transpose(), hi = V.colwise().maxCoeff().transpose();
  const double diag = (hi - lo).norm();
  std::vector<Vec3> q;
  for (int i = 0; i < count; ++i) {
    if (i % 2 == 0) {
      const int t = tri(rng);
      double a = u01(rng), b = u01(rng);
      if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
      const Vec3 p = V.row(F(t, 0)).transpose() * (1.0 - a - b) + V.row(F(t, 1)).transpose() * a +
                     V.row(F(t, 2)).transpose() * b;
      q.push_back(p + 0.05 * diag * u01(rng) * Vec3(u11(rng), u11(rng), u11(rng)));
    } else {
      const Vec3 s(u01(rng), u01(rng), u01(rng));
      q.push_back(lo - Vec3::Constant(diag) +
                  (hi - lo + Vec3::Constant(2.0 * diag)).cwiseProduct(s));
    }
  }
  return q;
}

void check_against_brute_force(const TriangleBvh& bvh, const Positions& V, const Triangles& F,
                               const std::vector<Vec3>& qs) {
  const double diag = bounding_box_diagonal(V);
  for (const Vec3& p : qs) {
    const SurfacePoint got = bvh.closest(p);
    const SurfacePoint want = test::brute_force_closest(V, F, p);
    REQUIRE(got.triangle >= 0);
    CHECK(got.dist2 == Approx(want.dist2).margin(1e-14 * diag * diag));
    // The reported triangle holds the reported point, whichever of several tied triangles won.
    const TrianglePoint own = closest_point_on_triangle(p, V.row(F(got.triangle, 0)).transpose(),
                                                        V.row(F(got.triangle, 1)).transpose(),
                                                        V.row(F(got.triangle, 2)).transpose());
    CHECK(own.dist2 == got.dist2);
    CHECK((own.point - got.point).norm() <= 1e-12 * diag);
    CHECK((got.point - p).squaredNorm() == Approx(got.dist2).margin(1e-14 * diag * diag));
  }
}

}  // namespace

TEST_CASE("BVH closest point equals brute force", "[bvh]") {
  unsigned seed = 1;
  for (const TriMesh& mesh : test_meshes()) {
    const TriangleBvh bvh(mesh);
    REQUIRE_FALSE(bvh.empty());
    CHECK(bvh.triangles() == mesh.F);
    check_against_brute_force(bvh, mesh.V, mesh.F, queries(mesh.V, mesh.F, 1200, seed++));
  }
}

TEST_CASE("BVH respects the distance bound", "[bvh]") {
  const TriMesh mesh = make_torus(30, 15, 2.0, 0.6);
  const TriangleBvh bvh(mesh);
  for (const Vec3& p : queries(mesh.V, mesh.F, 300, 9)) {
    const SurfacePoint want = test::brute_force_closest(mesh.V, mesh.F, p);
    if (want.dist2 == 0.0) continue;
    CHECK(bvh.closest(p, 0.5 * want.dist2).triangle == -1);
    CHECK(bvh.closest(p, want.dist2).triangle == -1);  // strictly closer only
    const SurfacePoint got = bvh.closest(p, want.dist2 * (1.0 + 1e-9));
    REQUIRE(got.triangle >= 0);
    CHECK(got.dist2 == Approx(want.dist2).epsilon(1e-12));
  }
}

TEST_CASE("BVH refit follows new positions", "[bvh]") {
  unsigned seed = 100;
  for (const TriMesh& mesh : test_meshes()) {
    TriangleBvh bvh(mesh);
    // Twist around z, stretch along x and jitter: boxes change a lot, the tree is kept.
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.02, 0.02);
    Positions W = mesh.V;
    for (int i = 0; i < W.rows(); ++i) {
      const double angle = 0.8 * W(i, 2), c = std::cos(angle), s = std::sin(angle);
      const double x = W(i, 0), y = W(i, 1);
      W(i, 0) = 1.7 * (c * x - s * y) + jitter(rng);
      W(i, 1) = s * x + c * y + jitter(rng);
      W(i, 2) += jitter(rng);
    }
    bvh.refit(W);
    CHECK(bvh.positions() == W);
    check_against_brute_force(bvh, W, mesh.F, queries(W, mesh.F, 1000, seed++));
    // Back to the original positions: the same answers as a freshly built tree.
    bvh.refit(mesh.V);
    const TriangleBvh fresh(mesh);
    for (const Vec3& p : queries(mesh.V, mesh.F, 200, seed++))
      CHECK(bvh.closest(p).dist2 == fresh.closest(p).dist2);
  }
}

TEST_CASE("BVH queries from many threads agree with one thread", "[bvh]") {
  const TriMesh mesh = make_icosphere(4, 1.0);
  const TriangleBvh bvh(mesh);
  const std::vector<Vec3> qs = queries(mesh.V, mesh.F, 20000, 5);
  std::vector<SurfacePoint> parallel(qs.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, qs.size(), 64),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t i = r.begin(); i != r.end(); ++i)
                        parallel[i] = bvh.closest(qs[i]);
                    });
  for (size_t i = 0; i < qs.size(); ++i) {
    const SurfacePoint s = bvh.closest(qs[i]);
    CHECK(s.triangle == parallel[i].triangle);
    CHECK(s.dist2 == parallel[i].dist2);
  }
}

TEST_CASE("BVH edge cases", "[bvh]") {
  const TriangleBvh none;
  CHECK(none.empty());
  CHECK(none.closest(Vec3(1, 2, 3)).triangle == -1);

  TriMesh one;
  one.V = Positions(3, 3);
  one.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  one.F = Triangles(1, 3);
  one.F << 0, 1, 2;
  TriangleBvh single(one);
  const SurfacePoint s = single.closest(Vec3(0.25, 0.25, 2.0));
  CHECK(s.triangle == 0);
  CHECK(s.dist2 == Approx(4.0));

  CHECK_THROWS_AS(single.refit(Positions::Zero(4, 3)), InputError);
  TriMesh bad = one;
  bad.F(0, 2) = 7;
  CHECK_THROWS_AS(TriangleBvh(bad), InputError);

  // Long triangles crossing near one axis: every box overlaps every other one.
  TriMesh fan;
  const int k = 64;
  fan.V = Positions(2 * k, 3);
  fan.F = Triangles(k, 3);
  for (int i = 0; i < k; ++i) {
    const double a = M_PI * i / k;
    fan.V.row(2 * i) << std::cos(a), std::sin(a), 0.01 * i;
    fan.V.row(2 * i + 1) << -std::cos(a), -std::sin(a), -0.01 * i;
  }
  for (int i = 0; i < k; ++i) fan.F.row(i) << 2 * i, 2 * i + 1, 2 * ((i + 1) % k);
  const TriangleBvh fan_bvh(fan);
  check_against_brute_force(fan_bvh, fan.V, fan.F, queries(fan.V, fan.F, 300, 77));

  // Identical triangles (equal centroids everywhere) and a few small meshes around the leaf size.
  TriMesh copies = make_grid(1, 1, 1.0, 1.0);
  Triangles many(41, 3);
  for (int i = 0; i < 40; ++i) many.row(i) = copies.F.row(0);
  many.row(40) = copies.F.row(1);
  copies.F = many;
  check_against_brute_force(TriangleBvh(copies), copies.V, copies.F,
                            queries(copies.V, copies.F, 300, 78));
  for (int cells : {2, 3, 5}) {
    const TriMesh small = make_grid(cells, 1, 1.0, 1.0);  // 4, 6 and 10 triangles
    check_against_brute_force(TriangleBvh(small), small.V, small.F,
                              queries(small.V, small.F, 200, 79));
  }
}
