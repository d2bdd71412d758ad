#include <catch2/catch.hpp>

#include <random>

#include "geometry/surface_walk.hpp"
#include "geometry/triangle_planes.hpp"
#include "mesh/primitives.hpp"
#include "mesh/topology.hpp"

using namespace sm;

namespace {

Vec3 random_vec(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vec3(u(rng), u(rng), u(rng));
}

TrianglePoint ericson(const TriMesh& m, int t, const Vec3& p) {
  return closest_point_on_triangle(p, m.vertex(m.F(t, 0)), m.vertex(m.F(t, 1)),
                                   m.vertex(m.F(t, 2)));
}

// Random triangles (some thin, some degenerate) as a mesh of separate triangles.
TriMesh random_triangles(std::mt19937& rng, int count) {
  TriMesh m;
  m.V.resize(3 * count, 3);
  m.F.resize(count, 3);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int t = 0; t < count; ++t) {
    const Vec3 a = random_vec(rng, 1.0), b = random_vec(rng, 1.0);
    Vec3 c = random_vec(rng, 1.0);
    if (t % 7 == 3) c = a + u01(rng) * (b - a);                           // collinear
    if (t % 7 == 5) c = a + 0.5 * (b - a) + 1e-6 * random_vec(rng, 1.0);  // thin
    m.V.row(3 * t) = a.transpose();
    m.V.row(3 * t + 1) = b.transpose();
    m.V.row(3 * t + 2) = c.transpose();
    m.F.row(t) << 3 * t, 3 * t + 1, 3 * t + 2;
  }
  return m;
}

// An icosphere with bumps (convex and concave edges, seen from outside and inside).
TriMesh bumpy_sphere() {
  TriMesh bumpy = make_icosphere(3, 1.0);
  for (int v = 0; v < bumpy.num_vertices(); ++v) {
    const Vec3 p = bumpy.vertex(v);
    bumpy.V.row(v) *= 1.0 + 0.2 * std::sin(6.0 * p.x()) * std::cos(4.0 * p.z());
  }
  return bumpy;
}

// A grid folded along both diagonals' directions: a ridge and a valley.
TriMesh folded_grid() {
  TriMesh folded = make_grid(12, 12, 1.0, 1.0);
  for (int v = 0; v < folded.num_vertices(); ++v)
    folded.V(v, 2) = 0.6 * std::abs(folded.V(v, 0) - 0.5) - 0.4 * std::abs(folded.V(v, 1) - 0.5);
  return folded;
}

}  // namespace

TEST_CASE("the face case of the projection frames agrees with the full test", "[planes]") {
  std::mt19937 rng(5);
  const TriMesh m = random_triangles(rng, 400);
  const TrianglePlanes planes(m.V, m.F);
  REQUIRE(planes.size() == m.num_triangles());
  int inside = 0;
  for (int t = 0; t < m.num_triangles(); ++t)
    for (int i = 0; i < 50; ++i) {
      const Vec3 p = random_vec(rng, 1.5);
      const TrianglePoint full = ericson(m, t, p);
      TrianglePoint fast;
      if (!planes.closest_in_face(t, p, fast)) {
        // Outside the face: the full test agrees, up to points on the boundary.
        if (full.region == TriangleRegion::Face) CHECK(full.bary.minCoeff() <= 1e-9);
        continue;
      }
      ++inside;
      const double scale = 1.0 + p.squaredNorm();
      CHECK(fast.region == TriangleRegion::Face);
      CHECK(fast.dist2 == Approx(full.dist2).margin(1e-12 * scale));
      CHECK((fast.point - full.point).norm() <= 1e-9 * std::sqrt(scale));
      CHECK(fast.bary.sum() == Approx(1.0).margin(1e-12));
      CHECK(fast.bary.minCoeff() >= 0.0);
      const Vec3 at = fast.bary[0] * m.vertex(m.F(t, 0)) + fast.bary[1] * m.vertex(m.F(t, 1)) +
                      fast.bary[2] * m.vertex(m.F(t, 2));
      CHECK((at - fast.point).norm() <= 1e-9 * std::sqrt(scale));
    }
  CHECK(inside > 1000);
}

TEST_CASE("closer_than decides like the full test, its lower bound never lies", "[planes]") {
  std::mt19937 rng(6);
  const TriMesh m = random_triangles(rng, 300);
  const TrianglePlanes planes(m.V, m.F);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int closer = 0, farther = 0;
  for (int t = 0; t < m.num_triangles(); ++t)
    for (int i = 0; i < 60; ++i) {
      const Vec3 p = random_vec(rng, 1.5);
      const TrianglePoint full = ericson(m, t, p);
      // Bounds around the true distance, and the degenerate cases 0 and infinity.
      double bound2 = full.dist2 * (0.5 + u01(rng));
      if (i == 0) bound2 = 0.0;
      if (i == 1) bound2 = std::numeric_limits<double>::infinity();
      TrianglePoint out;
      const double tol = 1e-12 * (1.0 + p.squaredNorm());
      if (planes.closer_than(t, p, bound2, m.V, m.F, out)) {
        ++closer;
        CHECK(out.dist2 < bound2);
        CHECK(out.dist2 == Approx(full.dist2).margin(tol));
      } else {
        ++farther;
        CHECK(full.dist2 >= bound2 - tol);
      }
    }
  CHECK(closer > 1000);
  CHECK(farther > 1000);
}

TEST_CASE("the walk with projection frames finds the same points", "[planes][walk]") {
  for (const TriMesh& mesh : {make_icosphere(3, 1.0), make_torus(40, 20, 2.0, 0.6),
                              make_box(6, 1.0, 2.0, 0.5), make_grid(20, 20, 2.0, 1.0)}) {
    const Topology topo = build_topology(mesh);
    const TrianglePlanes planes(mesh.V, mesh.F);
    const double h = mean_edge_length(mesh);
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> tri(0, mesh.num_triangles() - 1);
    int same = 0;
    const int count = 1000;
    for (int i = 0; i < count; ++i) {
      const int t = tri(rng);
      const Vec3 p = mesh.vertex(mesh.F(t, 0)) + h * random_vec(rng, 0.5);
      SurfacePoint plain, fast;
      const bool a = walk_closest(mesh.V, mesh.F, topo, p, t, 50, plain);
      const bool b = walk_closest(mesh.V, mesh.F, topo, p, t, 50, fast, &planes);
      REQUIRE(a);
      REQUIRE(b);
      // Both settle on a local minimum; ties between triangles sharing the answer may differ.
      CHECK(fast.dist2 == Approx(plain.dist2).margin(1e-14));
      if ((fast.point - plain.point).norm() <= 1e-9 * h) ++same;
    }
    CHECK(same >= 0.98 * count);
  }
}

TEST_CASE("a walk that runs out of steps returns the best point seen", "[planes][walk]") {
  const TriMesh mesh = make_grid(30, 30, 1.0, 1.0);
  const Topology topo = build_topology(mesh);
  const TrianglePlanes planes(mesh.V, mesh.F);
  const Vec3 p(0.9, 0.9, 0.05);
  SurfacePoint out;
  REQUIRE_FALSE(walk_closest(mesh.V, mesh.F, topo, p, 0, 2, out, &planes));
  REQUIRE(out.triangle >= 0);
  // An upper bound: a real point of the mesh, closer than the start triangle.
  CHECK(out.dist2 == Approx((p - out.point).squaredNorm()).margin(1e-12));
  CHECK(out.dist2 < ericson(mesh, 0, p).dist2);
}

TEST_CASE("a face that settles has no closer edge neighbour", "[planes]") {
  // Convex and concave edges (box, bumpy sphere seen from outside and inside, a folded grid),
  // points inside faces at heights from far below to far above the surface.
  const TriMesh bumpy = bumpy_sphere(), folded = folded_grid();
  for (const TriMesh& mesh : {make_box(4, 1.0, 2.0, 0.5), bumpy, folded}) {
    const Topology topo = build_topology(mesh);
    const TrianglePlanes planes(mesh.V, mesh.F, &topo);
    const TrianglePlanes unknown(mesh.V, mesh.F);
    const double h = mean_edge_length(mesh);
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> u01(0.0, 1.0), height(-1.0, 1.0);
    int settled = 0, count = 0;
    for (int t = 0; t < mesh.num_triangles(); ++t)
      for (int i = 0; i < 40; ++i) {
        double a = u01(rng), b = u01(rng);
        if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
        const Vec3 bary(1.0 - a - b, a, b);
        const Vec3 foot = bary[0] * mesh.vertex(mesh.F(t, 0)) +
                          bary[1] * mesh.vertex(mesh.F(t, 1)) + bary[2] * mesh.vertex(mesh.F(t, 2));
        const Vec3 p = foot + std::pow(height(rng), 3) * 2.0 * h * planes[t].normal;
        TrianglePoint face;
        if (!planes.closest_in_face(t, p, face)) continue;
        ++count;
        CHECK_FALSE(unknown.face_settles(t, p, face.bary));
        if (!planes.face_settles(t, p, face.bary)) continue;
        ++settled;
        for (int k = 0; k < 3; ++k) {
          const int across = topo.triangle_neighbours[t][k];
          if (across < 0) continue;
          INFO("triangle " << t << " edge " << k << " height " << (p - foot).norm() / h);
          CHECK(ericson(mesh, across, p).dist2 >= face.dist2 * (1.0 - 1e-12) - 1e-24);
        }
      }
    CHECK(settled > count / 2);
  }
}

TEST_CASE("bends only spare tests: a walk answers the same with or without them",
          "[planes][walk]") {
  // The walk's shortcuts (the start face settling, face_settles later on) may skip neighbours
  // only when they cannot be closer: the answers must be bit-identical to the walk that tries
  // them all, also when it runs out of steps. Convex and concave edges, queries above and below.
  const TriMesh bumpy = bumpy_sphere(), folded = folded_grid();
  for (const TriMesh& mesh :
       {bumpy, folded, make_torus(40, 20, 2.0, 0.6), make_box(4, 1.0, 2.0, 0.5)}) {
    const Topology topo = build_topology(mesh);
    const TrianglePlanes bends(mesh.V, mesh.F, &topo), none(mesh.V, mesh.F);
    REQUIRE(bends.has_bends());
    REQUIRE_FALSE(none.has_bends());
    const double h = mean_edge_length(mesh);
    std::mt19937 rng(12);
    std::uniform_int_distribution<int> tri(0, mesh.num_triangles() - 1), edge(0, 2);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    int settled_at_start = 0;
    for (int i = 0; i < 3000; ++i) {
      const int t = tri(rng);
      double a = u01(rng), b = u01(rng);
      if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
      const Vec3 foot = (1.0 - a - b) * mesh.vertex(mesh.F(t, 0)) + a * mesh.vertex(mesh.F(t, 1)) +
                        b * mesh.vertex(mesh.F(t, 2));
      const Vec3 p = foot + h * (0.3 * random_vec(rng, 1.0) + (u01(rng) - 0.5) * bends[t].normal);
      int start = t;  // mostly the triangle below, else up to three edges away
      for (int hop = 0; hop < i % 4; ++hop)
        if (const int u = topo.triangle_neighbours[start][edge(rng)]; u >= 0) start = u;
      const int steps = i % 5 == 4 ? 1 : 16;
      SurfacePoint with, without;
      const bool a_ok = walk_closest(mesh.V, mesh.F, topo, p, start, steps, with, &bends);
      const bool b_ok = walk_closest(mesh.V, mesh.F, topo, p, start, steps, without, &none);
      REQUIRE(a_ok == b_ok);
      REQUIRE(with.triangle == without.triangle);
      CHECK(with.dist2 == without.dist2);
      CHECK((with.point - without.point).norm() == 0.0);
      CHECK((with.bary - without.bary).norm() == 0.0);
      TrianglePoint face;
      if (with.triangle == start && bends.closest_in_face(start, p, face) &&
          bends.face_settles(start, p, face.bary))
        ++settled_at_start;
    }
    CHECK(settled_at_start > 300);
  }
}
