#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "geometry/closest_point.hpp"

using namespace sm;

namespace {

// Smallest squared distance from p to a dense barycentric lattice (n divisions) on the triangle.
double lattice_min_dist2(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, int n) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double u = double(i) / n, v = double(j) / n;
      best = std::min(best, (p - (u * a + v * b + (1.0 - u - v) * c)).squaredNorm());
    }
  return best;
}

Vec3 random_vec(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vec3(u(rng), u(rng), u(rng));
}

// The answer is a point of the triangle, described consistently by bary, region and dist2.
void check_consistent(const TrianglePoint& r, const Vec3& p, const Vec3& a, const Vec3& b,
                      const Vec3& c) {
  const double scale = std::max({a.norm(), b.norm(), c.norm(), p.norm(), 1.0});
  REQUIRE(r.point.allFinite());
  REQUIRE(r.bary.allFinite());
  CHECK(r.bary.sum() == Approx(1.0).margin(1e-12));
  CHECK(r.bary.minCoeff() >= 0.0);
  CHECK((r.bary[0] * a + r.bary[1] * b + r.bary[2] * c - r.point).norm() <= 1e-12 * scale);
  CHECK(r.dist2 == Approx((p - r.point).squaredNorm()).margin(1e-12 * scale * scale));
  switch (r.region) {
    case TriangleRegion::Vertex0:
      CHECK(r.bary[0] == 1.0);
      break;
    case TriangleRegion::Vertex1:
      CHECK(r.bary[1] == 1.0);
      break;
    case TriangleRegion::Vertex2:
      CHECK(r.bary[2] == 1.0);
      break;
    case TriangleRegion::Edge01:
      CHECK(r.bary[2] == 0.0);
      break;
    case TriangleRegion::Edge12:
      CHECK(r.bary[0] == 0.0);
      break;
    case TriangleRegion::Edge20:
      CHECK(r.bary[1] == 0.0);
      break;
    case TriangleRegion::Face:
      CHECK(r.bary.minCoeff() >= 0.0);
      break;
  }
}

}  // namespace

TEST_CASE("closest point on a triangle beats dense sampling", "[closest_point]") {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3 a = random_vec(rng, 1.0), b = random_vec(rng, 1.0), c = random_vec(rng, 1.0);
    const Vec3 p = random_vec(rng, trial % 3 == 0 ? 5.0 : 1.5);
    const TrianglePoint r = closest_point_on_triangle(p, a, b, c);
    check_consistent(r, p, a, b, c);
    const int n = 120;
    const double lattice = lattice_min_dist2(p, a, b, c, n);
    // Never farther than any point of the triangle, and every triangle point lies within
    // diameter / n of a lattice point.
    const double diameter = std::max({(a - b).norm(), (b - c).norm(), (c - a).norm()});
    CHECK(r.dist2 <= lattice + 1e-12);
    CHECK(std::sqrt(lattice) - std::sqrt(r.dist2) <= diameter / n + 1e-12);
  }
}

TEST_CASE("closest point regions follow the Voronoi regions", "[closest_point]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 a = random_vec(rng, 1.0), b = random_vec(rng, 1.0), c = random_vec(rng, 1.0);
    const Vec3 p = random_vec(rng, 2.0);
    const TrianglePoint r = closest_point_on_triangle(p, a, b, c);
    const Vec3 d = p - r.point;
    const Vec3 corner[3] = {a, b, c};
    const double tol = 1e-10;
    switch (r.region) {
      case TriangleRegion::Face: {
        // The offset is normal to the plane: orthogonal to both edges.
        CHECK(std::abs(d.dot((b - a).normalized())) <= tol);
        CHECK(std::abs(d.dot((c - a).normalized())) <= tol);
        CHECK(r.bary.minCoeff() > 0.0);
        break;
      }
      case TriangleRegion::Edge01:
      case TriangleRegion::Edge12:
      case TriangleRegion::Edge20: {
        const int k = r.region == TriangleRegion::Edge01   ? 0
                      : r.region == TriangleRegion::Edge12 ? 1
                                                           : 2;
        const Vec3 e = corner[(k + 1) % 3] - corner[k];
        CHECK(std::abs(d.dot(e.normalized())) <= tol);
        // Outside the edge: on the far side from the opposite corner, within the plane.
        const Vec3 n = (b - a).cross(c - a);
        const Vec3 inward = n.cross(e);
        CHECK(d.dot(inward) <= tol * inward.norm());
        break;
      }
      default: {
        const int k = r.region == TriangleRegion::Vertex0   ? 0
                      : r.region == TriangleRegion::Vertex1 ? 1
                                                            : 2;
        CHECK((r.point - corner[k]).norm() == 0.0);
        CHECK(d.dot(corner[(k + 1) % 3] - corner[k]) <= tol);
        CHECK(d.dot(corner[(k + 2) % 3] - corner[k]) <= tol);
      }
    }
  }
}

TEST_CASE("closest point on a known triangle", "[closest_point]") {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  auto r = closest_point_on_triangle(Vec3(0.5, 0.5, 3.0), a, b, c);
  CHECK(r.region == TriangleRegion::Face);
  CHECK(r.dist2 == Approx(9.0));
  CHECK(r.bary.isApprox(Vec3(0.5, 0.25, 0.25)));

  r = closest_point_on_triangle(Vec3(-1.0, -2.0, 1.0), a, b, c);
  CHECK(r.region == TriangleRegion::Vertex0);
  CHECK(r.dist2 == Approx(6.0));

  r = closest_point_on_triangle(Vec3(1.0, -1.0, 0.0), a, b, c);
  CHECK(r.region == TriangleRegion::Edge01);
  CHECK(r.point.isApprox(Vec3(1.0, 0.0, 0.0)));
  CHECK(r.dist2 == Approx(1.0));

  r = closest_point_on_triangle(Vec3(2.0, 2.0, 0.0), a, b, c);
  CHECK(r.region == TriangleRegion::Edge12);
  CHECK(r.point.isApprox(Vec3(1.0, 1.0, 0.0)));
  CHECK(r.bary.isApprox(Vec3(0.0, 0.5, 0.5)));

  r = closest_point_on_triangle(Vec3(-0.5, 1.0, -1.0), a, b, c);
  CHECK(r.region == TriangleRegion::Edge20);
  CHECK(r.dist2 == Approx(1.25));

  r = closest_point_on_triangle(Vec3(5.0, -1.0, 0.0), a, b, c);
  CHECK(r.region == TriangleRegion::Vertex1);
  r = closest_point_on_triangle(Vec3(-1.0, 5.0, 0.0), a, b, c);
  CHECK(r.region == TriangleRegion::Vertex2);
}

TEST_CASE("degenerate triangles give the closest point on their edges", "[closest_point]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3 a = random_vec(rng, 1.0), dir = random_vec(rng, 1.0);
    Vec3 b, c;
    switch (trial % 4) {
      case 0:
        b = a + unit(rng) * dir;
        c = a + unit(rng) * dir;
        break;  // collinear
      case 1:
        b = a;
        c = a + dir;
        break;  // two coincident
      case 2:
        b = a;
        c = a;
        break;  // all coincident
      default:
        b = a + dir;
        c = a + 2.0 * dir;
        break;  // collinear, ordered
    }
    const Vec3 p = random_vec(rng, 2.0);
    const TrianglePoint r = closest_point_on_triangle(p, a, b, c);
    check_consistent(r, p, a, b, c);
    CHECK(r.region != TriangleRegion::Face);
    // Brute force over the segment spanned by the corners.
    double best = std::numeric_limits<double>::infinity();
    const Vec3 corner[3] = {a, b, c};
    for (int k = 0; k < 3; ++k)
      for (int s = 0; s <= 2000; ++s) {
        const Vec3 q = corner[k] + (s / 2000.0) * (corner[(k + 1) % 3] - corner[k]);
        best = std::min(best, (p - q).squaredNorm());
      }
    CHECK(r.dist2 <= best + 1e-12);
    CHECK(std::sqrt(best) - std::sqrt(r.dist2) <= 2.0 * dir.norm() / 2000.0 + 1e-12);
  }
}

TEST_CASE("thin triangles stay accurate", "[closest_point]") {
  // Heights from 1e-3 down to 1e-12 of the length: the distance to a point above the middle
  // must stay the exact height, whichever branch handles the triangle.
  for (double h = 1e-3; h >= 1e-12; h /= 10.0) {
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0.5, h, 0);
    const Vec3 p(0.4, 0.3 * h, 0.25);
    const TrianglePoint r = closest_point_on_triangle(p, a, b, c);
    CHECK(r.point.allFinite());
    CHECK(std::sqrt(r.dist2) == Approx(0.25).epsilon(1e-9));
    check_consistent(r, p, a, b, c);
  }
}
