#pragma once
/// An embedded deformation graph on a template (Sumner et al. 2007): nodes sampled on the
/// template's surface, each carrying an affine map, blended at every vertex by weights that fall
/// off with the geodesic (edge-path) distance to the node. The tracker fits it to a raw frame.
///
/// Vertex i of the template (position v_i) deforms to
///   v_i' = Σ_j w_ij [A_j (v_i − g_j) + g_j + t_j]
/// with node j at g_j, its 3×3 map A_j and translation t_j; written X_j = [A_j | t_j] (3×4),
/// v_i' = Σ_j X_j a_ij + Σ_j w_ij g_j with a_ij = w_ij [v_i − g_j; 1] (the fit's linear form).
#include <array>
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.hpp"
#include "mesh/topology.hpp"

namespace sm {

/// One node's map X_j = [A_j | t_j]: row c maps to output coordinate c.
using NodeMap = Eigen::Matrix<double, 3, 4>;

class DeformationGraph {
 public:
  DeformationGraph() = default;
  /// Nodes by geodesic Poisson-disk sampling of the vertices (visited in a fixed pseudo-random
  /// order) with spacing `spacing` (model units); each vertex is influenced by its at most
  /// `max_influences` nearest nodes within 2 × spacing along the edges, weight (1 − d / 2s)²,
  /// normalised. Every vertex in a triangle is within `spacing` of a node. Two nodes are linked
  /// when they influence a common vertex.
  DeformationGraph(const TriMesh& templ, const Topology& topology, double spacing,
                   int max_influences = 6);

  int num_nodes() const { return static_cast<int>(node_vertex_.size()); }
  int num_vertices() const { return static_cast<int>(offsets_.size()) - 1; }
  /// The template vertex each node sits on.
  const std::vector<int>& node_vertices() const { return node_vertex_; }
  const Positions& node_positions() const { return g_; }  ///< N×3
  /// Influences of vertex i: nodes and weights [begin(i), end(i)).
  int begin(int i) const { return offsets_[i]; }
  int end(int i) const { return offsets_[i + 1]; }
  int node(int k) const { return nodes_[k]; }
  double weight(int k) const { return weights_[k]; }
  /// The 4-vector a_ij = w_ij [v_i − g_j; 1] of influence k.
  const Eigen::Vector4d& coefficient(int k) const { return coeff_[k]; }
  /// Σ_j w_ij g_j of vertex i (equal to v_i up to the blending).
  Vec3 base(int i) const { return base_.row(i).transpose(); }
  /// Graph edges (j < k), each once.
  const std::vector<std::array<int, 2>>& edges() const { return edges_; }

  /// The deformed vertex positions (n×3) for node maps X (N of them).
  Positions deform(const std::vector<NodeMap>& X) const;
  /// Identity maps.
  std::vector<NodeMap> identity() const;

 private:
  std::vector<int> node_vertex_;
  Positions g_;
  std::vector<int> offsets_{0};
  std::vector<int> nodes_;
  std::vector<double> weights_;
  std::vector<Eigen::Vector4d> coeff_;
  Positions base_;
  std::vector<std::array<int, 2>> edges_;
};

}  // namespace sm
