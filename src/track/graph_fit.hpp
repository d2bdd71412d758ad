#pragma once
/// Non-rigid ICP of a deformation graph to a raw frame of any connectivity: closest points both
/// ways (template samples → frame, frame samples → deformed template) on the engine's BVH,
/// pruned by distance and normals, weighted robustly; each iteration one Gauss-Newton step of
///
///   E(X) = Σ_s ρ_s e_sᵀ (n_s n_sᵀ + ε I) e_s                         (data, both directions)
///        + λ Σ_(j,k) ‖R_j (g_k − g_j) + g_j + t_j − g_k − t_k‖² / s²  (graph, both directions)
///
/// over rigid node maps X_j = [R_j | t_j], each step (ω_j, δt_j) per node (6 N unknowns, R_j ←
/// R_j exp([ω_j]×)), Levenberg-Marquardt damped, solved by supernodal Cholesky (BlockCholesky) on a
/// block pattern fixed for the template; coarse to fine: λ from `regularizer` down to
/// `regularizer_final`, σ halving. Data weights are per node (N / samples), lengths in units of
/// the template's mean edge length h.
#include <memory>
#include <vector>

#include "geometry/bvh.hpp"
#include "massage/reference.hpp"
#include "track/deformation_graph.hpp"
#include "track/track_options.hpp"

namespace sm {

/// A raw frame prepared for fitting: welded mesh, BVH, normals, sample vertices.
struct RawFrame {
  std::shared_ptr<const Reference> reference;  ///< N of the refinement: mesh, BVH, topology
  Positions triangle_normals;                  ///< m×3
  Positions vertex_normals;                    ///< n×3
  std::vector<int> samples;  ///< vertices in a triangle, at most `samples` of them
  double mean_edge = 0.0;
};

/// Builds the RawFrame of `mesh` (already welded) with at most `max_samples` samples.
RawFrame prepare_raw_frame(TriMesh mesh, int max_samples);

/// One fit's schedule: where it starts and how wide it searches.
struct FitSchedule {
  double scale = 1.0;   ///< σ and pruning distance times this (recovery widens the search)
  int first_stage = 0;  ///< skip the coarsest stages (0: all)
};

struct FitResult {
  std::vector<NodeMap> X;
  Positions V;  ///< the deformed template (n×3)
  int iterations = 0;
  int correspondences = 0;  ///< kept in the last iteration, both directions
};

class GraphFit {
 public:
  /// For `templ` (welded, mean edge length `mean_edge`) and its graph; keeps references to both.
  GraphFit(const TriMesh& templ, const DeformationGraph& graph, const TrackOptions& options,
           double mean_edge);
  ~GraphFit();
  GraphFit(GraphFit&&) noexcept;

  /// Fits the graph to `raw` starting from maps X0. Thread-safe (const).
  FitResult fit(const RawFrame& raw, std::vector<NodeMap> X0, const FitSchedule& schedule) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The rotation nearest to A (polar decomposition; a reflection is flipped on its weakest axis).
Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& A);

}  // namespace sm
