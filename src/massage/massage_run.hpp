#pragma once
/// One run of the optimizer (Massager::run), one outer iteration at a time (internal to the
/// massage module). Per iteration k (massage.hpp has the equations):
///   assemble   B, c (eq. 4) from the current correspondences and weights, μ, K = μA + (1−μ)B,
///              the right-hand side μδ + (1−μ)c, pinned rows, the ILU(0) factors;
///   solve      K v = rhs, warm-started (BiCGSTAB, sparse LU as the fall-back);
///   closest    v̂_i on N and ŵ_j on M for the new positions (§2.2.1);
///   measure    the distances both ways and the energy after the solve (IterationStats);
///   reweight   Lawson's update of α, β (eq. 5);
///   stop test  the largest move against the tolerance.
#include <optional>
#include <vector>

#include "geometry/triangle_planes.hpp"
#include "massage/correspondence.hpp"
#include "massage/coupled_solver.hpp"
#include "massage/linear_solver.hpp"
#include "massage/massager_state.hpp"
#include "core/timing.hpp"

namespace sm {

class MassageRun {
 public:
  enum class Step {
    Continue,  ///< another iteration follows
    Done,      ///< the last iteration, or the movement tolerance was met
    Failed,    ///< numerical failure; finish() returns the start positions
  };

  /// Starts a run of `state`'s optimizer at `start` (n×3, finite, the caller's labels) against
  /// `reference`: both into the internal labels, the first (exact) correspondences, α = β = 1,
  /// the shape target δ. Both must outlive the run.
  MassageRun(const MassagerState& state, const Positions& start, const Reference& reference);
  MassageRun(const MassageRun&) = delete;
  MassageRun& operator=(const MassageRun&) = delete;

  /// One outer iteration. Call while it returns Continue.
  Step step();
  /// The figures of the last successful iteration.
  const IterationStats& last() const { return result_.iterations.back(); }
  /// M's current positions in the caller's labels (n×3).
  Positions positions() const;
  /// The fold-over check and the result in the caller's labels; call once, after the last step.
  MassageResult finish();

 private:
  bool assemble(IterationStats& it);  // returns whether to take the direct solver
  void add_plane_term();
  bool solve(IterationStats& it, bool use_direct, int k);
  void closest_points(IterationStats& it);
  void measure(IterationStats& it);
  void refit_m();
  void fail(IterationStats& it, const std::string& why);

  const MassagerState& s_;
  const MassageOptions& o_;
  Clock::time_point t_run_;
  const Positions& start_in_;
  Positions start_;  // internal labels
  std::optional<Reference> relabelled_;
  const Reference& reference_;
  TriMesh M_;
  TriangleBvh bvh_m_;  // copied from the template's on first use
  bool bvh_m_current_ = false;
  TrianglePlanes planes_m_;
  SurfaceView on_n_, on_m_;
  std::vector<SurfacePoint> v_hat_, w_hat_;  // v̂_i on N, ŵ_j on M
  Eigen::VectorXd alpha_, beta_, d_alpha_, d_beta_;
  double move_limit_ = 0.0;
  SparseMatrixR K_;  // values overwritten every iteration
  std::vector<double> A_values_, B_values_;
  Positions c_, rhs_, X_, AV_, V_prev_, delta_;
  bool use_target_ = false;
  double mu_ = 0.0;
  Ilu0 ilu_;
  // The plane term (plane_term.hpp): ε per vertex, N's vertex normals, the blocks D and the
  // isotropic matrix whose ILU(0) preconditions the coupled system.
  bool plane_ = false;
  Eigen::VectorXd epsilon_;
  Positions normals_n_;
  VertexBlocks D_;
  SparseMatrixR K_pre_;
  BicgstabWorkspace workspace_;
  DirectSolver direct_;
  int k_ = 0;  // iterations done
  MassageResult result_;
};

}  // namespace sm
