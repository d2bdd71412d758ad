#include <catch2/catch.hpp>

#include <random>

#include "massage/correspondence.hpp"
#include "massage/massage.hpp"
#include "mesh/primitives.hpp"
#include "support/brute_force_closest.hpp"

using namespace sm;
using test::brute_force_dist2;

namespace {

struct Surface {
  TriMesh mesh;
  Topology topo;
  TriangleBvh bvh;
  TrianglePlanes planes;
  explicit Surface(TriMesh m)
      : mesh(std::move(m)), topo(build_topology(mesh)), bvh(mesh), planes(mesh.V, mesh.F) {}
  SurfaceView view(bool with_planes) const {
    return {&mesh.V, &mesh.F, &topo, &bvh, with_planes ? &planes : nullptr};
  }
};

}  // namespace

TEST_CASE("exact correspondences are exact with or without hints", "[correspondence]") {
  const Surface s(make_torus(30, 14, 2.0, 0.6));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  Positions points(300, 3);
  for (int i = 0; i < points.rows(); ++i) points.row(i) << u(rng), u(rng), 0.4 * u(rng);
  std::uniform_int_distribution<int> tri(0, s.mesh.num_triangles() - 1);
  for (bool with_planes : {false, true}) {
    std::vector<SurfacePoint> none, hinted(points.rows());
    for (SurfacePoint& h : hinted) h.triangle = tri(rng);  // arbitrary hints: only bounds
    update_correspondences(s.view(with_planes), points, true, 16, none);
    const int queries = update_correspondences(s.view(with_planes), points, true, 16, hinted);
    CHECK(queries == points.rows());
    for (int i = 0; i < points.rows(); ++i) {
      const double exact = brute_force_dist2(s.mesh, points.row(i).transpose());
      CHECK(none[i].dist2 == Approx(exact).margin(1e-13));
      CHECK(hinted[i].dist2 == Approx(exact).margin(1e-13));
      CHECK(hinted[i].triangle >= 0);
    }
  }
}

TEST_CASE("a hint at distance zero needs no exact query", "[correspondence]") {
  const Surface s(make_icosphere(2, 1.0));
  std::vector<SurfacePoint> corr(s.mesh.num_vertices());
  for (int v = 0; v < s.mesh.num_vertices(); ++v)
    corr[v].triangle = s.topo.vertex_triangles.data[s.topo.vertex_triangles.begin(v)];
  int prepared = 0;
  const int queries =
      update_correspondences(s.view(true), s.mesh.V, true, 16, corr, [&] { ++prepared; });
  CHECK(queries == 0);
  CHECK(prepared == 0);
  for (int v = 0; v < s.mesh.num_vertices(); ++v) {
    CHECK(corr[v].dist2 == 0.0);
    CHECK((corr[v].point - s.mesh.vertex(v)).norm() == 0.0);
  }
}

TEST_CASE("walks that do not settle fall back to the exact query, prepared once",
          "[correspondence]") {
  const Surface s(make_grid(40, 40, 1.0, 1.0));
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  Positions points(500, 3);
  for (int i = 0; i < points.rows(); ++i) points.row(i) << u01(rng), u01(rng), 0.1 * u01(rng);
  for (bool with_planes : {false, true}) {
    std::vector<SurfacePoint> corr(points.rows());
    for (SurfacePoint& c : corr) c.triangle = 0;  // far from most queries
    int prepared = 0;
    const int queries =
        update_correspondences(s.view(with_planes), points, false, 3, corr, [&] { ++prepared; });
    CHECK(queries > 0);
    CHECK(queries < points.rows());
    CHECK(prepared == 1);
    for (int i = 0; i < points.rows(); ++i)  // a grid has a single local minimum
      CHECK(corr[i].dist2 ==
            Approx(brute_force_dist2(s.mesh, points.row(i).transpose())).margin(1e-13));
  }
}

TEST_CASE("a reference refitted from the template's tree answers like a freshly built one",
          "[correspondence]") {
  const TriMesh templ = make_torus(30, 14, 2.0, 0.6);
  TriMesh frame = templ;  // the same connectivity, moved (bent and squeezed)
  for (int v = 0; v < frame.num_vertices(); ++v) {
    const Vec3 p = templ.vertex(v);
    frame.V.row(v) << p.x() + 0.3 * std::sin(p.y()), 0.7 * p.y(), p.z() + 0.2 * p.x() * p.x();
  }
  const Massager m(templ, MassageOptions{});
  const Reference fresh(frame, SampleKind::Vertices, "fresh");
  const Reference refitted(frame, SampleKind::Vertices, "refitted", m.shared_topology(),
                           &m.template_bvh());
  const TriMesh other = make_grid(3, 3, 1.0, 1.0);  // different triangles: the tree is ignored
  const Reference ignored(other, SampleKind::Vertices, "other", nullptr, &m.template_bvh());
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < 500; ++i) {
    const Vec3 p(u(rng), u(rng), 0.5 * u(rng));
    CHECK(refitted.bvh().closest(p).dist2 == fresh.bvh().closest(p).dist2);
    CHECK(ignored.bvh().closest(p).dist2 == Approx(brute_force_dist2(other, p)).margin(1e-13));
  }
}
