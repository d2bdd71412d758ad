#pragma once
/// Bounding volume hierarchy over a mesh's triangles for exact closest-point queries (the
/// fall-back of the paper's local search, §2.2.1). Built once per connectivity; refit() updates
/// the boxes in O(m) when only the positions change (the optimized mesh M between iterations).
#include <limits>
#include <vector>

#include "mesh/mesh.hpp"

namespace sm {

/// A point on a mesh: triangle index, barycentric coordinates, position, squared distance to the
/// query that produced it. triangle == -1 means "none found".
struct SurfacePoint {
  int triangle = -1;
  Vec3 bary = Vec3::Zero();
  Vec3 point = Vec3::Zero();
  double dist2 = std::numeric_limits<double>::infinity();
};

class TriangleBvh {
 public:
  TriangleBvh() = default;
  /// Builds the hierarchy over mesh.F with positions mesh.V (both copied). O(m log m).
  explicit TriangleBvh(const TriMesh& mesh);

  /// New positions for the same vertices (n×3): recompute every box bottom-up, keep the tree.
  void refit(const Positions& V);

  /// Exact closest point of the mesh to p. Only candidates closer than sqrt(max_dist2) are
  /// considered (pass a known upper bound to prune); returns triangle == -1 if there is none.
  /// Thread-safe: const and allocation-free.
  SurfacePoint closest(const Vec3& p,
                       double max_dist2 = std::numeric_limits<double>::infinity()) const;

  const Positions& positions() const { return V_; }
  const Triangles& triangles() const { return F_; }
  bool empty() const { return nodes_.empty(); }

 private:
  /// An inner node holds the boxes of its two children (floats rounded outwards), so that one
  /// traversal step reads one cache line. Node 0 is the root; a mesh of at most 4 triangles
  /// gets a root with one leaf and one empty child.
  struct alignas(64) Node {
    float lo[2][3];
    float hi[2][3];
    int child[2];  ///< >= 0: inner node index; < 0: leaf ~(first << 3 | count) over order_
  };
  void build(int node, int first, int count, std::vector<Vec3>& centroids);
  Positions V_;
  Triangles F_;
  std::vector<Node> nodes_;
  std::vector<int> order_;     ///< triangle ids, leaves refer to ranges of it
  std::vector<Vec3> corners_;  ///< 3 corners per entry of order_, contiguous for the leaves
};

}  // namespace sm
