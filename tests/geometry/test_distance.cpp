#include <catch2/catch.hpp>

#include <cmath>
#include <set>

#include <tbb/global_control.h>

#include "geometry/distance.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

namespace {

double longest_edge(const TriMesh& mesh) {
  double longest = 0.0;
  for (int t = 0; t < mesh.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest,
                         (mesh.vertex(mesh.F(t, k)) - mesh.vertex(mesh.F(t, (k + 1) % 3))).norm());
  return longest;
}

TriMesh scaled(TriMesh mesh, double s) {
  mesh.V *= s;
  return mesh;
}

TriMesh shifted(TriMesh mesh, const Vec3& d) {
  mesh.V.rowwise() += d.transpose();
  return mesh;
}

}  // namespace

TEST_CASE("distance of a mesh to itself is zero", "[distance]") {
  for (const TriMesh& mesh : {make_icosphere(3, 1.0), make_torus(30, 12, 2.0, 0.5),
                              make_box(4, 1.0, 2.0, 3.0), make_grid(7, 5, 1.0, 2.0)}) {
    const DistanceStats d = one_sided_distance(mesh, TriangleBvh(mesh));
    CHECK(d.samples > 5 * mesh.num_triangles());
    CHECK(d.max <= 1e-12);
    CHECK(d.mean <= 1e-12);
    CHECK(d.rms <= 1e-12);
  }
}

TEST_CASE("distance between concentric spheres is the radius difference", "[distance]") {
  const TriMesh a = make_icosphere(4, 1.0);
  const TriMesh b = make_icosphere(4, 1.1);
  // The faceted spheres deviate from the round ones by at most their sagitta, below e²/R for
  // edges of length e on radius R: the distances lie in [0.1 − sag(B), 0.1 + sag(A)].
  const double sag_a = std::pow(longest_edge(a), 2) / 1.0;
  const double sag_b = std::pow(longest_edge(b), 2) / 1.1;
  const DistanceStats ab = one_sided_distance(a, TriangleBvh(b));
  const DistanceStats ba = one_sided_distance(b, TriangleBvh(a));
  for (const DistanceStats& d : {ab, ba}) {
    CHECK(d.max <= 0.1 + sag_a + sag_b);
    CHECK(d.mean >= 0.1 - sag_a - sag_b);
    CHECK(d.mean <= d.rms);
    CHECK(d.rms <= d.max);
  }
  // Vertices of A lie on the round sphere of radius 1, inside B's polytope: at least 0.1 − sag_b.
  CHECK(ab.max >= 0.1 - sag_b);
  CHECK(symmetric_hausdorff(ab, ba) == std::max(ab.max, ba.max));
  // Relative values share the diagonal of both meshes' joint bounding box (B's here).
  Positions both(a.V.rows() + b.V.rows(), 3);
  both << a.V, b.V;
  const double diag = bounding_box_diagonal(both);
  CHECK(ab.max_rel == Approx(ab.max / diag));
  CHECK(ab.mean_rel == Approx(ab.mean / diag));
  CHECK(ab.rms_rel == Approx(ab.rms / diag));
  CHECK(ba.max_rel == Approx(ba.max / diag));
}

TEST_CASE("distance between parallel grids is their offset", "[distance]") {
  const TriMesh a = make_grid(8, 6, 2.0, 1.5);
  const TriMesh b = shifted(make_grid(3, 5, 2.0, 1.5), Vec3(0, 0, 0.3));
  const DistanceStats d = one_sided_distance(a, TriangleBvh(b));
  CHECK(d.max == Approx(0.3).epsilon(1e-12));
  CHECK(d.mean == Approx(0.3).epsilon(1e-12));
  CHECK(d.rms == Approx(0.3).epsilon(1e-12));

  // Half of B's width removed: points of A beyond x = 1 see B's edge at x = 1.
  const TriMesh half = shifted(make_grid(4, 4, 1.0, 1.5), Vec3(0, 0, 0.3));
  const DistanceStats h = one_sided_distance(a, TriangleBvh(half));
  CHECK(h.max == Approx(std::hypot(1.0, 0.3)).epsilon(1e-12));
  CHECK(h.mean > 0.3);
  CHECK(one_sided_distance(half, TriangleBvh(a)).max == Approx(0.3).epsilon(1e-12));
}

TEST_CASE("distance sampling follows the documented pattern", "[distance]") {
  const TriMesh a = make_grid(3, 2, 3.0, 1.0);  // unit squares split in two
  const TriangleBvh b(a);
  DistanceOptions o;
  o.spacing = 0.3;
  const double h = o.spacing * mean_edge_length(a);
  long expected = a.num_vertices();
  std::set<std::pair<int, int>> edges;
  long faces = 0;
  for (int t = 0; t < a.num_triangles(); ++t) {
    double longest = 0.0;
    for (int k = 0; k < 3; ++k) {
      const int i = a.F(t, k), j = a.F(t, (k + 1) % 3);
      const double len = (a.vertex(i) - a.vertex(j)).norm();
      longest = std::max(longest, len);
      if (edges.insert({std::min(i, j), std::max(i, j)}).second)
        expected += static_cast<long>(std::ceil(len / h)) - 1;
    }
    const long n = static_cast<long>(std::ceil(longest / h));
    faces += n < 3 ? 1 : (n - 1) * (n - 2) / 2;
  }
  CHECK(one_sided_distance(a, b, o).samples == expected + faces);
  o.sample_faces = false;
  CHECK(one_sided_distance(a, b, o).samples == expected);
  o.sample_edges = false;
  CHECK(one_sided_distance(a, b, o).samples == a.num_vertices());
}

TEST_CASE("distance does not depend on the number of threads", "[distance]") {
  const TriMesh a = make_torus(60, 24, 2.0, 0.5);
  const TriMesh b = scaled(make_icosphere(4, 1.0), 2.2);
  DistanceStats one, many;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = one_sided_distance(a, TriangleBvh(b));
  }
  many = one_sided_distance(a, TriangleBvh(b));
  CHECK(one.samples == many.samples);
  CHECK(one.max == many.max);
  CHECK(one.mean == many.mean);
  CHECK(one.rms == many.rms);
  CHECK(one.max > 0.0);
}

TEST_CASE("distance with corresponding triangles is the same distance", "[distance]") {
  // B is A moved vertex by vertex (same connectivity, as a frame and its corrected output), and
  // a mesh with fewer triangles than A, where the hint must be ignored past B's last triangle.
  const TriMesh a = make_torus(40, 16, 2.0, 0.5);
  TriMesh moved = a;
  for (int i = 0; i < moved.num_vertices(); ++i)
    moved.V.row(i) += 0.02 * Eigen::RowVector3d(std::sin(3.0 * i), std::cos(5.0 * i), std::sin(i));
  const TriMesh fewer = scaled(make_icosphere(2, 1.0), 2.2);
  REQUIRE(fewer.num_triangles() < a.num_triangles());
  const TriMesh* targets[] = {&moved, &fewer};
  for (const TriMesh* b : targets) {
    DistanceOptions plain, hinted;
    hinted.corresponding_triangles = true;
    for (double spacing : {0.25, 0.6}) {
      plain.spacing = hinted.spacing = spacing;
      const TriangleBvh bvh(*b);
      const DistanceStats x = one_sided_distance(a, bvh, plain);
      const DistanceStats y = one_sided_distance(a, bvh, hinted);
      CHECK(y.samples == x.samples);
      CHECK(y.max == Approx(x.max).epsilon(1e-12));
      CHECK(y.mean == Approx(x.mean).epsilon(1e-12));
      CHECK(y.rms == Approx(x.rms).epsilon(1e-12));
      CHECK(x.max > 0.0);
    }
  }
}

TEST_CASE("distance input errors", "[distance]") {
  const TriMesh a = make_grid(2, 2, 1.0, 1.0);
  DistanceOptions o;
  o.spacing = 0.0;
  CHECK_THROWS_AS(one_sided_distance(a, TriangleBvh(a), o), OptionError);
  CHECK_THROWS_AS(one_sided_distance(a, TriangleBvh()), InputError);
  TriMesh bad = a;
  bad.V(0, 0) = std::nan("");
  CHECK_THROWS_AS(one_sided_distance(bad, TriangleBvh(a)), InputError);
  const DistanceStats none = one_sided_distance(TriMesh{}, TriangleBvh(a));
  CHECK(none.samples == 0);
  CHECK(none.max == 0.0);
}
