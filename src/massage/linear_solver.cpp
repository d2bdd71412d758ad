#include "massage/linear_solver.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <array>
#include <cmath>

namespace sm {

void multiply(const SparseMatrixR& K, const Positions& X, Positions& Y) {
  const int n = static_cast<int>(K.rows());
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  const double* val = K.valuePtr();
  const double* x = X.data();
  Y.resize(n, 3);
  double* y = Y.data();
  for (int i = 0; i < n; ++i) {
    double s0 = 0.0, s1 = 0.0, s2 = 0.0;
    for (int p = outer[i]; p < outer[i + 1]; ++p) {
      const double v = val[p];
      const double* xj = x + 3 * inner[p];
      s0 += v * xj[0];
      s1 += v * xj[1];
      s2 += v * xj[2];
    }
    y[3 * i] = s0;
    y[3 * i + 1] = s1;
    y[3 * i + 2] = s2;
  }
}

IluSchedule::IluSchedule(const SparseMatrixR& K, const std::vector<int>& diagonal_slots)
    : diagonal(diagonal_slots) {
  const int n = static_cast<int>(K.rows());
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  std::vector<int> marker(n, -1);
  row_lower.assign(1, 0);
  update_begin.assign(1, 0);
  for (int i = 0; i < n; ++i) {
    for (int p = outer[i]; p < outer[i + 1]; ++p) marker[inner[p]] = p;
    for (int p = outer[i]; p < outer[i + 1] && inner[p] < i; ++p) {
      const int j = inner[p];
      lower.push_back(p);
      pivot.push_back(diagonal_slots[j]);
      for (int q = diagonal_slots[j] + 1; q < outer[j + 1]; ++q)
        if (const int slot = marker[inner[q]]; slot >= 0) {
          target.push_back(slot);
          source.push_back(q);
        }
      update_begin.push_back(static_cast<int>(target.size()));
    }
    row_lower.push_back(static_cast<int>(lower.size()));
    for (int p = outer[i]; p < outer[i + 1]; ++p) marker[inner[p]] = -1;
  }
}

bool Ilu0::factor(const SparseMatrixR& K, const std::vector<int>& diagonal_slots) {
  own_ = IluSchedule(K, diagonal_slots);
  const bool ok = factor(K, own_);
  schedule_ = nullptr;
  return ok;
}

bool Ilu0::factor(const SparseMatrixR& K, const IluSchedule& schedule) {
  K_ = &K;
  schedule_ = &schedule;
  const int n = static_cast<int>(K.rows());
  lu_.assign(K.valuePtr(), K.valuePtr() + K.nonZeros());
  double* lu = lu_.data();
  const int* lower = schedule.lower.data();
  const int* pivot = schedule.pivot.data();
  const int* begin = schedule.update_begin.data();
  const int* target = schedule.target.data();
  const int* source = schedule.source.data();
  for (int i = 0; i < n; ++i) {
    for (int e = schedule.row_lower[i]; e < schedule.row_lower[i + 1]; ++e) {
      const int p = lower[e];
      lu[p] /= lu[pivot[e]];
      const double l = lu[p];
      if (l == 0.0) continue;
      for (int u = begin[e]; u < begin[e + 1]; ++u) lu[target[u]] -= l * lu[source[u]];
    }
    const double d = lu[schedule.diagonal[i]];
    if (!(std::abs(d) > 0.0) || !std::isfinite(d)) return false;
  }
  return true;
}

void Ilu0::apply(const Positions& R, Positions& Z) const {
  const SparseMatrixR& K = *K_;
  const std::vector<int>& diag = (schedule_ ? *schedule_ : own_).diagonal;
  const int n = static_cast<int>(K.rows());
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  Z.resize(n, 3);
  double* z = Z.data();
  const double* r = R.data();
  // Forward: L has a unit diagonal and the entries left of it.
  for (int i = 0; i < n; ++i) {
    double s0 = r[3 * i], s1 = r[3 * i + 1], s2 = r[3 * i + 2];
    for (int p = outer[i]; p < diag[i]; ++p) {
      const double l = lu_[p];
      const double* zj = z + 3 * inner[p];
      s0 -= l * zj[0];
      s1 -= l * zj[1];
      s2 -= l * zj[2];
    }
    z[3 * i] = s0;
    z[3 * i + 1] = s1;
    z[3 * i + 2] = s2;
  }
  // Backward: U holds the diagonal and the entries right of it.
  for (int i = n - 1; i >= 0; --i) {
    double s0 = z[3 * i], s1 = z[3 * i + 1], s2 = z[3 * i + 2];
    for (int p = diag[i] + 1; p < outer[i + 1]; ++p) {
      const double u = lu_[p];
      const double* zj = z + 3 * inner[p];
      s0 -= u * zj[0];
      s1 -= u * zj[1];
      s2 -= u * zj[2];
    }
    const double inv = 1.0 / lu_[diag[i]];
    z[3 * i] = s0 * inv;
    z[3 * i + 1] = s1 * inv;
    z[3 * i + 2] = s2 * inv;
  }
}

namespace {

// K as the operator of bicgstab_loop().
struct SparseOperator {
  const SparseMatrixR& K;
  void apply(const Positions& X, Positions& Y) const { multiply(K, X, Y); }
};

}  // namespace

SolveStats bicgstab(const SparseMatrixR& K, const Ilu0& M, const Positions& R, Positions& X,
                    double tolerance, int max_iterations) {
  BicgstabWorkspace ws;
  return bicgstab(K, M, R, X, tolerance, max_iterations, ws);
}

std::array<double, 3> centred_scale(const SparseMatrixR& K, const Positions& R, const Positions& X,
                                    const std::vector<unsigned char>& fixed) {
  const int n = static_cast<int>(K.rows());
  const bool has_fixed = fixed.size() == static_cast<size_t>(n);
  double mean[3] = {0.0, 0.0, 0.0};
  long count = 0;
  for (int i = 0; i < n; ++i) {
    if (has_fixed && fixed[i]) continue;
    for (int c = 0; c < 3; ++c) mean[c] += X(i, c);
    ++count;
  }
  std::array<double, 3> scale{0.0, 0.0, 0.0};
  if (count == 0) return {1.0, 1.0, 1.0};
  for (double& m : mean) m /= static_cast<double>(count);
  const int* outer = K.outerIndexPtr();
  const double* values = K.valuePtr();
  for (int i = 0; i < n; ++i) {
    if (has_fixed && fixed[i]) continue;
    double row_sum = 0.0;
    for (int p = outer[i]; p < outer[i + 1]; ++p) row_sum += values[p];
    for (int c = 0; c < 3; ++c) {
      const double r = R(i, c) - row_sum * mean[c];
      scale[c] += r * r;
    }
  }
  double largest = 0.0;
  for (double& s : scale) largest = std::max(largest, s = std::sqrt(s));
  for (double& s : scale)
    if (!(s > 0.0)) s = largest > 0.0 ? largest : 1.0;
  return scale;
}

SolveStats bicgstab(const SparseMatrixR& K, const Ilu0& M, const Positions& R, Positions& X,
                    double tolerance, int max_iterations, BicgstabWorkspace& w,
                    const std::array<double, 3>* scale) {
  std::array<double, 3> size;
  if (scale) {
    size = *scale;
  } else {
    const krylov::Col3 norm = krylov::column_dots(R, R).sqrt();
    size = {norm[0], norm[1], norm[2]};
  }
  return bicgstab_loop<ColumnScalars>(SparseOperator{K}, M, R, X, tolerance, max_iterations, w,
                                      size);
}

struct DirectSolver::Impl {
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  // The pattern the ordering was computed for (column starts, row indices): an O(nnz) comparison
  // per call, against a factorization that costs far more.
  std::vector<int> outer, inner;

  bool same_pattern(const Eigen::SparseMatrix<double>& K) const {
    const int cols = static_cast<int>(K.cols()), nnz = static_cast<int>(K.nonZeros());
    return static_cast<int>(outer.size()) == cols + 1 && static_cast<int>(inner.size()) == nnz &&
           std::equal(outer.begin(), outer.end(), K.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), K.innerIndexPtr());
  }
};

DirectSolver::DirectSolver() : impl_(std::make_unique<Impl>()) {}
DirectSolver::~DirectSolver() = default;

SolveStats DirectSolver::solve(const SparseMatrixR& K, const Positions& R, Positions& X) {
  SolveStats st;
  Eigen::SparseMatrix<double> Kc = K;
  Kc.makeCompressed();
  if (!impl_->same_pattern(Kc)) {
    impl_->lu.analyzePattern(Kc);
    impl_->outer.assign(Kc.outerIndexPtr(), Kc.outerIndexPtr() + Kc.cols() + 1);
    impl_->inner.assign(Kc.innerIndexPtr(), Kc.innerIndexPtr() + Kc.nonZeros());
  }
  impl_->lu.factorize(Kc);
  if (impl_->lu.info() != Eigen::Success) {
    st.message = "sparse LU factorization failed: " + impl_->lu.lastErrorMessage();
    return st;
  }
  const Eigen::MatrixXd Rc = R;
  const Eigen::MatrixXd Xc = impl_->lu.solve(Rc);
  if (impl_->lu.info() != Eigen::Success || !Xc.allFinite()) {
    st.message = "sparse LU solve failed";
    return st;
  }
  X = Xc;
  Positions KX;
  multiply(K, X, KX);
  const Eigen::Array<double, 1, 3> rn = (R - KX).colwise().norm().array();
  const Eigen::Array<double, 1, 3> bn = R.colwise().norm().array();
  for (int c = 0; c < 3; ++c)
    st.residual = std::max(st.residual, rn[c] / (bn[c] > 0 ? bn[c] : 1.0));
  st.ok = true;
  st.iterations = 1;
  return st;
}

}  // namespace sm
