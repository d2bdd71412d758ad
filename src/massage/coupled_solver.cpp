#include "massage/coupled_solver.hpp"

#include <Eigen/SparseLU>
#include <algorithm>

namespace sm {

void multiply_coupled(const SparseMatrixR& K, const VertexBlocks& D, const Positions& X,
                      Positions& Y) {
  if (D.empty()) {
    multiply(K, X, Y);
    return;
  }
  const int n = static_cast<int>(K.rows());
  Y.resize(n, 3);
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  const double* values = K.valuePtr();
  const double* x = X.data();
  double* y = Y.data();
  for (int i = 0; i < n; ++i) {
    double y0 = 0.0, y1 = 0.0, y2 = 0.0;
    for (int p = outer[i]; p < outer[i + 1]; ++p) {
      const double* xj = x + 3 * inner[p];
      const double k = values[p];
      const std::array<double, 6>& d = D[p];
      y0 += (k - d[0]) * xj[0] - d[3] * xj[1] - d[4] * xj[2];
      y1 += -d[3] * xj[0] + (k - d[1]) * xj[1] - d[5] * xj[2];
      y2 += -d[4] * xj[0] - d[5] * xj[1] + (k - d[2]) * xj[2];
    }
    y[3 * i] = y0;
    y[3 * i + 1] = y1;
    y[3 * i + 2] = y2;
  }
}

namespace {

// K ⊗ I₃ − D as the operator of bicgstab_loop().
struct CoupledOperator {
  const SparseMatrixR& K;
  const VertexBlocks& D;
  void apply(const Positions& X, Positions& Y) const { multiply_coupled(K, D, X, Y); }
};

}  // namespace

SolveStats bicgstab_coupled(const SparseMatrixR& K, const VertexBlocks& D, const Ilu0& M,
                            const Positions& R, Positions& X, double tolerance, int max_iterations,
                            BicgstabWorkspace& w, const std::array<double, 3>& scale) {
  return bicgstab_loop<SharedScalars>(CoupledOperator{K, D}, M, R, X, tolerance, max_iterations, w,
                                      scale);
}

SolveStats solve_coupled_direct(const SparseMatrixR& K, const VertexBlocks& D, const Positions& R,
                                Positions& X) {
  const int n = static_cast<int>(K.rows());
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(12 * K.nonZeros()));
  static constexpr int kRow[6] = {0, 1, 2, 0, 0, 1}, kCol[6] = {0, 1, 2, 1, 2, 2};
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  for (int i = 0; i < n; ++i)
    for (int p = outer[i]; p < outer[i + 1]; ++p) {
      const int j = inner[p];
      for (int c = 0; c < 3; ++c) entries.emplace_back(3 * i + c, 3 * j + c, K.valuePtr()[p]);
      if (D.empty()) continue;
      for (int q = 0; q < 6; ++q) {
        entries.emplace_back(3 * i + kRow[q], 3 * j + kCol[q], -D[p][q]);
        if (kRow[q] != kCol[q]) entries.emplace_back(3 * i + kCol[q], 3 * j + kRow[q], -D[p][q]);
      }
    }
  Eigen::SparseMatrix<double> S(3 * n, 3 * n);
  S.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  lu.compute(S);
  SolveStats st;
  if (lu.info() != Eigen::Success) {
    st.message = "sparse LU of the coupled system failed: " + lu.lastErrorMessage();
    return st;
  }
  Eigen::VectorXd rhs(3 * n);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) rhs[3 * i + c] = R(i, c);
  const Eigen::VectorXd x = lu.solve(rhs);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) X(i, c) = x[3 * i + c];
  Positions check;
  multiply_coupled(K, D, X, check);
  st.ok = X.allFinite();
  st.residual = (R - check).norm() / std::max(R.norm(), 1e-300);
  st.iterations = 1;
  if (!st.ok) st.message = "the coupled direct solve produced NaN";
  return st;
}

}  // namespace sm
