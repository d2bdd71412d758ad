#pragma once
/// Symmetric maximum shear distortion of every triangle against a template (paper eq. 8).
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.hpp"

namespace sm {

/// Distortion of each triangle t of the mesh (V, F) against the template (templ_V, F), the same
/// triangles on other positions (m values). Each of the two triangles is laid out in its own
/// orthonormal 2-D frame (first edge along x, third corner at y > 0) and J is the 2×2 linear map
/// taking the template's triangle to the mesh's; with σ1 ≥ σ2 its singular values (closed form),
///
///     D = max(σ1 + 1/σ1, σ2 + 1/σ2) − 2                                        (eq. 8)
///
/// evaluated as max((σ − 1)² / σ) to avoid cancellation. D = 0 for a congruent triangle,
/// s + 1/s − 2 for one scaled by s, and +infinity when either triangle is degenerate
/// (|e1 × e2| ≤ 1e-14 · longest edge², or non-finite corners). templ_V and V are n×3, F is m×3.
/// Throws InputError if templ_V and V differ in size or F refers to a missing vertex.
Eigen::VectorXd shear_distortion(const Positions& templ_V, const Positions& V, const Triangles& F);

struct DistortionSummary {
  double max = 0.0;   ///< over all values: +infinity if any triangle is degenerate
  double mean = 0.0;  ///< over the finite values
  double p95 = 0.0;   ///< 95th percentile (nearest rank) of the finite values
  int infinite = 0;   ///< number of non-finite values (degenerate triangles)
};

/// Summary of per-triangle distortions; all zero for an empty vector.
DistortionSummary summarize_distortion(const Eigen::VectorXd& distortion);

/// Counts of `values` per bin: bin i holds edges[i] ≤ x < edges[i+1], the last bin also its right
/// edge (so edges ending in +infinity count the degenerate triangles). Values outside, and NaN,
/// are not counted. Returns edges.size() − 1 counts. Throws InputError unless there are at least
/// two edges in strictly increasing order.
std::vector<int> histogram(const Eigen::VectorXd& values, const std::vector<double>& edges);

}  // namespace sm
