#pragma once
/// The fixed sparsity pattern of the combined system K = μA + (1−μ)B (paper eq. 7) and the
/// numeric assembly of B and c (eq. 4) onto it.
///
/// Every β-term of B couples the three vertices of one triangle of M, which are already
/// neighbours in A, so K has A's pattern (with its diagonal) for every iteration, frame and
/// reference. SystemPattern computes, once per connectivity, the slot of every diagonal entry and
/// of the nine (vertex, vertex) pairs of every triangle, so assembly is a scatter with no search.
#include <array>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/weights.hpp"
#include "massage/linear_solver.hpp"

namespace sm {

class SystemPattern {
 public:
  SystemPattern() = default;
  /// A: the shape matrix (n×n, explicit diagonal in every row); F: M's triangles (m×3).
  SystemPattern(const SparseMatrixR& A, const Triangles& F);

  int size() const { return static_cast<int>(structure_.rows()); }
  /// K's structure with A's values (n×n row-major, sorted columns).
  const SparseMatrixR& shape_matrix() const { return structure_; }
  double shape_norm() const { return shape_norm_; }  ///< ‖A‖_F
  int diagonal_slot(int i) const { return diag_[i]; }
  /// Slot of entry (F(t,a), F(t,b)) in the value array: slots(t)[3a + b].
  const std::array<int, 9>& triangle_slots(int t) const { return tri_slots_[t]; }
  const std::vector<int>& diagonal_slots() const { return diag_; }
  /// The symbolic ILU(0) analysis of the pattern (Ilu0::factor).
  const IluSchedule& ilu_schedule() const { return ilu_; }

 private:
  SparseMatrixR structure_;
  double shape_norm_ = 0.0;
  std::vector<int> diag_;
  std::vector<std::array<int, 9>> tri_slots_;
  IluSchedule ilu_;
};

/// The correspondences of the distance energy (eq. 3) as one iteration holds them.
struct Correspondences {
  const std::vector<SurfacePoint>& v_hat;  ///< v̂_i: the point of N closest to vertex i (n)
  const Eigen::VectorXd& alpha;            ///< α_i, its weight (n)
  const Positions& samples;                ///< w_j: the samples on N (s×3)
  const std::vector<SurfacePoint>& w_hat;  ///< ŵ_j: the point of M closest to w_j (s)
  const Eigen::VectorXd& beta;             ///< β_j, its weight (s)
};

/// The distance energy's normal equations B v = c (eq. 4) on the pattern:
///   B = Σ_i α_i e_i e_iᵀ + Σ_j β_j b_j b_jᵀ,   c = Σ_i α_i v̂_i + Σ_j β_j b_j w_j
/// where b_j holds ŵ_j's barycentric coordinates scattered onto the vertices of its triangle of
/// F (M's triangles). `B_values` gets nnz entries, `c` n×3 (buffers reused from call to call).
void assemble_distance_system(const SystemPattern& pattern, const Triangles& F,
                              const Correspondences& pairs, std::vector<double>& B_values,
                              Positions& c);

}  // namespace sm
