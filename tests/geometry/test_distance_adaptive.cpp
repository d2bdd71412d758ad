#include <catch2/catch.hpp>

#include <cmath>

#include <tbb/global_control.h>

#include "geometry/distance.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

namespace {

DistanceOptions uniform(double spacing) {
  DistanceOptions o;
  o.spacing = spacing;
  return o;
}

DistanceOptions adaptive(double spacing, double refine_above = 0.5) {
  DistanceOptions o = uniform(spacing);
  o.adaptive = true;
  o.refine_above = refine_above;
  return o;
}

// Two triangles spanning [−10, 10]² in the plane z = c + s·x.
TriMesh tilted_plane(double c, double s) {
  TriMesh m;
  m.V.resize(4, 3);
  m.V << -10, -10, c - 10 * s, 10, -10, c + 10 * s, 10, 10, c + 10 * s, -10, 10, c - 10 * s;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 2, 3;
  return m;
}

TriMesh wobbled(TriMesh mesh, double amplitude) {
  for (int i = 0; i < mesh.num_vertices(); ++i)
    mesh.V.row(i) +=
        amplitude * Eigen::RowVector3d(std::sin(3.0 * i), std::cos(5.0 * i), std::sin(7.0 * i));
  return mesh;
}

}  // namespace

TEST_CASE("adaptive distance: mean and RMS are area integrals, exact where d² is quadratic",
          "[distance]") {
  // A: a grid of unequal cells under a tilted plane, so d = (c + s·x) / sqrt(1 + s²) is linear
  // and the degree-2 rule exact: mean(d²) over [0, W] is a² + a·b·W + b²·W²/3.
  const double W = 3.0, c = 0.2, s = 0.1, k = 1.0 / std::sqrt(1.0 + s * s);
  TriMesh a = make_grid(6, 4, W, 2.0);
  for (int i = 0; i < a.num_vertices(); ++i) a.V(i, 0) = W * std::pow(a.V(i, 0) / W, 1.7);
  const TriangleBvh b(tilted_plane(c, s));
  const DistanceStats d = one_sided_distance(a, b, adaptive(0.25));
  CHECK(d.mean == Approx(k * (c + s * W / 2)).epsilon(1e-12));
  CHECK(d.rms == Approx(k * std::sqrt(c * c + c * s * W + s * s * W * W / 3)).epsilon(1e-12));
  CHECK(d.max == Approx(k * (c + s * W)).epsilon(1e-12));
  // The uniform samples crowd where the cells are small: their RMS is not the area's.
  const DistanceStats u = one_sided_distance(a, b, uniform(0.25));
  CHECK(std::abs(u.rms / d.rms - 1.0) > 1e-3);
}

TEST_CASE("adaptive distance: the maximum is the dense sampling's", "[distance]") {
  // A coarse sphere inside a fine one: the largest distances are inside A's triangles, around
  // their centroids; a wobbled torus against its original (captured-frame-like noise); a plane
  // against a bump on it (the only distances, in a few triangles).
  const TriMesh coarse = make_icosphere(1, 1.0), fine = make_icosphere(5, 1.05);
  const TriMesh torus = make_torus(40, 16, 2.0, 0.5), noisy = wobbled(torus, 0.01);
  const TriMesh plane = make_grid(30, 30, 3.0, 3.0);
  TriMesh bump = plane;
  for (int i = 0; i < bump.num_vertices(); ++i)
    bump.V(i, 2) =
        0.05 *
        std::exp(-(std::pow(bump.V(i, 0) - 1.33, 2) + std::pow(bump.V(i, 1) - 1.71, 2)) / 0.02);
  const std::pair<const TriMesh*, const TriMesh*> pairs[] = {{&coarse, &fine}, {&fine, &coarse},
                                                             {&torus, &noisy}, {&noisy, &torus},
                                                             {&plane, &bump},  {&bump, &plane}};
  for (const auto& [a, b] : pairs) {
    const TriangleBvh bvh(*b);
    for (double spacing : {0.125, 0.25}) {
      const DistanceStats dense = one_sided_distance(*a, bvh, uniform(spacing));
      const DistanceStats x = one_sided_distance(*a, bvh, adaptive(spacing));
      // The refined triangles' samples are the dense ones (shared edges up to rounding), and
      // the triangle with the dense maximum is among them: never below it (the centroids may
      // lift it a little).
      CHECK(x.max >= dense.max * (1.0 - 1e-12));
      CHECK(x.max <= dense.max * 1.05);
      CHECK(x.refined > 0);
      CHECK(x.refined <= a->num_triangles());
      // Every triangle refined: all the dense samples are taken.
      const DistanceStats all = one_sided_distance(*a, bvh, adaptive(spacing, 0.0));
      CHECK(all.max >= dense.max * (1.0 - 1e-12));
      CHECK(all.max == Approx(x.max).epsilon(1e-12));
      CHECK(x.mean <= x.rms);
      if (a == &plane || a == &bump) {
        // Local differences: few triangles refined, far fewer samples.
        CHECK(x.refined < a->num_triangles() / 10);
        CHECK(x.samples < dense.samples / 2);
      } else {
        // Even differences: the RMS (the area integral) is close to the dense samples' RMS.
        CHECK(x.rms == Approx(dense.rms).epsilon(0.05));
        CHECK(x.mean == Approx(dense.mean).epsilon(0.05));
      }
    }
  }
}

TEST_CASE("adaptive distance does not depend on the number of threads", "[distance]") {
  const TriMesh a = make_torus(60, 24, 2.0, 0.5);
  const TriMesh b = wobbled(a, 0.02);
  const TriangleBvh bvh(b);
  for (bool corresponding : {false, true}) {
    DistanceOptions o = adaptive(0.125);
    o.corresponding_triangles = corresponding;
    DistanceStats one, many;
    {
      tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
      one = one_sided_distance(a, bvh, o);
    }
    many = one_sided_distance(a, bvh, o);
    CHECK(one.samples == many.samples);
    CHECK(one.refined == many.refined);
    CHECK(one.max == many.max);
    CHECK(one.mean == many.mean);
    CHECK(one.rms == many.rms);
    CHECK(one.max > 0.0);
  }
}

TEST_CASE("adaptive distance: identical meshes, degenerate meshes, bad options", "[distance]") {
  const TriMesh a = make_box(3, 1.0, 2.0, 3.0);
  const DistanceStats same = one_sided_distance(a, TriangleBvh(a), adaptive(0.25));
  CHECK(same.max <= 1e-12);
  CHECK(same.rms <= 1e-12);
  // Every triangle degenerate (no area): the triangles count alike.
  TriMesh flat = make_grid(3, 3, 1.0, 1.0);
  flat.V.col(1).setZero();
  const DistanceStats d =
      one_sided_distance(flat, TriangleBvh(tilted_plane(0.5, 0.0)), adaptive(0.25));
  CHECK(std::isfinite(d.rms));
  CHECK(d.rms == Approx(0.5).epsilon(1e-12));
  DistanceOptions o = adaptive(0.25, 1.5);
  CHECK_THROWS_AS(one_sided_distance(a, TriangleBvh(a), o), OptionError);
  o.refine_above = std::nan("");
  CHECK_THROWS_AS(one_sided_distance(a, TriangleBvh(a), o), OptionError);
}
