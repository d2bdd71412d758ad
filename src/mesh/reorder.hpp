#pragma once
/// A relabelling of a mesh's vertices and triangles in narrow bands across the surface (reverse
/// Cuthill–McKee), so that neighbours on the surface are neighbours in memory: the closest-point
/// walks, the assembly of eq. 7 and the ILU(0) sweeps then hit the caches, and ILU(0) in this
/// order is a better preconditioner. Captured meshes often come in scan or tracking order, which
/// scatters neighbours across memory; this order makes every optimizer iteration cheaper.
#include <vector>

#include "mesh/mesh.hpp"

namespace sm {

/// A relabelling: new vertex k is old vertex `vertex_order[k]`, old vertex i is new vertex
/// `vertex_rank[i]`; new triangle k is old triangle `triangle_order[k]`, with its corners in the
/// same (cyclic) order, so orientation is kept.
struct MeshOrder {
  std::vector<int> vertex_order, vertex_rank, triangle_order;
};

/// Reverse Cuthill–McKee on the vertex graph of `mesh`'s triangles: per connected component (in
/// the order of their lowest vertex), breadth first from a pseudo-peripheral vertex (the
/// lowest-degree vertex of the last level of a breadth-first search, twice), unplaced neighbours
/// by increasing degree then index; the whole component's labels reversed. Vertices in no
/// triangle are components of their own. Triangles by their lowest new corner (ties by index).
/// Deterministic; O(n log n + m).
MeshOrder banded_order(const TriMesh& mesh);

/// Rows of X (n×3, old labels) in the new order: out.row(k) = X.row(vertex_order[k]).
Positions to_new_order(const MeshOrder& order, const Positions& X);
/// The inverse: out.row(i) = X.row(vertex_rank[i]).
Positions to_old_order(const MeshOrder& order, const Positions& X);
/// F's triangles in the new order with new vertex labels (m×3).
Triangles to_new_order(const MeshOrder& order, const Triangles& F);

}  // namespace sm
