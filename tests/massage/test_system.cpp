#include <catch2/catch.hpp>

#include <Eigen/Cholesky>
#include <random>

#include "massage/system.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

namespace {

// E(v) = Σ α_i |v_i − v̂_i|² + Σ β_j |Σ_k b_jk v_k − w_j|²  (eq. 4 with fixed correspondences)
double energy(const Positions& V, const Triangles& F, const std::vector<SurfacePoint>& v_hat,
              const Eigen::VectorXd& alpha, const Positions& W,
              const std::vector<SurfacePoint>& w_hat, const Eigen::VectorXd& beta) {
  double e = 0.0;
  for (int i = 0; i < V.rows(); ++i) e += alpha[i] * (V.row(i) - v_hat[i].point.transpose()).squaredNorm();
  for (int j = 0; j < W.rows(); ++j) {
    Vec3 p = Vec3::Zero();
    for (int a = 0; a < 3; ++a) p += w_hat[j].bary[a] * V.row(F(w_hat[j].triangle, a)).transpose();
    e += beta[j] * (p - W.row(j).transpose()).squaredNorm();
  }
  return e;
}

}  // namespace

TEST_CASE("B and c are the normal equations of the distance energy", "[system]") {
  const std::vector<TriMesh> meshes = {make_icosphere(1, 1.0), make_grid(4, 3, 1.0, 1.0),
                                       make_torus(8, 6, 2.0, 0.5)};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.1, 2.0);
  for (const TriMesh& m : meshes) {
    const SystemPattern pattern(shape_matrix(compute_weights(m, WeightKind::MeanValue)), m.F);
    const int n = m.num_vertices();
    std::vector<SurfacePoint> v_hat(n);
    for (auto& sp : v_hat) sp.point = Vec3(u(rng), u(rng), u(rng));
    const int s = 2 * n;
    Positions W(s, 3);
    std::vector<SurfacePoint> w_hat(s);
    for (int j = 0; j < s; ++j) {
      W.row(j) << u(rng), u(rng), u(rng);
      w_hat[j].triangle = static_cast<int>(rng() % m.num_triangles());
      Vec3 b(pos(rng), pos(rng), pos(rng));
      w_hat[j].bary = b / b.sum();
    }
    Eigen::VectorXd alpha(n), beta(s);
    for (int i = 0; i < n; ++i) alpha[i] = pos(rng);
    for (int j = 0; j < s; ++j) beta[j] = pos(rng);

    std::vector<double> B_values;
    Positions c;
    assemble_distance_system(pattern, m.F, {v_hat, alpha, W, w_hat, beta}, B_values, c);
    SparseMatrixR B = pattern.shape_matrix();
    std::copy(B_values.begin(), B_values.end(), B.valuePtr());

    Positions V(n, 3);
    for (int i = 0; i < n; ++i) V.row(i) << u(rng), u(rng), u(rng);
    const Positions grad = 2.0 * (B * V - c);  // ∇E = 2(Bv − c)
    const double h = 1e-6;
    for (int i = 0; i < n; i += 3)
      for (int d = 0; d < 3; ++d) {
        Positions Vp = V, Vm = V;
        Vp(i, d) += h;
        Vm(i, d) -= h;
        const double fd = (energy(Vp, m.F, v_hat, alpha, W, w_hat, beta) -
                           energy(Vm, m.F, v_hat, alpha, W, w_hat, beta)) / (2 * h);
        CHECK(grad(i, d) == Approx(fd).epsilon(1e-6).margin(1e-6));
      }
    // B is symmetric positive definite: α > 0 on the diagonal, β-terms are outer products.
    const Eigen::MatrixXd Bd = Eigen::MatrixXd(B);
    CHECK((Bd - Bd.transpose()).cwiseAbs().maxCoeff() < 1e-12);
    CHECK(Eigen::LLT<Eigen::MatrixXd>(Bd).info() == Eigen::Success);
  }
}

TEST_CASE("the system pattern is A's pattern and holds every triangle's pairs", "[system]") {
  const TriMesh m = make_box(3, 1.0, 1.0, 1.0);
  const SparseMatrixR A = shape_matrix(compute_weights(m, WeightKind::MeanValue));
  const SystemPattern pattern(A, m.F);
  CHECK(pattern.shape_matrix().nonZeros() == A.nonZeros());
  CHECK(pattern.shape_norm() == Approx(A.norm()));
  for (int t = 0; t < m.num_triangles(); ++t)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const int slot = pattern.triangle_slots(t)[3 * a + b];
        CHECK(pattern.shape_matrix().innerIndexPtr()[slot] == m.F(t, b));
      }
}
