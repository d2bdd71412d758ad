#pragma once
/// Solvers for K X = R with X, R n×3 (x, y, z share K, paper eq. 7) on a fixed sparsity pattern:
/// ILU(0)-preconditioned BiCGSTAB on all three columns at once (one pass over K per product),
/// warm-started from the current positions, and a sparse LU fall-back.
#include <array>
#include <memory>
#include <vector>

#include "geometry/weights.hpp"
#include "massage/bicgstab.hpp"
#include "mesh/mesh.hpp"

namespace sm {

/// Y = K X for n×3 X, one pass over K.
void multiply(const SparseMatrixR& K, const Positions& X, Positions& Y);

/// The symbolic part of ILU(0) on a fixed pattern (sorted columns, explicit diagonal): for every
/// strictly lower entry, row after row, the slot of its pivot and the list of updates
/// lu[target] −= l · lu[source] it makes. Computed once per pattern; factoring is then a straight
/// pass over these lists.
struct IluSchedule {
  std::vector<int> diagonal;      ///< n slots
  std::vector<int> row_lower;     ///< n+1 offsets into `lower`
  std::vector<int> lower;         ///< slots of the strictly lower entries, in row order
  std::vector<int> pivot;         ///< per lower entry: the slot of its column's diagonal
  std::vector<int> update_begin;  ///< per lower entry: offsets into target/source (one more)
  std::vector<int> target, source;

  IluSchedule() = default;
  IluSchedule(const SparseMatrixR& K, const std::vector<int>& diagonal_slots);
  bool matches(const SparseMatrixR& K) const {
    return static_cast<Eigen::Index>(diagonal.size()) == K.rows() &&
           static_cast<Eigen::Index>(row_lower.size()) == K.rows() + 1;
  }
};

/// Incomplete LU factorization with zero fill-in on K's own pattern (K must have sorted columns
/// and an explicit diagonal). The structure is K's; factor() only recomputes the values.
class Ilu0 {
 public:
  /// Computes the factors of K's current values (K must outlive this object's use; the diagonal
  /// slots are copied). Returns false on a zero pivot.
  bool factor(const SparseMatrixR& K, const std::vector<int>& diagonal_slots);
  /// The same with the symbolic analysis done beforehand (`schedule` must be K's pattern's and
  /// outlive this object's use): the same factors, bit for bit, in about half the time.
  bool factor(const SparseMatrixR& K, const IluSchedule& schedule);
  /// Z = (LU)⁻¹ R, n×3.
  void apply(const Positions& R, Positions& Z) const;

 private:
  const SparseMatrixR* K_ = nullptr;
  const IluSchedule* schedule_ = nullptr;  ///< null: own_ (so that copies stay valid)
  IluSchedule own_;
  std::vector<double> lu_;
};

/// Preconditioned BiCGSTAB (van der Vorst, bicgstab.hpp) on the three columns together, each
/// column with its own scalars and stopping test ‖R − K X‖ <= tolerance · ‖R‖ (ColumnScalars).
/// X holds the initial guess.
/// With `scale` (3 positive values), column c stops at ‖R − K X‖ <= tolerance · scale[c] instead
/// (see centred_scale), and the residual reported is relative to it.
SolveStats bicgstab(const SparseMatrixR& K, const Ilu0& preconditioner, const Positions& R,
                    Positions& X, double tolerance, int max_iterations, BicgstabWorkspace& ws,
                    const std::array<double, 3>* scale = nullptr);

/// A size of the system K X = R that does not depend on where the mesh sits: per column,
/// ‖R − K 1 x̄‖ over the rows not in `fixed` (n flags; may be empty), where x̄ is that column's mean
/// over the same rows of `X` (the current positions). For a system that moves with its solution
/// (K X = R gives K (X + 1 t) = R + K 1 t, as eq. 7 does), this is the right-hand side of the
/// problem centred at the origin, so a tolerance relative to it means the same accuracy for a
/// mesh at the origin and for the same mesh far from it; ‖R‖ would be dominated by the offset
/// (and by fixed rows such as a stray vertex far away). A column of zero size takes the largest
/// of the three (1 if all are 0).
std::array<double, 3> centred_scale(const SparseMatrixR& K, const Positions& R, const Positions& X,
                                    const std::vector<unsigned char>& fixed);
SolveStats bicgstab(const SparseMatrixR& K, const Ilu0& preconditioner, const Positions& R,
                    Positions& X, double tolerance, int max_iterations);

/// Sparse LU of K (Eigen's SparseLU, COLAMD ordering). The ordering is computed on the first
/// call and reused while K's sparsity pattern is the same (compared on every call; another
/// pattern is analysed afresh); each call refactors numerically.
class DirectSolver {
 public:
  DirectSolver();
  ~DirectSolver();
  SolveStats solve(const SparseMatrixR& K, const Positions& R, Positions& X);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sm
