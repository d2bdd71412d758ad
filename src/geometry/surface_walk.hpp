#pragma once
/// The paper's fast closest-point update (§2.2.1): starting from the triangle of the previous
/// correspondence, walk over adjacent triangles while that brings the query closer.
#include "geometry/bvh.hpp"
#include "geometry/triangle_planes.hpp"
#include "mesh/topology.hpp"

namespace sm {

/// Local closest-point search on `mesh` (positions V, triangles F, connectivity topo) for the
/// query p, starting at triangle `start` (must be valid). At each step the closest point on the
/// current triangle decides where to look next: inside the face, the three edge neighbours are
/// tried (a point just inside a convex edge projects into both faces); on an edge, the neighbour
/// across it; at a corner, every triangle around that vertex. The walk
/// moves to the best candidate while it is strictly closer and stops after `max_steps` moves.
///
/// Returns true and the local minimum in `out` when the walk settled; false when it ran out of
/// steps — the caller must then use the exact query (TriangleBvh::closest), and `out` holds the
/// closest point seen so far, an upper bound to pass to it. An edge without a neighbour (boundary
/// or non-manifold) is treated like its two corners: every triangle around both endpoints is
/// tried. `planes`, when given, must hold the frames of (V, F): the face case is then answered by
/// TrianglePlanes::closest_in_face. Thread-safe, allocation-free.
bool walk_closest(const Positions& V, const Triangles& F, const Topology& topo, const Vec3& p,
                  int start, int max_steps, SurfacePoint& out,
                  const TrianglePlanes* planes = nullptr);

}  // namespace sm
