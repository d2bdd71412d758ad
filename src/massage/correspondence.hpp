#pragma once
/// Corresponding points between M and N (paper §2.2.1): v̂_i, the closest point of N to each
/// vertex of M, and ŵ_j, the closest point of M to each sample of N, kept up to date across
/// iterations by a local walk from the previous answer with an exact BVH query as fall-back.
#include <functional>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/triangle_planes.hpp"
#include "mesh/topology.hpp"

namespace sm {

/// A surface to project onto: positions, triangles, connectivity, a BVH over the same positions
/// (it may be brought up to date lazily, see update_correspondences) and, optionally, the
/// triangles' projection frames for the walk's face case.
struct SurfaceView {
  const Positions* V;
  const Triangles* F;
  const Topology* topology;
  const TriangleBvh* bvh;
  const TrianglePlanes* planes = nullptr;
};

/// Updates `corr[i]` to the closest point of `surface` to points.row(i), for every i, in parallel.
/// Where corr[i] has a triangle it is the starting point: without `exact`, the walk from it with
/// at most `max_steps` moves, and the BVH when the walk does not settle; with `exact`, the BVH,
/// pruned by the distance to that triangle (the answer is exact either way). Where corr[i] has
/// no triangle, the BVH unpruned. An answer at distance 0 needs no BVH. `before_exact`, if given,
/// is called once before the first BVH query (e.g. to refit the BVH only when it is needed).
/// Returns the number of BVH queries. Deterministic whatever the thread count.
int update_correspondences(const SurfaceView& surface, const Positions& points, bool exact,
                           int max_steps, std::vector<SurfacePoint>& corr,
                           const std::function<void()>& before_exact = {});

}  // namespace sm
