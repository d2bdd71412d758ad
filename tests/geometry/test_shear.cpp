#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "geometry/shear.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

namespace {

Positions transformed(const Positions& V, const Eigen::Matrix3d& A, const Vec3& shift) {
  Positions W = V * A.transpose();
  W.rowwise() += shift.transpose();
  return W;
}

double expected(double s1, double s2) {
  return std::max(s1 + 1.0 / s1, s2 + 1.0 / s2) - 2.0;
}

}  // namespace

TEST_CASE("shear distortion vanishes for rigid motions", "[shear]") {
  const std::vector<TriMesh> meshes = {make_icosphere(3, 1.0), make_torus(30, 12, 2.0, 0.5),
                                       make_box(4, 1.0, 2.0, 3.0)};
  for (const TriMesh& mesh : meshes) {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(1.1, Vec3(0.3, -1.0, 2.0).normalized()).toRotationMatrix();
    const Eigen::VectorXd D =
        shear_distortion(mesh.V, transformed(mesh.V, R, Vec3(3, -1, 2)), mesh.F);
    REQUIRE(D.size() == mesh.num_triangles());
    CHECK(D.maxCoeff() <= 1e-13);
    CHECK(D.minCoeff() >= 0.0);
    // A reflection is congruent too.
    const Eigen::Matrix3d M = Eigen::Vector3d(-1, 1, 1).asDiagonal();
    CHECK(shear_distortion(mesh.V, transformed(mesh.V, M, Vec3::Zero()), mesh.F).maxCoeff() <=
          1e-13);
  }
}

TEST_CASE("shear distortion of a uniform scale is s + 1/s - 2", "[shear]") {
  const TriMesh mesh = make_icosphere(2, 1.5);
  for (double s : {0.25, 0.5, 0.9, 1.0, 1.1, 2.0, 4.0}) {
    const Eigen::Matrix3d A = s * Eigen::Matrix3d::Identity();
    const Eigen::VectorXd D =
        shear_distortion(mesh.V, transformed(mesh.V, A, Vec3(1, 2, 3)), mesh.F);
    for (int t = 0; t < D.size(); ++t) CHECK(D[t] == Approx(s + 1.0 / s - 2.0).margin(1e-12));
  }
}

TEST_CASE("shear distortion of planar linear maps matches an SVD", "[shear]") {
  // A plane z = 0 mapped by a linear map A: every triangle sees the 3×2 map A(:, 0:2), whose
  // singular values an iterative SVD gives independently.
  const TriMesh grid = make_grid(6, 5, 2.0, 1.0);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Matrix3d A;
    for (int i = 0; i < 9; ++i) A(i / 3, i % 3) = u(rng);
    const Eigen::Matrix<double, 3, 2> J = A.leftCols<2>();
    const Eigen::Vector2d sv = Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>>(J).singularValues();
    if (sv[1] < 0.05) continue;
    const Eigen::VectorXd D =
        shear_distortion(grid.V, transformed(grid.V, A, Vec3(0, 0, 1)), grid.F);
    for (int t = 0; t < D.size(); ++t) CHECK(D[t] == Approx(expected(sv[0], sv[1])).epsilon(1e-10));
  }
  // The simple shear x' = x + k·y has σ1 = k/2 + sqrt(1 + k²/4), σ2 = 1/σ1: D = sqrt(4 + k²) − 2.
  for (double k : {0.1, 0.5, 1.0, 3.0}) {
    Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
    S(0, 1) = k;
    const Eigen::VectorXd D =
        shear_distortion(grid.V, transformed(grid.V, S, Vec3::Zero()), grid.F);
    for (int t = 0; t < D.size(); ++t)
      CHECK(D[t] == Approx(std::sqrt(4.0 + k * k) - 2.0).epsilon(1e-12));
  }
  // Anisotropic stretch (2, 0.8): the larger excess wins, 2 + 1/2 − 2.
  Eigen::Matrix3d S = Eigen::Vector3d(2.0, 0.8, 1.0).asDiagonal();
  const Eigen::VectorXd D = shear_distortion(grid.V, transformed(grid.V, S, Vec3::Zero()), grid.F);
  for (int t = 0; t < D.size(); ++t) CHECK(D[t] == Approx(0.5).epsilon(1e-12));
}

TEST_CASE("shear distortion is infinite for degenerate triangles", "[shear]") {
  const TriMesh grid = make_grid(3, 3, 1.0, 1.0);
  Positions V = grid.V;
  V.row(5) = V.row(6);  // collapse an interior vertex onto a neighbour
  const Eigen::VectorXd D = shear_distortion(grid.V, V, grid.F);
  int infinite = 0;
  for (int t = 0; t < D.size(); ++t) {
    const bool touches = (grid.F.row(t).array() == 5).any();
    const bool both = touches && (grid.F.row(t).array() == 6).any();
    if (both) {
      CHECK(std::isinf(D[t]));
      ++infinite;
    } else {
      CHECK(std::isfinite(D[t]));
    }
  }
  CHECK(infinite > 0);
  // Degenerate template: the same, the other way round.
  const Eigen::VectorXd E = shear_distortion(V, grid.V, grid.F);
  CHECK((E.array().isInf()).count() == infinite);

  const DistortionSummary s = summarize_distortion(D);
  CHECK(s.infinite == infinite);
  CHECK(std::isinf(s.max));
  CHECK(std::isfinite(s.mean));

  CHECK_THROWS_AS(shear_distortion(grid.V, V.topRows(4), grid.F), InputError);
  Triangles bad = grid.F;
  bad(0, 0) = 100;
  CHECK_THROWS_AS(shear_distortion(grid.V, V, bad), InputError);
}

TEST_CASE("distortion summary and histogram", "[shear]") {
  Eigen::VectorXd d(100);
  for (int i = 0; i < 100; ++i) d[i] = double(100 - i);  // 100, 99, ..., 1
  DistortionSummary s = summarize_distortion(d);
  CHECK(s.max == 100.0);
  CHECK(s.mean == Approx(50.5));
  CHECK(s.p95 == 95.0);
  CHECK(s.infinite == 0);

  Eigen::VectorXd with_inf(5);
  with_inf << 1.0, std::numeric_limits<double>::infinity(), 3.0, 2.0, 4.0;
  s = summarize_distortion(with_inf);
  CHECK(s.infinite == 1);
  CHECK(std::isinf(s.max));
  CHECK(s.mean == Approx(2.5));
  CHECK(s.p95 == 4.0);

  s = summarize_distortion(Eigen::VectorXd());
  CHECK(s.max == 0.0);
  CHECK(s.mean == 0.0);

  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<int> h = histogram(with_inf, {0.0, 2.0, 4.0, inf});
  CHECK(h == std::vector<int>{1, 2, 2});
  CHECK(histogram(d, {0.0, 50.0, 100.0}) == std::vector<int>{49, 51});
  CHECK(histogram(d, {10.5, 20.5}) == std::vector<int>{10});
  CHECK_THROWS_AS(histogram(d, {1.0}), InputError);
  CHECK_THROWS_AS(histogram(d, {1.0, 1.0}), InputError);
}
