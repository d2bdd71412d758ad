#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "geometry/quality.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

namespace {

TriMesh triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  TriMesh m;
  m.V = Positions(3, 3);
  m.V.row(0) = a.transpose();
  m.V.row(1) = b.transpose();
  m.V.row(2) = c.transpose();
  m.F = Triangles(1, 3);
  m.F << 0, 1, 2;
  return m;
}

// 2r/R from the incircle (area / semi-perimeter) and the circumcentre solved in the plane.
double reference_ratio(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a, v = c - a;
  const double area = 0.5 * u.cross(v).norm();
  const double s = 0.5 * ((b - a).norm() + (c - b).norm() + (a - c).norm());
  const double r = area / s;
  Eigen::Matrix2d G;
  G << u.dot(u), u.dot(v), u.dot(v), v.dot(v);
  const Eigen::Vector2d x = G.fullPivLu().solve(0.5 * Eigen::Vector2d(u.dot(u), v.dot(v)));
  const double R = (x[0] * u + x[1] * v).norm();
  return 2.0 * r / R;
}

}  // namespace

TEST_CASE("radius ratio of known triangles", "[quality]") {
  const Eigen::VectorXd eq =
      radius_ratio(triangle(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, std::sqrt(3.0), 0)));
  REQUIRE(eq.size() == 1);
  CHECK(eq[0] == Approx(1.0).epsilon(1e-14));
  // Right isosceles: r = (2 − √2)/2, R = √2/2.
  const double right = radius_ratio(triangle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)))[0];
  CHECK(right == Approx(2.0 * (2.0 - std::sqrt(2.0)) / 2.0 / (std::sqrt(2.0) / 2.0)));
  // Degenerate: collinear corners and a repeated corner.
  CHECK(radius_ratio(triangle(Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)))[0] == 0.0);
  CHECK(radius_ratio(triangle(Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0)))[0] == 0.0);
}

TEST_CASE("radius ratio matches the inradius and circumradius", "[quality]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const double q = radius_ratio(triangle(a, b, c))[0];
    CHECK(q == Approx(reference_ratio(a, b, c)).epsilon(1e-9));
    CHECK(q >= 0.0);
    CHECK(q <= 1.0);
    // Invariant under similarity transforms.
    const double s = 0.01 + std::abs(u(rng));
    CHECK(radius_ratio(triangle(s * a + Vec3(1, 2, 3), s * b + Vec3(1, 2, 3),
                                s * c + Vec3(1, 2, 3)))[0] == Approx(q).epsilon(1e-10));
  }
}

TEST_CASE("radius ratio summary over meshes", "[quality]") {
  const TriMesh sphere = make_icosphere(3, 2.0);
  const Eigen::VectorXd q = radius_ratio(sphere);
  REQUIRE(q.size() == sphere.num_triangles());
  const QualitySummary s = summarize_quality(q);
  CHECK(s.min == q.minCoeff());
  CHECK(s.mean == Approx(q.sum() / q.size()));
  CHECK(s.min > 0.9);  // an icosphere is nearly equilateral everywhere
  CHECK(s.mean <= 1.0);

  // A grid of right isosceles triangles: every ratio is the right-isosceles value.
  const Eigen::VectorXd g = radius_ratio(make_grid(5, 5, 1.0, 1.0));
  for (int t = 0; t < g.size(); ++t) CHECK(g[t] == Approx(2.0 * std::sqrt(2.0) - 2.0));

  const QualitySummary empty = summarize_quality(Eigen::VectorXd());
  CHECK(empty.min == 0.0);
  CHECK(empty.mean == 0.0);

  TriMesh bad = make_grid(1, 1, 1.0, 1.0);
  bad.F(1, 2) = 9;
  CHECK_THROWS_AS(radius_ratio(bad), InputError);
}
