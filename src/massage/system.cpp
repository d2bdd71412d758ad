#include "massage/system.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace sm {
namespace {

int find_slot(const SparseMatrixR& S, int row, int col) {
  const int* inner = S.innerIndexPtr();
  const int b = S.outerIndexPtr()[row], e = S.outerIndexPtr()[row + 1];
  const int* it = std::lower_bound(inner + b, inner + e, col);
  if (it == inner + e || *it != col)
    throw SolverError("internal: entry (" + std::to_string(row) + ", " + std::to_string(col) +
                      ") is missing from the system's sparsity pattern");
  return static_cast<int>(it - inner);
}

}  // namespace

SystemPattern::SystemPattern(const SparseMatrixR& A, const Triangles& F) : structure_(A) {
  structure_.makeCompressed();
  const int n = static_cast<int>(structure_.rows());
  diag_.resize(n);
  for (int i = 0; i < n; ++i) diag_[i] = find_slot(structure_, i, i);
  tri_slots_.resize(F.rows());
  for (int t = 0; t < F.rows(); ++t)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) tri_slots_[t][3 * a + b] = find_slot(structure_, F(t, a), F(t, b));
  double s = 0.0;
  for (int p = 0; p < structure_.nonZeros(); ++p) s += structure_.valuePtr()[p] * structure_.valuePtr()[p];
  shape_norm_ = std::sqrt(s);
  ilu_ = IluSchedule(structure_, diag_);
}

void assemble_distance_system(const SystemPattern& pattern, const Triangles& F,
                              const Correspondences& pairs, std::vector<double>& B_values,
                              Positions& c) {
  const std::vector<SurfacePoint>& on_reference = pairs.v_hat;
  const std::vector<SurfacePoint>& on_mesh = pairs.w_hat;
  const Eigen::VectorXd& alpha = pairs.alpha;
  const Eigen::VectorXd& beta = pairs.beta;
  const Positions& samples = pairs.samples;
  const int n = pattern.size();
  B_values.assign(pattern.shape_matrix().nonZeros(), 0.0);
  c.setZero(n, 3);
  for (int i = 0; i < n; ++i) {
    B_values[pattern.diagonal_slot(i)] += alpha[i];
    c.row(i) += alpha[i] * on_reference[i].point.transpose();
  }
  for (size_t j = 0; j < on_mesh.size(); ++j) {
    const SurfacePoint& sp = on_mesh[j];
    const std::array<int, 9>& slot = pattern.triangle_slots(sp.triangle);
    const double bj = beta[static_cast<int>(j)];
    for (int a = 0; a < 3; ++a) {
      const double wa = bj * sp.bary[a];
      for (int b = 0; b < 3; ++b) B_values[slot[3 * a + b]] += wa * sp.bary[b];
      c.row(F(sp.triangle, a)) += wa * samples.row(static_cast<int>(j));
    }
  }
}

}  // namespace sm
