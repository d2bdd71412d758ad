// The optimizer on meshes that are valid input but not clean manifolds:
// isolated vertices, non-manifold edges and vertices, degenerate and duplicate triangles in the
// template or in a frame. None may crash or produce a NaN; what happens to each is defined here.
#include <catch2/catch.hpp>

#include "massage/massage.hpp"
#include "mesh/mesh_check.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

namespace {

// A 6×6 grid over [0, 1]² bent into a gentle bump, and the same mesh with its interior vertices
// slid tangentially (in x, y) by a smooth field: the frame to correct.
struct Pair {
  TriMesh templ;
  TriMesh frame;
};

Pair bumpy_grid() {
  Pair p;
  p.templ = make_grid(6, 6, 1.0, 1.0);
  for (int i = 0; i < p.templ.num_vertices(); ++i) {
    const double x = p.templ.V(i, 0), y = p.templ.V(i, 1);
    p.templ.V(i, 2) = 0.2 * x * (1 - x) * y * (1 - y);
  }
  p.frame = p.templ;
  for (int i = 0; i < p.frame.num_vertices(); ++i) {
    const double x = p.frame.V(i, 0), y = p.frame.V(i, 1);
    const double s = x * (1 - x) * y * (1 - y);  // 0 on the boundary
    p.frame.V(i, 0) += 0.8 * s;
    p.frame.V(i, 1) -= 0.5 * s;
  }
  return p;
}

// Appends vertex `v` (row) to both meshes.
int add_vertex(Pair& p, const Vec3& v) {
  const int n = p.templ.num_vertices();
  for (TriMesh* m : {&p.templ, &p.frame}) {
    m->V.conservativeResize(n + 1, 3);
    m->V.row(n) = v.transpose();
  }
  return n;
}

void add_triangle(Pair& p, int a, int b, int c) {
  const int m = p.templ.num_triangles();
  for (TriMesh* mesh : {&p.templ, &p.frame}) {
    mesh->F.conservativeResize(m + 1, 3);
    mesh->F.row(m) << a, b, c;
  }
}

MassageResult run(const Pair& p, const MassageOptions& o = {}) {
  const Massager m(p.templ, o);
  const Reference reference(p.frame, o.samples, "frame", m.shared_topology());
  return m.run(p.frame.V, reference);
}

// The run succeeded with finite positions, and the grid part (vertices [0, grid)) got no farther
// from the template's shapes than the frame was.
void check_finite_and_ok(const MassageResult& r) {
  INFO(r.failure);
  REQUIRE(r.ok);
  CHECK(r.V.allFinite());
  for (const IterationStats& it : r.iterations) CHECK(std::isfinite(it.energy));
}

}  // namespace

TEST_CASE("an isolated vertex keeps its position and does not pull the surface",
          "[massage][errors]") {
  Pair clean = bumpy_grid();
  const int grid = clean.templ.num_vertices();
  const MassageResult without = run(clean);
  check_finite_and_ok(without);
  // A stray point in no triangle, near or far above the surface (as captured data has them).
  // Were it a sample of the reference, Lawson's reweighting would let it drag the surface to it.
  for (const double height : {0.05, 1.0, 50.0}) {
    INFO("isolated vertex at height " << height);
    Pair p = clean;
    const int lonely = add_vertex(p, Vec3(0.5, 0.5, height));
    CHECK(check_mesh(p.templ).isolated_vertices == 1);
    const MassageResult r = run(p);
    check_finite_and_ok(r);
    CHECK(r.V.row(lonely) == p.frame.V.row(lonely));
    CHECK((r.V.topRows(grid) - without.V).cwiseAbs().maxCoeff() < 1e-6);
  }
}

TEST_CASE("non-manifold edges and vertices are counted, and the optimizer runs on them",
          "[massage][errors]") {
  {  // a fin: a third triangle on an interior edge of the grid
    Pair p = bumpy_grid();
    const int top = add_vertex(p, Vec3(0.25, 0.3, 0.4));
    add_triangle(p, 8, 9, top);  // edge (8, 9) already has two triangles
    const MeshReport report = check_mesh(p.templ);
    CHECK(report.nonmanifold_edges >= 1);
    CHECK_FALSE(report.ok_for_optimization());
    check_finite_and_ok(run(p));
  }
  {  // a bow tie: a second fan of triangles at vertex 0, the grid's corner
    Pair p = bumpy_grid();
    const int a = add_vertex(p, Vec3(-0.2, -0.1, 0.0));
    const int b = add_vertex(p, Vec3(-0.1, -0.2, 0.0));
    add_triangle(p, 0, a, b);
    const MeshReport report = check_mesh(p.templ);
    CHECK(report.nonmanifold_vertices == 1);
    CHECK(report.nonmanifold_edges == 0);
    check_finite_and_ok(run(p));
  }
}

TEST_CASE("degenerate and duplicate triangles in the template or a frame keep results finite",
          "[massage][errors]") {
  {  // template: one triangle collapsed to a segment (vertex 8 moved onto its neighbour 9)
    Pair p = bumpy_grid();
    p.templ.V.row(8) = p.templ.V.row(9);
    const MeshReport report = check_mesh(p.templ);
    CHECK(report.degenerate_triangles >= 1);
    const Massager m(p.templ, {});
    CHECK(m.weights().fallback_vertices > 0);  // those corners use uniform weights
    check_finite_and_ok(run(p));
  }
  {  // a duplicate triangle (the same three vertices twice)
    Pair p = bumpy_grid();
    add_triangle(p, p.templ.F(3, 0), p.templ.F(3, 1), p.templ.F(3, 2));
    CHECK(check_mesh(p.templ).duplicate_triangles == 1);
    check_finite_and_ok(run(p));
  }
  {  // a frame with zero-area triangles: three vertices collapsed onto one point
    Pair p = bumpy_grid();
    for (int v : {15, 16, 22}) p.frame.V.row(v) = p.frame.V.row(23);
    CHECK(check_mesh(p.frame).degenerate_triangles >= 3);
    check_finite_and_ok(run(p));
  }
  {  // a frame collapsed entirely to one point: nothing to project onto but a point
    Pair p = bumpy_grid();
    for (int v = 0; v < p.frame.num_vertices(); ++v) p.frame.V.row(v) = Eigen::RowVector3d(1, 2, 3);
    const MassageResult r = run(p);
    if (r.ok) {
      CHECK(r.V.allFinite());
    } else {
      CHECK_FALSE(r.failure.empty());  // failed with a reason; the frame is written unchanged
    }
  }
}
