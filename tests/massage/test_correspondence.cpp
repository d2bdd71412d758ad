#include <catch2/catch.hpp>

#include <random>

#include "geometry/surface_walk.hpp"
#include "massage/correspondence.hpp"
#include "massage/massage.hpp"
#include "core/errors.hpp"
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

TEST_CASE("local correspondences are the walks' answers, with or without bends",
          "[correspondence]") {
  // update_correspondences fetches frames ahead of the walks; the answers must be exactly those
  // of walk_closest from the same starts, and the same whatever the frames know.
  const Surface s(make_torus(36, 18, 2.0, 0.6));
  const TrianglePlanes bends(s.mesh.V, s.mesh.F, &s.topo);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  Positions points = s.mesh.V;
  for (int i = 0; i < points.rows(); ++i) points.row(i) += Vec3(u(rng), u(rng), u(rng)).transpose();
  std::vector<SurfacePoint> starts(points.rows());
  std::uniform_int_distribution<int> pick(0, 5);
  for (int v = 0; v < points.rows(); ++v) {
    const int b = s.topo.vertex_triangles.begin(v);
    starts[v].triangle =
        s.topo.vertex_triangles.data[b + pick(rng) % s.topo.vertex_triangles.size(v)];
  }
  std::vector<std::vector<SurfacePoint>> answers;
  for (const TrianglePlanes* planes : {&s.planes, &bends}) {
    SurfaceView view = s.view(true);
    view.planes = planes;
    std::vector<SurfacePoint> corr = starts;
    CHECK(update_correspondences(view, points, false, 16, corr) == 0);
    for (int i = 0; i < points.rows(); ++i) {
      SurfacePoint walked;
      REQUIRE(walk_closest(s.mesh.V, s.mesh.F, s.topo, points.row(i).transpose(),
                           starts[i].triangle, 16, walked, planes));
      CHECK(corr[i].triangle == walked.triangle);
      CHECK(corr[i].dist2 == walked.dist2);
      CHECK((corr[i].point - walked.point).norm() == 0.0);
    }
    answers.push_back(corr);
  }
  for (int i = 0; i < points.rows(); ++i) {
    CHECK(answers[0][i].triangle == answers[1][i].triangle);
    CHECK((answers[0][i].bary - answers[1][i].bary).norm() == 0.0);
  }
}

TEST_CASE("a start triangle out of range is an error, also for the fetching ahead",
          "[correspondence]") {
  const Surface s(make_torus(20, 10, 2.0, 0.6));
  const int m = s.mesh.num_triangles();
  std::vector<SurfacePoint> corr(60);
  for (int i = 0; i < 60; ++i) corr[i].triangle = i % m;
  corr[30].triangle = m + 1000;  // read ahead by the queries before it
  Positions points(60, 3);
  for (int i = 0; i < 60; ++i) points.row(i) = s.mesh.V.row(i);
  for (bool with_planes : {false, true}) {
    std::vector<SurfacePoint> c = corr;
    CHECK_THROWS_AS(update_correspondences(s.view(with_planes), points, false, 16, c), InputError);
  }
}
