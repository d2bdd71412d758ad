// The coupled solvers of the point-to-plane term (massage/coupled_solver.hpp) against a dense
// solve of the 3n×3n matrix K ⊗ I₃ − D assembled here from its definition, independently of the
// solvers' own assembly.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cstring>
#include <random>

#include "massage/coupled_solver.hpp"
#include "massage/system.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

namespace {

struct CoupledCase {
  SparseMatrixR K;
  VertexBlocks D;
  std::vector<int> diagonal;
};

int slot_of(const SparseMatrixR& K, int i, int j) {
  for (int p = K.outerIndexPtr()[i]; p < K.outerIndexPtr()[i + 1]; ++p)
    if (K.innerIndexPtr()[p] == j) return p;
  FAIL("no slot (" << i << ", " << j << ") in the pattern");
  return -1;
}

// b (I − n nᵀ) as the six stored values (xx, yy, zz, xy, xz, yz).
std::array<double, 6> projector_block(const Eigen::Vector3d& n, double b) {
  return {b * (1 - n.x() * n.x()), b * (1 - n.y() * n.y()), b * (1 - n.z() * n.z()),
          -b * n.x() * n.y(),      -b * n.x() * n.z(),      -b * n.y() * n.z()};
}

void add_block(std::array<double, 6>& to, const std::array<double, 6>& b) {
  for (int q = 0; q < 6; ++q) to[q] += b[q];
}

// The plane term's structure (plane_term.hpp) with random data: K = μA + (1−μ)diag(α), vertex
// blocks (1−μ)α_i(1−ε)(I − n_i n_iᵀ), and per triangle one sample whose block
// (1−μ)β(1−ε) b_a b_b (I − n nᵀ) lands on every slot (a, b) of the triangle.
CoupledCase coupled_case(const TriMesh& m, double epsilon, unsigned seed) {
  const double mu = 0.3;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  CoupledCase c;
  c.K = shape_matrix(compute_weights(m, WeightKind::MeanValue));
  const int n = static_cast<int>(c.K.rows());
  c.D.assign(static_cast<size_t>(c.K.nonZeros()), std::array<double, 6>{});
  c.diagonal.resize(n);
  for (int i = 0; i < n; ++i) {
    const double alpha = 0.5 + u(rng);
    const int d = slot_of(c.K, i, i);
    c.diagonal[i] = d;
    for (int p = c.K.outerIndexPtr()[i]; p < c.K.outerIndexPtr()[i + 1]; ++p)
      c.K.valuePtr()[p] *= mu;
    c.K.valuePtr()[d] += (1 - mu) * alpha;
    const Eigen::Vector3d normal = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    add_block(c.D[d], projector_block(normal, (1 - mu) * alpha * (1 - epsilon)));
  }
  for (Eigen::Index t = 0; t < m.F.rows(); ++t) {
    const double beta = 0.2 * u(rng);
    Eigen::Vector3d b(u(rng), u(rng), u(rng));
    b /= b.sum();
    const Eigen::Vector3d normal = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < 3; ++k) {
        const int va = m.F(t, a), vk = m.F(t, k);
        c.K.valuePtr()[slot_of(c.K, va, vk)] += (1 - mu) * beta * b[a] * b[k];
        add_block(c.D[slot_of(c.K, va, vk)],
                  projector_block(normal, (1 - mu) * beta * (1 - epsilon) * b[a] * b[k]));
      }
  }
  return c;
}

Eigen::MatrixXd dense_coupled(const CoupledCase& c) {
  const Eigen::Index n = c.K.rows();
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (int i = 0; i < n; ++i)
    for (SparseMatrixR::InnerIterator it(c.K, i); it; ++it) {
      const std::array<double, 6>& d = c.D[static_cast<size_t>(&it.valueRef() - c.K.valuePtr())];
      Eigen::Matrix3d block;
      block << d[0], d[3], d[4], d[3], d[1], d[5], d[4], d[5], d[2];
      S.block<3, 3>(3 * i, 3 * it.col()) = it.value() * Eigen::Matrix3d::Identity() - block;
    }
  return S;
}

Eigen::VectorXd flat(const Positions& X) {
  Eigen::VectorXd v(X.size());
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    for (int k = 0; k < 3; ++k) v[3 * i + k] = X(i, k);
  return v;
}

// ILU(0) of K with the mean of D's diagonal taken off, as the optimizer preconditions.
Ilu0 preconditioner(const CoupledCase& c, SparseMatrixR& shifted) {
  shifted = c.K;
  for (size_t i = 0; i < c.diagonal.size(); ++i) {
    const std::array<double, 6>& d = c.D[c.diagonal[i]];
    shifted.valuePtr()[c.diagonal[i]] -= (d[0] + d[1] + d[2]) / 3.0;
  }
  Ilu0 ilu;
  REQUIRE(ilu.factor(shifted, c.diagonal));
  return ilu;
}

}  // namespace

TEST_CASE("the coupled product is (K ⊗ I3 − D) X", "[solver][coupled]") {
  const TriMesh m = make_icosphere(1, 1.0);
  const CoupledCase c = coupled_case(m, 0.2, 3);
  const Positions X = Positions::Random(c.K.rows(), 3);
  Positions Y;
  multiply_coupled(c.K, c.D, X, Y);
  const Eigen::VectorXd expected = dense_coupled(c) * flat(X);
  CHECK((flat(Y) - expected).cwiseAbs().maxCoeff() < 1e-12 * expected.cwiseAbs().maxCoeff());
}

TEST_CASE("coupled BiCGSTAB and the coupled LU agree with a dense solve", "[solver][coupled]") {
  const std::vector<TriMesh> meshes = {make_icosphere(2, 1.0), make_grid(9, 7, 1.0, 1.0)};
  unsigned seed = 11;
  for (const TriMesh& m : meshes)
    for (double epsilon : {0.05, 0.2, 1.0}) {
      CAPTURE(m.V.rows(), epsilon);
      const CoupledCase c = coupled_case(m, epsilon, seed++);
      const Positions R = Positions::Random(c.K.rows(), 3);
      const Eigen::VectorXd expected = dense_coupled(c).fullPivLu().solve(flat(R));
      const double size = expected.cwiseAbs().maxCoeff();

      Positions direct = Positions::Zero(c.K.rows(), 3);
      const SolveStats d = solve_coupled_direct(c.K, c.D, R, direct);
      REQUIRE(d.ok);
      CHECK((flat(direct) - expected).cwiseAbs().maxCoeff() < 1e-9 * size);

      SparseMatrixR shifted;
      const Ilu0 ilu = preconditioner(c, shifted);
      BicgstabWorkspace ws;
      Positions iterative = Positions::Zero(c.K.rows(), 3);
      const SolveStats it = bicgstab_coupled(c.K, c.D, ilu, R, iterative, 1e-12, 2000, ws,
                                             {R.col(0).norm(), R.col(1).norm(), R.col(2).norm()});
      REQUIRE(it.ok);
      CHECK((flat(iterative) - expected).cwiseAbs().maxCoeff() < 1e-8 * size);
    }
}

TEST_CASE("with no blocks the coupled solvers are the uncoupled ones", "[solver][coupled]") {
  const TriMesh m = make_torus(12, 8, 2.0, 0.5);
  CoupledCase c = coupled_case(m, 1.0, 5);
  const Positions R = Positions::Random(c.K.rows(), 3);
  Positions coupled = Positions::Zero(c.K.rows(), 3), plain = coupled;
  REQUIRE(solve_coupled_direct(c.K, {}, R, coupled).ok);
  DirectSolver lu;
  REQUIRE(lu.solve(c.K, R, plain).ok);
  CHECK((coupled - plain).cwiseAbs().maxCoeff() < 1e-10 * plain.cwiseAbs().maxCoeff());
}

TEST_CASE("ILU(0) from a precomputed schedule equals ILU(0) bit for bit", "[solver]") {
  for (unsigned seed : {1u, 2u}) {
    const CoupledCase c = coupled_case(make_torus(20, 12, 2.0, 0.5), 0.5, seed);
    Ilu0 plain, scheduled;
    REQUIRE(plain.factor(c.K, c.diagonal));
    const IluSchedule schedule(c.K, c.diagonal);
    REQUIRE(scheduled.factor(c.K, schedule));
    const Positions R = Positions::Random(c.K.rows(), 3);
    Positions a, b;
    plain.apply(R, a);
    scheduled.apply(R, b);
    REQUIRE(a.size() == b.size());
    CHECK(std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0);
  }
}
