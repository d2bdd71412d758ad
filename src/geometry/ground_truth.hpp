#pragma once
/// How far a mesh's vertices are from their true positions (a generated sequence's clean frame),
/// split into the part along the true surface (tangential: the vertex slid, the correspondence is
/// wrong) and the part off it (normal: the vertex left the surface).
#include "mesh/mesh.hpp"

namespace sm {

/// Means and maxima over the vertices, in `unit`s (a mean edge length).
struct CorrespondenceError {
  double mean = 0.0, max = 0.0;                        ///< |v_i − p_i|
  double tangential_mean = 0.0, tangential_max = 0.0;  ///< |(I − n_i n_iᵀ)(v_i − p_i)|
  double normal_mean = 0.0, normal_max = 0.0;          ///< |n_iᵀ (v_i − p_i)|
};

/// V (n×3) against the true positions p = truth.V (n×3, truth.F its triangles), with n_i the
/// area-weighted vertex normal of `truth` at p_i (a vertex with no normal counts as tangential).
/// `unit` > 0.
CorrespondenceError correspondence_error(const Positions& V, const TriMesh& truth, double unit);

}  // namespace sm
