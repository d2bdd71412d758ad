#pragma once
/// What a run of the optimizer gives back: the figures of each outer iteration (IterationStats),
/// the result (MassageResult) and the observer that sees iterations as they end. A low header:
/// the Massager's API (massage.hpp) and its internal state and run (massager_state.hpp,
/// massage_run.hpp) read it without including each other.
#include <functional>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace sm {

/// What one outer iteration did (all distances in model units).
struct IterationStats {
  int iteration = 0;
  double mu = 0.0;
  double energy = 0.0;  ///< μ‖Av − δ‖² + (1−μ)·(weighted distances, eq. 4), after solve
  double max_dist_m_to_n = 0.0;  ///< max_i |v_i − v̂_i| (after the solve)
  double rms_dist_m_to_n = 0.0;
  double max_dist_n_to_m = 0.0;  ///< max_j |w_j − ŵ_j|
  double rms_dist_n_to_m = 0.0;
  double max_move = 0.0;  ///< largest vertex displacement of this iteration
  int solver_iterations = 0;
  double solver_residual = 0.0;   ///< relative residual reached
  int exact_queries = 0;          ///< closest-point queries that needed the exact (BVH) search
  double seconds_closest = 0.0;   ///< closest points both ways, BVH refit
  double seconds_assemble = 0.0;  ///< B, c, K, preconditioner or factorization
  double seconds_solve = 0.0;
};

struct MassageResult {
  Positions V;  ///< optimized positions of M (n×3)
  std::vector<IterationStats> iterations;
  bool ok = true;              ///< false: numerical failure, see `failure`; V is then the start
  std::string failure;         ///< why the run failed (solver breakdown, NaN, ...)
  bool stopped_early = false;  ///< the movement tolerance was met before the last iteration
  /// Triangles of the result whose normal opposes N's where their corners land: the sum of the
  /// normals of the three triangles of N that hold the corners' closest points v̂ (not N's normal
  /// at the triangle's centroid).
  int folded_triangles = 0;
  /// With shape_target "template": vertices whose normal is undefined in T or in the start (no
  /// area around them), which keep the paper's target δ_i = 0.
  int target_fallback_vertices = 0;
  double seconds = 0.0;
};

/// Sees each outer iteration as it ends: its figures and M's positions then (n×3, the caller's
/// labels; valid during the call). Not called for an iteration that fails.
using IterationObserver = std::function<void(const IterationStats& stats, const Positions& V)>;

}  // namespace sm
