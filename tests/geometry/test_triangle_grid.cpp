#include <catch2/catch.hpp>

#include <random>

#include "geometry/distance.hpp"
#include "geometry/triangle_grid.hpp"
#include "mesh/primitives.hpp"
#include "support/brute_force_closest.hpp"

using namespace sm;
using test::brute_force_dist2;

namespace {

// A bumpy sphere: not convex, uneven triangles.
TriMesh bumpy_sphere() {
  TriMesh m = make_icosphere(3, 1.0);
  for (int v = 0; v < m.num_vertices(); ++v) {
    const Vec3 p = m.vertex(v);
    m.V.row(v) *= 1.0 + 0.15 * std::sin(5.0 * p.x()) * std::cos(3.0 * p.y());
  }
  return m;
}

}  // namespace

TEST_CASE("grid queries are exact whenever they answer", "[grid]") {
  for (const TriMesh& mesh :
       {bumpy_sphere(), make_torus(40, 16, 2.0, 0.5), make_grid(10, 10, 1, 1)}) {
    const Topology topo = build_topology(mesh);
    const TrianglePlanes planes(mesh.V, mesh.F, &topo);  // with bends: settled hints skip
    const double h = mean_edge_length(mesh);
    for (double cell : {0.5 * h, h, 3.0 * h}) {
      const TriangleGrid grid(mesh.V, mesh.F, planes, cell, cell == h ? &topo : nullptr);
      std::mt19937 rng(17);
      std::uniform_int_distribution<int> vertex(0, mesh.num_vertices() - 1);
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      int answered = 0;
      const int count = 400;
      for (int i = 0; i < count; ++i) {
        // Near the surface mostly, some farther than a cell.
        const double reach = (i % 5 == 0 ? 4.0 : 0.3) * h;
        const Vec3 p = mesh.vertex(vertex(rng)) + reach * Vec3(u(rng), u(rng), u(rng));
        double best2 = std::numeric_limits<double>::infinity();
        int best = -1;
        const int hint = i % 3 == 0 ? -1 : (i * 7919) % mesh.num_triangles();
        if (!grid.closest(p, best2, best, hint)) continue;
        ++answered;
        REQUIRE(best >= 0);
        CHECK(best2 == Approx(brute_force_dist2(mesh, p)).margin(1e-13));
      }
      INFO("mesh of " << mesh.num_triangles() << " triangles, cell " << cell / h << " h");
      CHECK(answered >= (cell < h ? count / 5 : count / 2));
    }
  }
}

TEST_CASE("grid queries only improve on the bound they are given", "[grid]") {
  const TriMesh mesh = make_torus(30, 12, 2.0, 0.5);
  const TrianglePlanes planes(mesh.V, mesh.F);
  const TriangleGrid grid(mesh.V, mesh.F, planes, mean_edge_length(mesh));
  const Vec3 p(2.0, 0.0, 0.55);
  const double exact = brute_force_dist2(mesh, p);
  double best2 = 0.5 * exact;  // nothing beats it
  int best = -1;
  CHECK(grid.closest(p, best2, best));
  CHECK(best == -1);
  CHECK(best2 == 0.5 * exact);
  // Far outside the grid: no answer, the caller must ask an exact structure.
  double far2 = std::numeric_limits<double>::infinity();
  CHECK_FALSE(grid.closest(Vec3(50.0, 0.0, 0.0), far2, best));
}

TEST_CASE("sampled distance equals brute force at the samples", "[grid][distance]") {
  // Vertex samples only, so that the expected values are easy to enumerate; B near A (grid
  // answers), partly far from it (the BVH answers) and degenerate triangles in B.
  const TriMesh a = bumpy_sphere();
  for (double offset : {0.01, 0.3, 3.0}) {
    TriMesh b = make_icosphere(2, 1.05);
    b.V.col(0).array() += offset;
    b.V.row(b.F(0, 1)) = b.V.row(b.F(0, 0));  // a degenerate triangle
    DistanceOptions o;
    o.sample_edges = o.sample_faces = false;
    const DistanceStats d = one_sided_distance(a, TriangleBvh(b), o);
    double max = 0.0, sum = 0.0, sum2 = 0.0;
    for (int v = 0; v < a.num_vertices(); ++v) {
      const double d2 = brute_force_dist2(b, a.vertex(v));
      max = std::max(max, std::sqrt(d2));
      sum += std::sqrt(d2);
      sum2 += d2;
    }
    REQUIRE(d.samples == a.num_vertices());
    CHECK(d.max == Approx(max).margin(1e-12));
    CHECK(d.mean == Approx(sum / a.num_vertices()).margin(1e-12));
    CHECK(d.rms == Approx(std::sqrt(sum2 / a.num_vertices())).margin(1e-12));
  }
}

TEST_CASE("a grid rebuilt for another mesh answers as a new grid does", "[grid]") {
  // build() reuses the arrays of the previous mesh (larger, then smaller, then empty).
  const TriMesh meshes[] = {make_torus(40, 16, 2.0, 0.5), bumpy_sphere(), make_grid(3, 3, 1, 1)};
  TriangleGrid reused;
  for (const TriMesh& mesh : meshes) {
    const TrianglePlanes planes(mesh.V, mesh.F);
    const double h = mean_edge_length(mesh);
    reused.build(mesh.V, mesh.F, planes, h);
    const TriangleGrid fresh(mesh.V, mesh.F, planes, h);
    CHECK(reused.cell_size() == fresh.cell_size());
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> vertex(0, mesh.num_vertices() - 1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 200; ++i) {
      const Vec3 p = mesh.vertex(vertex(rng)) + 0.3 * h * Vec3(u(rng), u(rng), u(rng));
      double a2 = std::numeric_limits<double>::infinity(), b2 = a2;
      int a = -1, b = -1;
      const bool ra = reused.closest(p, a2, a), rb = fresh.closest(p, b2, b);
      CHECK(ra == rb);
      CHECK(a == b);
      CHECK(a2 == b2);
    }
  }
  const TriMesh none;
  const TrianglePlanes no_planes(none.V, none.F);
  reused.build(none.V, none.F, no_planes, 1.0);
  CHECK(reused.empty());
  double d2 = 1.0;
  int t = -1;
  CHECK_FALSE(reused.closest(Vec3::Zero(), d2, t));
}
