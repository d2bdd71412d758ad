#include <catch2/catch.hpp>

#include <random>

#include "massage/linear_solver.hpp"
#include "massage/system.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

namespace {

// K = μA + (1−μ)D with a random positive diagonal D: the shape of the massage system.
SparseMatrixR massage_like(const TriMesh& m, double mu, double spread, unsigned seed) {
  SparseMatrixR K = shape_matrix(compute_weights(m, WeightKind::MeanValue));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < K.rows(); ++i)
    for (SparseMatrixR::InnerIterator it(K, i); it; ++it) {
      it.valueRef() *= mu;
      if (it.col() == i) it.valueRef() += (1.0 - mu) * std::pow(spread, u(rng));
    }
  return K;
}

std::vector<int> diagonal_slots(const SparseMatrixR& K) {
  std::vector<int> d(K.rows());
  for (int i = 0; i < K.rows(); ++i)
    for (int p = K.outerIndexPtr()[i]; p < K.outerIndexPtr()[i + 1]; ++p)
      if (K.innerIndexPtr()[p] == i) d[i] = p;
  return d;
}

}  // namespace

TEST_CASE("BiCGSTAB with ILU(0) agrees with sparse LU", "[solver]") {
  const std::vector<TriMesh> meshes = {make_icosphere(3, 1.0), make_torus(40, 20, 2.0, 0.5),
                                       make_grid(30, 20, 1.0, 1.0)};
  unsigned seed = 1;
  for (const TriMesh& m : meshes)
    for (double spread : {1.0, 1e3, 1e6}) {
      const SparseMatrixR K = massage_like(m, 0.4, spread, seed++);
      Positions R = Positions::Random(K.rows(), 3);
      Ilu0 ilu;
      REQUIRE(ilu.factor(K, diagonal_slots(K)));
      Positions X = Positions::Zero(K.rows(), 3);
      const SolveStats it = bicgstab(K, ilu, R, X, 1e-12, 2000);
      REQUIRE(it.ok);
      CHECK(it.residual <= 1e-12);
      Positions Y;
      DirectSolver direct;
      const SolveStats d = direct.solve(K, R, Y);
      REQUIRE(d.ok);
      CHECK(d.residual < 1e-10);
      CHECK((X - Y).cwiseAbs().maxCoeff() < 1e-8 * Y.cwiseAbs().maxCoeff());
    }
}

TEST_CASE("one DirectSolver solves systems of different patterns and sizes in turn", "[solver]") {
  // The ordering is reused only for the pattern it was computed on: each system is checked by
  // its residual and against a fresh solver's answer.
  const SparseMatrixR a = massage_like(make_icosphere(2, 1.0), 0.4, 1.0, 11);
  const SparseMatrixR b = massage_like(make_torus(12, 8, 2.0, 0.5), 0.3, 1.0, 12);
  const SparseMatrixR c = massage_like(make_grid(9, 9, 1.0, 1.0), 0.4, 10.0, 13);
  // Same size as `a`, another pattern: `a` without some of its off-diagonal pairs.
  SparseMatrixR a2 = a;
  a2.prune([](int i, int j, double) { return i == j || (i + j) % 7 != 0; });
  REQUIRE(a2.rows() == a.rows());
  REQUIRE(a2.nonZeros() < a.nonZeros());
  DirectSolver shared;
  for (const SparseMatrixR* K : std::vector<const SparseMatrixR*>{&a, &b, &a, &a2, &c, &a}) {
    const Positions R = Positions::Random(K->rows(), 3);
    Positions X, Y;
    const SolveStats s = shared.solve(*K, R, X);
    REQUIRE(s.ok);
    CHECK(s.residual < 1e-10);
    DirectSolver fresh;
    REQUIRE(fresh.solve(*K, R, Y).ok);
    CHECK((X - Y).cwiseAbs().maxCoeff() <= 1e-9 * Y.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("ILU(0) is the exact LU when the pattern has no fill", "[solver]") {
  // A tridiagonal matrix: its LU factors have no fill-in, so one preconditioner step solves it.
  const int n = 50;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 4.0 + i % 3);
    if (i > 0) t.emplace_back(i, i - 1, -1.0 - 0.01 * i);
    if (i + 1 < n) t.emplace_back(i, i + 1, -0.5);
  }
  SparseMatrixR K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  Ilu0 ilu;
  REQUIRE(ilu.factor(K, diagonal_slots(K)));
  const Positions R = Positions::Random(n, 3);
  Positions Z, KZ;
  ilu.apply(R, Z);
  multiply(K, Z, KZ);
  CHECK((KZ - R).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("a warm start at the solution needs no iteration", "[solver]") {
  const TriMesh m = make_icosphere(2, 1.0);
  const SparseMatrixR K = massage_like(m, 0.3, 10.0, 3);
  const Positions X0 = Positions::Random(K.rows(), 3);
  Positions R;
  multiply(K, X0, R);
  Ilu0 ilu;
  REQUIRE(ilu.factor(K, diagonal_slots(K)));
  Positions X = X0;
  const SolveStats st = bicgstab(K, ilu, R, X, 1e-10, 100);
  CHECK(st.ok);
  CHECK(st.iterations == 0);
}

TEST_CASE("a zero pivot is reported, not divided by", "[solver]") {
  SparseMatrixR K(2, 2);
  std::vector<Eigen::Triplet<double>> t = {{0, 0, 0.0}, {0, 1, 1.0}, {1, 0, 1.0}, {1, 1, 0.0}};
  K.setFromTriplets(t.begin(), t.end());
  Ilu0 ilu;
  CHECK_FALSE(ilu.factor(K, diagonal_slots(K)));
}

TEST_CASE("the centred scale does not depend on where the mesh sits", "[solver]") {
  // K X = R moved by t: K (X + 1t) = R + K1 t. The centred scale (and so the tolerance's meaning
  // and the iterations BiCGSTAB takes) is the same for both, where ‖R‖ is not.
  const TriMesh m = make_torus(40, 20, 2.0, 0.5);
  const SparseMatrixR K = massage_like(m, 0.3, 10.0, 7);
  Positions X = m.V;
  Positions R;
  multiply(K, X, R);
  const Eigen::RowVector3d t(1000.0, -250.0, 40.0);
  const Positions X_far = X.rowwise() + t;
  Positions R_far;
  multiply(K, X_far, R_far);
  const std::vector<unsigned char> none;
  const std::array<double, 3> near = centred_scale(K, R, X, none);
  const std::array<double, 3> far = centred_scale(K, R_far, X_far, none);
  for (int c = 0; c < 3; ++c) {
    INFO("column " << c);
    CHECK(near[c] > 0.0);
    CHECK(far[c] == Approx(near[c]).epsilon(1e-6));
    CHECK(R_far.col(c).norm() > 10.0 * near[c]);  // what the plain criterion would have used
  }
  // Solving from the same relative start takes the same iterations and gives the moved solution.
  Ilu0 ilu;
  REQUIRE(ilu.factor(K, diagonal_slots(K)));
  BicgstabWorkspace ws;
  const Positions start = X + 1e-3 * Positions::Random(X.rows(), 3);
  Positions Y = start, Y_far = start.rowwise() + t;
  const SolveStats a = bicgstab(K, ilu, R, Y, 1e-8, 500, ws, &near);
  const SolveStats b = bicgstab(K, ilu, R_far, Y_far, 1e-8, 500, ws, &far);
  REQUIRE(a.ok);
  REQUIRE(b.ok);
  CHECK(a.iterations == b.iterations);
  CHECK(a.residual <= 1e-8);
  CHECK(((Y_far.rowwise() - t) - Y).cwiseAbs().maxCoeff() < 1e-6);
  CHECK((Y - X).cwiseAbs().maxCoeff() < 1e-5);
  // Fixed rows take no part: a far-away fixed row leaves the scale of the others alone.
  std::vector<unsigned char> fixed(X.rows(), 0);
  fixed[0] = 1;
  Positions R_fixed = R;
  R_fixed.row(0) = Eigen::RowVector3d(1e6, 1e6, 1e6);
  const std::array<double, 3> with_fixed = centred_scale(K, R_fixed, X, fixed);
  const std::array<double, 3> plain = centred_scale(K, R, X, fixed);
  for (int c = 0; c < 3; ++c) CHECK(with_fixed[c] == plain[c]);
}
