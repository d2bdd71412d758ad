#include <catch2/catch.hpp>

#include <set>

#include "mesh/primitives.hpp"
#include "mesh/topology.hpp"

using namespace sm;

TEST_CASE("closed meshes have no boundary and the right Euler characteristic", "[topology]") {
  SECTION("icosphere") {
    const TriMesh m = make_icosphere(2, 1.0);
    const Topology t = build_topology(m);
    CHECK(t.boundary_loops.empty());
    CHECK(t.is_manifold());
    CHECK(t.euler_characteristic() == 2);
    CHECK(t.num_edges == 3 * m.num_triangles() / 2);
  }
  SECTION("torus") {
    const Topology t = build_topology(make_torus(24, 12, 2.0, 0.5));
    CHECK(t.boundary_loops.empty());
    CHECK(t.euler_characteristic() == 0);
  }
  SECTION("box") {
    const TriMesh m = make_box(4, 1.0, 2.0, 3.0);
    const Topology t = build_topology(m);
    CHECK(t.is_manifold());
    CHECK(t.euler_characteristic() == 2);
    CHECK(m.num_vertices() == 6 * 16 + 2);  // 6n^2 + 2 lattice points on the surface
  }
}

TEST_CASE("one-rings are ordered and close around interior vertices", "[topology]") {
  const TriMesh m = make_grid(4, 3, 4.0, 3.0);
  const Topology t = build_topology(m);
  REQUIRE(t.boundary_loops.size() == 1);
  CHECK(t.boundary_loops[0].size() == 2 * (4 + 3));
  for (int v = 0; v < m.num_vertices(); ++v) {
    const int b = t.one_ring.begin(v), e = t.one_ring.end(v);
    const int ntri = t.vertex_triangles.size(v);
    // Interior: as many neighbours as triangles; boundary: one more.
    CHECK(e - b == ntri + (t.is_boundary_vertex[v] ? 1 : 0));
    // Consecutive ring neighbours span a triangle with v, counter-clockwise (positive z area).
    for (int q = b; q + 1 < e || (!t.is_boundary_vertex[v] && q < e); ++q) {
      const int a = t.one_ring.data[q];
      const int c = t.one_ring.data[q + 1 < e ? q + 1 : b];
      const Vec3 n = (m.vertex(a) - m.vertex(v)).cross(m.vertex(c) - m.vertex(v));
      CHECK(n.z() > 0.0);
    }
  }
}

TEST_CASE("triangle neighbours are symmetric", "[topology]") {
  const TriMesh m = make_torus(10, 8, 2.0, 0.7);
  const Topology t = build_topology(m);
  for (int f = 0; f < m.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int g = t.triangle_neighbours[f][k];
      REQUIRE(g >= 0);
      bool back = false;
      for (int q = 0; q < 3; ++q) back = back || t.triangle_neighbours[g][q] == f;
      CHECK(back);
    }
}

TEST_CASE("non-manifold configurations are counted, not fatal", "[topology]") {
  SECTION("three triangles on one edge") {
    TriMesh m;
    m.V.resize(5, 3);
    m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
    m.F.resize(3, 3);
    m.F << 0, 1, 2, 1, 0, 3, 0, 1, 4;
    const Topology t = build_topology(m);
    CHECK(t.num_nonmanifold_edges == 1);
    CHECK_FALSE(t.is_manifold());
  }
  SECTION("bowtie vertex") {
    TriMesh m;
    m.V.resize(5, 3);
    m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0;
    m.F.resize(2, 3);
    m.F << 0, 1, 2, 0, 3, 4;
    const Topology t = build_topology(m);
    CHECK(t.num_nonmanifold_vertices == 1);
    CHECK(t.one_ring.size(0) == 4);
  }
  SECTION("isolated vertex") {
    TriMesh m = make_grid(1, 1, 1, 1);
    m.V.conservativeResize(5, 3);
    m.V.row(4) << 7, 7, 7;
    const Topology t = build_topology(m);
    CHECK(t.num_isolated_vertices == 1);
    CHECK(t.one_ring.size(4) == 0);
  }
}
