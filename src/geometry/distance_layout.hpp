#pragma once
/// The sampling layout of one_sided_distance for one connectivity: which triangle samples each
/// vertex and edge, and the undirected edges. It depends on the triangles alone, so a sequence
/// (whose frames share their connectivity) builds it once and reuses it for every frame.
#include <array>
#include <cstdint>
#include <vector>

#include "mesh/mesh.hpp"

namespace sm {

class DistanceLayout {
 public:
  DistanceLayout() = default;
  /// Layout of the triangles F (m×3) over n vertices; indices must be in [0, n) (validate_mesh).
  /// Linear: the half-edges are bucketed by their lower vertex, and each (small) bucket sorted.
  DistanceLayout(const Triangles& F, int num_vertices);

  /// True when this is the layout of exactly these triangles over this many vertices.
  bool fits(const Triangles& F, int num_vertices) const {
    return num_vertices == num_vertices_ && F.rows() == F_.rows() && F == F_;
  }

  int num_vertices() const { return num_vertices_; }
  int num_triangles() const { return static_cast<int>(F_.rows()); }
  int num_edges() const { return static_cast<int>(edges_.size()); }

  /// Per triangle: the corners (bits 0–2) and edges k → k+1 (bits 3–5) it samples: every vertex
  /// and every undirected edge belongs to the first triangle (lowest index, then lowest corner)
  /// using it.
  const std::vector<uint8_t>& owns() const { return owns_; }
  /// The undirected edges (lower vertex, higher vertex), in increasing order.
  const std::vector<std::array<int, 2>>& edges() const { return edges_; }
  /// The triangle that owns each vertex (n; −1 for a vertex no triangle uses).
  const std::vector<int>& vertex_owner() const { return vertex_owner_; }

  /// Mean length of the undirected edges at positions V (n×3), each edge once, summed in the
  /// order of edges() (so that it is mean_edge_length's value, bit for bit); 0 without edges.
  double mean_edge_length(const Positions& V) const;

 private:
  Triangles F_;
  int num_vertices_ = 0;
  std::vector<uint8_t> owns_;
  std::vector<std::array<int, 2>> edges_;
  std::vector<int> vertex_owner_;
};

}  // namespace sm
