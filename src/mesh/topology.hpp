#pragma once
/// Connectivity of a triangle mesh: vertex→triangle incidence, triangle adjacency across edges,
/// ordered one-rings, boundary flags and boundary loops. Built once per connectivity.
#include <array>
#include <cstdint>
#include <vector>

#include "mesh/mesh.hpp"

namespace sm {

/// Compressed rows: the entries of row i are data[offsets[i] .. offsets[i+1]).
struct Csr {
  std::vector<int> offsets{0};
  std::vector<int> data;
  int rows() const { return static_cast<int>(offsets.size()) - 1; }
  int begin(int i) const { return offsets[i]; }
  int end(int i) const { return offsets[i + 1]; }
  int size(int i) const { return offsets[i + 1] - offsets[i]; }
};

struct Topology {
  int num_vertices = 0;
  int num_triangles = 0;
  /// Triangles incident to each vertex (n rows), ordered like `one_ring` where the vertex is manifold.
  Csr vertex_triangles;
  /// Neighbours of each vertex (n rows). For a manifold vertex they are in counter-clockwise
  /// order; for a boundary vertex the ring starts and ends at its two boundary neighbours.
  Csr one_ring;
  /// For triangle t and local edge k (from F(t,k) to F(t,(k+1)%3)), the triangle across that
  /// edge, or -1 on a boundary or non-manifold edge. m×3.
  std::vector<std::array<int, 3>> triangle_neighbours;
  std::vector<uint8_t> is_boundary_vertex;  ///< n flags
  /// Closed boundary loops as vertex lists, each following the boundary half-edges' direction.
  std::vector<std::vector<int>> boundary_loops;
  int num_edges = 0;
  int num_boundary_edges = 0;
  int num_nonmanifold_edges = 0;     ///< edges with more than two triangles or opposite orientation
  int num_nonmanifold_vertices = 0;  ///< vertices whose triangles form more than one fan
  int num_isolated_vertices = 0;     ///< vertices in no triangle

  bool is_manifold() const { return num_nonmanifold_edges == 0 && num_nonmanifold_vertices == 0; }
  /// Euler characteristic V - E + F over the referenced vertices.
  int euler_characteristic() const {
    return (num_vertices - num_isolated_vertices) - num_edges + num_triangles;
  }
};

/// Builds the connectivity of `mesh`. Never throws on bad topology: non-manifold edges and
/// vertices are counted (and such edges get no neighbour), so callers decide what to reject.
/// Triangle indices must be in range (see validate_mesh).
Topology build_topology(const TriMesh& mesh);

}  // namespace sm
