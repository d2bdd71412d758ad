#include <catch2/catch.hpp>

#include <random>

#include "geometry/bvh.hpp"
#include "geometry/closest_point.hpp"
#include "geometry/surface_walk.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"
#include "mesh/topology.hpp"
#include "support/brute_force_closest.hpp"

using namespace sm;
using test::brute_force_dist2;

namespace {

Vec3 random_surface_point(const TriMesh& mesh, int t, std::mt19937& rng) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  double a = u01(rng), b = u01(rng);
  if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
  return (1.0 - a - b) * mesh.vertex(mesh.F(t, 0)) + a * mesh.vertex(mesh.F(t, 1)) +
         b * mesh.vertex(mesh.F(t, 2));
}

// A triangle `hops` random steps across edges away from t.
int wander(const Topology& topo, int t, int hops, std::mt19937& rng) {
  std::uniform_int_distribution<int> edge(0, 2);
  for (int i = 0; i < hops; ++i) {
    const int next = topo.triangle_neighbours[t][edge(rng)];
    if (next >= 0) t = next;
  }
  return t;
}

}  // namespace

TEST_CASE("walk settles on a local minimum near the surface", "[walk]") {
  // Inside a convex edge (and near any concave region) the distance restricted to the surface
  // has several local minima, and the walk promises only one of them: check that the answer is
  // one, independently of the walk's region logic, and that it is usually the global minimum.
  const std::vector<TriMesh> meshes = {make_icosphere(3, 1.0), make_torus(40, 20, 2.0, 0.6),
                                       make_box(6, 1.0, 2.0, 0.5), make_cylinder(24, 8, 1.0, 2.0),
                                       make_grid(20, 20, 2.0, 1.0)};
  unsigned seed = 1;
  for (const TriMesh& mesh : meshes) {
    const Topology topo = build_topology(mesh);
    const double h = mean_edge_length(mesh);
    std::mt19937 rng(seed++);
    std::uniform_int_distribution<int> tri(0, mesh.num_triangles() - 1);
    std::uniform_real_distribution<double> u11(-1.0, 1.0);
    int global = 0;
    const int count = 1000;
    for (int i = 0; i < count; ++i) {
      const int t = tri(rng);
      // Within 0.4 edge lengths of the surface, starting up to three triangles away.
      const Vec3 offset = Vec3(u11(rng), u11(rng), u11(rng)).normalized() * std::abs(u11(rng));
      const Vec3 p = random_surface_point(mesh, t, rng) + 0.4 * h * offset;
      const int start = wander(topo, t, i % 4, rng);
      SurfacePoint out;
      REQUIRE(walk_closest(mesh.V, mesh.F, topo, p, start, 50, out));
      // The answer is the closest point of the triangle it names...
      const TrianglePoint own = closest_point_on_triangle(p, mesh.vertex(mesh.F(out.triangle, 0)),
                                                          mesh.vertex(mesh.F(out.triangle, 1)),
                                                          mesh.vertex(mesh.F(out.triangle, 2)));
      CHECK(own.dist2 == out.dist2);
      CHECK((own.point - out.point).norm() == 0.0);
      CHECK((own.bary - out.bary).norm() == 0.0);
      // ...and no triangle through that point (its whole surface neighbourhood) is closer.
      for (int s = 0; s < mesh.num_triangles(); ++s) {
        const Vec3 a = mesh.vertex(mesh.F(s, 0)), b = mesh.vertex(mesh.F(s, 1)),
                   c = mesh.vertex(mesh.F(s, 2));
        if (closest_point_on_triangle(out.point, a, b, c).dist2 > 1e-24) continue;
        CHECK(closest_point_on_triangle(p, a, b, c).dist2 >= out.dist2 - 1e-15);
      }
      if (out.dist2 <= brute_force_dist2(mesh, p) + 1e-15) ++global;
    }
    CHECK(global >= 0.9 * count);
  }
}

TEST_CASE("walk agrees with brute force outside convex meshes", "[walk]") {
  // Outside a convex surface the distance has a single local minimum near the query.
  for (const TriMesh& mesh : {make_icosphere(3, 1.0), make_box(6, 1.0, 2.0, 0.5)}) {
    const Topology topo = build_topology(mesh);
    const Positions N = triangle_normals(mesh);
    const double h = mean_edge_length(mesh);
    std::mt19937 rng(21);
    std::uniform_int_distribution<int> tri(0, mesh.num_triangles() - 1);
    std::uniform_real_distribution<double> u01(0.0, 1.0), u11(-1.0, 1.0);
    for (int i = 0; i < 1000; ++i) {
      const int t = tri(rng);
      const Vec3 n = N.row(t).transpose();
      const Vec3 tangent = Vec3(u11(rng), u11(rng), u11(rng)).cross(n);
      const Vec3 p = random_surface_point(mesh, t, rng) + h * (0.5 * u01(rng) * n + 0.5 * tangent);
      SurfacePoint out;
      REQUIRE(walk_closest(mesh.V, mesh.F, topo, p, wander(topo, t, i % 5, rng), 50, out));
      CHECK(out.dist2 == Approx(brute_force_dist2(mesh, p)).margin(1e-15));
    }
  }
}

TEST_CASE("walk on a planar grid finds the global minimum from anywhere", "[walk]") {
  // The grid is a convex set, so its distance field has one local minimum: a walk that
  // settles must be exact, also for queries beyond its boundary (edges without neighbours).
  const TriMesh mesh = make_grid(12, 9, 3.0, 2.0);
  const Topology topo = build_topology(mesh);
  std::mt19937 rng(4);
  std::uniform_int_distribution<int> tri(0, mesh.num_triangles() - 1);
  std::uniform_real_distribution<double> ux(-2.0, 5.0), uy(-2.0, 4.0), uz(-1.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p(ux(rng), uy(rng), uz(rng));
    SurfacePoint out;
    REQUIRE(walk_closest(mesh.V, mesh.F, topo, p, tri(rng), 1000, out));
    CHECK(out.dist2 == Approx(brute_force_dist2(mesh, p)).margin(1e-13));
  }
}

TEST_CASE("walk reports running out of steps instead of a wrong answer", "[walk]") {
  const TriMesh mesh = make_grid(16, 16, 1.0, 1.0);
  const Topology topo = build_topology(mesh);
  std::mt19937 rng(8);
  std::uniform_int_distribution<int> tri(0, mesh.num_triangles() - 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int refused = 0, answered = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p(u(rng), u(rng), 0.1 * u(rng));
    const int start = tri(rng);
    const int steps = i % 4;
    SurfacePoint limited, unlimited;
    REQUIRE(walk_closest(mesh.V, mesh.F, topo, p, start, 10000, unlimited));
    if (walk_closest(mesh.V, mesh.F, topo, p, start, steps, limited)) {
      ++answered;
      // Settling within the limit: the same end as an unlimited walk, hence exact here.
      CHECK(limited.triangle == unlimited.triangle);
      CHECK(limited.dist2 == Approx(brute_force_dist2(mesh, p)).margin(1e-13));
    } else {
      ++refused;
    }
  }
  CHECK(refused > 0);
  CHECK(answered > 0);

  // With zero steps the walk only settles where it starts.
  const Vec3 above(0.51, 0.52, 0.3);
  SurfacePoint exact = TriangleBvh(mesh).closest(above), out;
  REQUIRE(walk_closest(mesh.V, mesh.F, topo, above, exact.triangle, 0, out));
  CHECK(out.triangle == exact.triangle);
  const int far_start = exact.triangle == 0 ? mesh.num_triangles() - 1 : 0;
  CHECK_FALSE(walk_closest(mesh.V, mesh.F, topo, above, far_start, 0, out));
}

TEST_CASE("walk handles non-manifold edges and rejects bad starts", "[walk]") {
  // Three triangles on one edge (0, 1): no neighbours across it, the walk tries both fans.
  TriMesh mesh;
  mesh.V = Positions(5, 3);
  mesh.V << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0, 1;
  mesh.F = Triangles(3, 3);
  mesh.F << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  const Topology topo = build_topology(mesh);
  REQUIRE(topo.num_nonmanifold_edges > 0);
  const Vec3 p(0.5, 0.1, 0.8);  // over triangle 2
  SurfacePoint out;
  REQUIRE(walk_closest(mesh.V, mesh.F, topo, p, 1, 5, out));
  CHECK(out.triangle == 2);
  CHECK(out.dist2 == Approx(brute_force_dist2(mesh, p)));

  CHECK_THROWS_AS(walk_closest(mesh.V, mesh.F, topo, p, -1, 5, out), InputError);
  CHECK_THROWS_AS(walk_closest(mesh.V, mesh.F, topo, p, 3, 5, out), InputError);
}
