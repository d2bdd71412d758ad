#include "massage/coupled_solver.hpp"

#include <Eigen/SparseLU>
#include <cmath>

namespace sm {
namespace {

double dot_all(const Positions& a, const Positions& b) {
  const double* x = a.data();
  const double* y = b.data();
  double s = 0.0;
  for (Eigen::Index p = 0; p < a.size(); ++p) s += x[p] * y[p];
  return s;
}

std::array<double, 3> column_norms(const Positions& a) {
  std::array<double, 3> s{0.0, 0.0, 0.0};
  const double* x = a.data();
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (int c = 0; c < 3; ++c) s[c] += x[3 * i + c] * x[3 * i + c];
  for (double& v : s) v = std::sqrt(v);
  return s;
}

}  // namespace

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

SolveStats bicgstab_coupled(const SparseMatrixR& K, const VertexBlocks& D, const Ilu0& M,
                            const Positions& R, Positions& X, double tolerance,
                            int max_iterations, BicgstabWorkspace& w,
                            const std::array<double, 3>& scale) {
  SolveStats st;
  const int n = static_cast<int>(K.rows());
  Positions &r = w.r, &rhat = w.rhat, &p = w.p, &v = w.v, &y = w.y, &s = w.s, &z = w.z, &t = w.t;
  multiply_coupled(K, D, X, r);
  r = R - r;
  rhat = r;
  p.setZero(n, 3);
  v.setZero(n, 3);
  std::array<double, 3> target;
  for (int c = 0; c < 3; ++c) target[c] = tolerance * (scale[c] > 0.0 ? scale[c] : 1.0);
  std::array<double, 3> res = column_norms(r);
  auto converged = [&] {
    return res[0] <= target[0] && res[1] <= target[1] && res[2] <= target[2];
  };
  auto finish = [&](bool ok, const char* why) {
    st.ok = ok;
    st.message = why;
    for (int c = 0; c < 3; ++c)
      st.residual = std::max(st.residual, res[c] / (target[c] / tolerance));
    return st;
  };
  if (converged()) return finish(true, "");
  double rho = 1.0, alpha = 1.0, omega = 1.0;
  for (st.iterations = 1; st.iterations <= max_iterations; ++st.iterations) {
    const double rho_new = dot_all(rhat, r);
    if (rho_new == 0.0 || omega == 0.0)
      return finish(false, "BiCGSTAB breakdown (rho or omega is 0)");
    const double beta = (rho_new / rho) * (alpha / omega);
    rho = rho_new;
    p = r + beta * (p - omega * v);
    M.apply(p, y);
    multiply_coupled(K, D, y, v);
    const double rv = dot_all(rhat, v);
    if (rv == 0.0) return finish(false, "BiCGSTAB breakdown (r̂·v is 0)");
    alpha = rho / rv;
    s = r - alpha * v;
    X += alpha * y;
    res = column_norms(s);
    if (converged()) {
      r.swap(s);
      return finish(true, "");
    }
    M.apply(s, z);
    multiply_coupled(K, D, z, t);
    const double tt = dot_all(t, t);
    omega = tt > 0.0 ? dot_all(t, s) / tt : 0.0;
    X += omega * z;
    r = s - omega * t;
    res = column_norms(r);
    if (!std::isfinite(res[0] + res[1] + res[2]))
      return finish(false, "BiCGSTAB produced a non-finite residual");
    if (converged()) return finish(true, "");
  }
  st.iterations = max_iterations;
  return finish(false, "BiCGSTAB did not reach the tolerance");
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
