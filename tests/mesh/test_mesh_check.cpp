#include <catch2/catch.hpp>

#include "mesh/mesh_check.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

TEST_CASE("a clean mesh reports nothing wrong", "[mesh_check]") {
  const MeshReport r = check_mesh(make_icosphere(1, 1.0));
  CHECK(r.ok_for_optimization());
  CHECK(r.degenerate_triangles == 0);
  CHECK(r.duplicate_triangles == 0);
  CHECK(r.duplicate_vertices == 0);
  CHECK(r.boundary_loops == 0);
  CHECK(r.euler_characteristic == 2);
}

TEST_CASE("degenerate, duplicate and isolated elements are reported", "[mesh_check]") {
  TriMesh m = make_grid(2, 2, 1.0, 1.0);  // 9 vertices, 8 triangles
  m.V.conservativeResize(11, 3);
  m.V.row(9) = m.V.row(0);          // duplicate position
  m.V.row(10) << 5.0, 5.0, 5.0;     // isolated
  m.F.conservativeResize(11, 3);
  m.F.row(8) << 0, 0, 1;            // repeated index
  m.F.row(9) << 0, 1, 2;            // collinear: zero area
  m.F.row(10) = m.F.row(0);         // duplicate of triangle 0
  const MeshReport r = check_mesh(m);
  CHECK(r.degenerate_triangles == 2);
  CHECK(r.degenerate_triangle_ids == std::vector<int>{8, 9});
  CHECK(r.duplicate_triangles == 1);
  CHECK(r.duplicate_vertices == 1);
  CHECK(r.isolated_vertices == 2);  // vertices 9 and 10 are in no triangle
  CHECK_FALSE(r.ok_for_optimization());
  const std::string text = r.describe();
  CHECK(text.find("2 degenerate triangles (8, 9)") != std::string::npos);
  CHECK(text.find("2 isolated vertices") != std::string::npos);
}

TEST_CASE("mesh helpers", "[mesh]") {
  const TriMesh g = make_grid(2, 1, 2.0, 1.0);
  CHECK(triangle_areas(g).sum() == Approx(2.0));
  CHECK(bounding_box_diagonal(g.V) == Approx(std::sqrt(5.0)));
  const Positions n = vertex_normals(g);
  for (int i = 0; i < n.rows(); ++i) CHECK(n(i, 2) == Approx(1.0));
  TriMesh bad = g;
  bad.V(1, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(validate_mesh(bad, "frame 3"),
                    Catch::Contains("frame 3: vertex 1 has a non-finite coordinate y"));
  bad = g;
  bad.F(0, 2) = 99;
  CHECK_THROWS_WITH(validate_mesh(bad, "rest.obj"), Catch::Contains("refers to vertex 99"));
}
