#pragma once
/// Both one-sided distances between a frame and a moved copy of it (the same triangles), for the
/// many frames of one connectivity: the sampling layout of the triangles is built once, and the
/// scratch memory (triangle grid, adaptive samples' distances, the moved copy's BVH and
/// projection frames) is pooled, so that frames measured one after another, or several at once,
/// do not allocate it anew. The results are one_sided_distance's, exactly.
#include <memory>

#include "geometry/bvh.hpp"
#include "geometry/distance_options.hpp"
#include "geometry/distance_layout.hpp"
#include "geometry/distance_workspace.hpp"
#include "geometry/triangle_planes.hpp"
#include "mesh/mesh.hpp"
#include "mesh/topology.hpp"

namespace sm {

/// The two directions of a frame pair.
struct FrameDistances {
  DistanceStats moved_to_original;  ///< the moved copy sampled, to the original's surface
  DistanceStats original_to_moved;  ///< the original sampled, to the moved copy's surface
};

class DistanceMeter {
 public:
  /// For frames with triangles F (m×3) over `num_vertices` vertices, whose connectivity is
  /// `topology` (may be null), sampled as `options` says.
  DistanceMeter(const Triangles& F, int num_vertices, std::shared_ptr<const Topology> topology,
                DistanceOptions options);

  /// `original` (triangles F) with its BVH and projection frames (e.g. a Reference's), and its
  /// moved positions `moved` (n×3): the moved copy's BVH is the original's refitted. Thread-safe.
  FrameDistances measure(const TriMesh& original, const TriangleBvh& original_bvh,
                         const TrianglePlanes& original_planes, const Positions& moved) const;

 private:
  DistanceLayout layout_;
  std::shared_ptr<const Topology> topology_;
  DistanceOptions options_;
  std::unique_ptr<DistanceWorkspaces> pool_;  // one workspace per frame being measured
};

}  // namespace sm
