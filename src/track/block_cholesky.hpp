#pragma once
/// Supernodal (multifrontal) Cholesky factorization P K Pᵀ = L Lᵀ of a symmetric positive
/// definite matrix K made of dense b×b blocks over a fixed block pattern, for systems that are
/// factorized again and again with new values (the deformation graph's Gauss-Newton steps):
/// the pattern is analysed once (AMD ordering of the blocks, elimination tree, relaxed
/// supernodes), every factorization then runs on dense fronts with Eigen's blocked kernels.
/// A simplicial factorization (Eigen::SimplicialLDLT) spends most of its time in scalar
/// indexing: on the graph fit's 4584×4584 system with 1.06M non-zeros in L it reached about
/// 2 GFLOP/s. Deterministic: one thread, a fixed order of operations.
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace sm {

class BlockCholesky {
 public:
  BlockCholesky() = default;

  /// The pattern of the upper block triangle of an n×n block matrix (n = num_blocks, each
  /// block b×b), as CSR: block row j holds the blocks (j, cols[i]) for offsets[j] ≤ i <
  /// offsets[j + 1], each cols[i] ≥ j. Every diagonal block (j, j) must be listed.
  /// Throws InputError on an index out of range, a block below the diagonal or a missing
  /// diagonal block.
  BlockCholesky(int num_blocks, int block_size, const std::vector<int>& offsets,
                const std::vector<int>& cols);

  /// Factorizes K from `values`: the pattern's blocks in CSR order, each b×b column-major
  /// (b² doubles), block i being K's rows of j and columns of cols[i]; a diagonal block is read
  /// in its lower triangle. Returns false if K is not positive definite (numerically).
  bool factorize(const double* values);

  /// x = K⁻¹ rhs (rhs of length n b), with the last successful factorization.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;

  int size() const { return n_ * b_; }
  /// Non-zeros of the factor L, counting its dense fronts' lower triangles.
  long factor_nonzeros() const;
  int num_supernodes() const { return static_cast<int>(super_first_.size()) - 1; }

 private:
  // The analysis, step by step (in the elimination order).
  struct Symbolic {
    std::vector<std::vector<int>> structure;  // per column: its block rows below the diagonal
    std::vector<int> parent;                  // elimination tree, −1 at a root
  };
  Symbolic symbolic(const std::vector<int>& offsets, const std::vector<int>& cols,
                    const std::vector<int>& new_of) const;
  std::vector<int> form_supernodes(const Symbolic& sym);  // returns each column's supernode
  int position(int s, int index) const;  // block position of a block index in s's front
  // Supernode s's front: its k = b·columns and its size m = k + b·(rows below).
  std::pair<int, int> front_shape(int s) const {
    const int k = b_ * (super_first_[s + 1] - super_first_[s]);
    return {k, k + b_ * (rows_offsets_[s + 1] - rows_offsets_[s])};
  }
  void map_entries(const std::vector<int>& offsets, const std::vector<int>& cols,
                   const std::vector<int>& new_of, const std::vector<int>& super_of);
  void plan_stack();

  int n_ = 0, b_ = 0;
  std::vector<int> old_of_;           // block in the elimination order → block of K
  std::vector<int> super_first_{0};   // supernode s: block columns [first[s], first[s + 1])
  std::vector<int> rows_offsets_{0};  // supernode s: its block rows below, CSR
  std::vector<int> rows_;             // (in the elimination order)
  std::vector<int> super_parent_;     // −1 at a root
  std::vector<std::vector<int>> children_;
  // Per child: where each of its block rows sits in its parent's front (block position).
  std::vector<std::vector<int>> extend_map_;
  // Per input block: its supernode, its row and column block positions in that front, and
  // whether it enters transposed; grouped by supernode (`entry_offsets_`).
  struct Entry {
    int input = 0, row = 0, col = 0;
    bool transposed = false;
  };
  std::vector<int> entry_offsets_{0};
  std::vector<Entry> entries_;
  // Numeric: per supernode its front's first k = b·ncols columns (L11 over L21), m×k.
  std::vector<Eigen::MatrixXd> factor_;
  std::vector<int> order_;  // supernodes in postorder
  // Scratch kept from one factorization to the next, so that refactorizing allocates nothing:
  // the largest front, and the stack of updates to parents' fronts.
  int front_size_ = 0;
  long stack_peak_ = 0;
  Eigen::MatrixXd front_;
  std::vector<double> stack_;
};

}  // namespace sm
