#pragma once
/// Corresponding points between M and N (paper §2.2.1): v̂_i, the closest point of N to each
/// vertex of M, and ŵ_j, the closest point of M to each sample of N, kept up to date across
/// iterations by a local walk from the previous answer with an exact BVH query as fall-back.
#include <vector>

#include "geometry/bvh.hpp"
#include "mesh/topology.hpp"

namespace sm {

/// A surface to project onto: positions, triangles, connectivity and a BVH over the same positions.
struct SurfaceView {
  const Positions* V;
  const Triangles* F;
  const Topology* topology;
  const TriangleBvh* bvh;
};

/// Updates `corr[i]` to the closest point of `surface` to points.row(i), for every i, in parallel.
/// With `exact` (or where corr[i] has no triangle yet) the BVH answers; otherwise the walk from
/// corr[i].triangle with at most `max_steps` moves, and the BVH when the walk does not settle.
/// Returns the number of exact (BVH) queries. Deterministic whatever the thread count.
int update_correspondences(const SurfaceView& surface, const Positions& points, bool exact,
                           int max_steps, std::vector<SurfacePoint>& corr);

}  // namespace sm
