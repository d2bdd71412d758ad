#pragma once
/// The point-to-plane distance term ("distance_term": "plane"): vertex i's term of eq. 4 becomes
///   α_i [ (n_iᵀ(v_i − v̂_i))² + ε_i ‖(I − n_i n_iᵀ)(v_i − v̂_i)‖² ]
/// with n_i N's normal at v̂_i (vertex normals interpolated there), so M may slide along N where
/// ε_i is small, as in point-to-plane ICP. Its normal equations are the isotropic term of B (kept
/// in K) minus D_i = (1−μ)α_i(1−ε_i)(I − n_i n_iᵀ) on the vertex's 3×3 diagonal block, with
/// right-hand side (1−μ)α_i v̂_i − D_i v̂_i (coupled_solver.hpp). At a fixed point v̂_i is the
/// closest point of v_i, v_i − v̂_i is normal and the term's gradient equals eq. 4's: the energy's
/// stationary points are the paper's, the iteration reaches them faster along the surface.
#include <vector>

#include "geometry/bvh.hpp"
#include "massage/coupled_solver.hpp"
#include "massage/system.hpp"
#include "mesh/topology.hpp"

namespace sm {

/// ε_i per vertex (n): `stiffness` everywhere, raised where the surface stretches between the
/// template T and the start S: ε_i = min(1, stiffness + adapt · s_i), s_i the magnitude of the
/// log area ratio log(area_S / area_T) of the triangles around i, smoothed by `passes` passes of
/// 1-ring averaging first (so that the oscillating area change of a tangential drift averages out
/// and a real stretch stays). Boundary vertices take 1 (point-to-point: a boundary has no tangent
/// plane to slide in across it).
Eigen::VectorXd tangential_stiffness(const Positions& T, const Positions& S, const Triangles& F,
                                     const Topology& topology, double stiffness, double adapt,
                                     int passes);

/// What the plane term reads: M and its correspondences on N, N's normals, the weights. All
/// references, to the caller's arrays (which outlive the call of plane_blocks()).
struct PlaneInputs {
  const SystemPattern& pattern;
  // M: its triangles (the pattern's), its positions, n vertices.
  const Triangles& F;
  const Positions& V;
  // N: its triangles and vertex normals, and the samples w_j on it.
  const Triangles& N_F;
  const Positions& normals_n;
  const Positions& samples;
  // The correspondences: v̂_i on N (n), ŵ_j on M (one per sample).
  const std::vector<SurfacePoint>& v_hat;
  const std::vector<SurfacePoint>& w_hat;
  // α_i (n), β_j (per sample), ε_i (n, tangential_stiffness()), the pinned rows (n flags), μ.
  const Eigen::VectorXd& alpha;
  const Eigen::VectorXd& beta;
  const Eigen::VectorXd& epsilon;
  const std::vector<unsigned char>& pinned;
  double mu;
};

/// The plane term's blocks D on the pattern's slots (nnz) and its part of the right-hand side
/// (rhs −= D-part of the targets), for the current correspondences. Vertex i's term as above;
/// sample w_j's term (eq. 4's β-part) the same with M's normal n_j on the triangle ŵ_j lies on and
/// ε_j the mean of that triangle's ε: (1−μ)β_j(1−ε_j) b_a b_b (I − n_j n_jᵀ) on slot (a, b).
/// Rows of pinned vertices get none.
void plane_blocks(const PlaneInputs& in, VertexBlocks& D, Positions& rhs);

}  // namespace sm
