#pragma once
/// Quality and validity report of a triangle mesh: degenerate and duplicate triangles, duplicate
/// and isolated vertices, non-manifold edges and vertices, boundary loops.
#include <string>
#include <vector>

#include "mesh/mesh.hpp"
#include "mesh/topology.hpp"

namespace sm {

struct MeshReport {
  int vertices = 0;
  int triangles = 0;
  int degenerate_triangles = 0;  ///< repeated index or zero area
  int duplicate_triangles = 0;   ///< same three vertices as an earlier triangle (any order)
  int duplicate_vertices = 0;    ///< same position as an earlier vertex
  int isolated_vertices = 0;
  int nonmanifold_edges = 0;
  int nonmanifold_vertices = 0;
  int boundary_loops = 0;
  int euler_characteristic = 0;
  std::vector<int> degenerate_triangle_ids;  ///< at most the first 20, for messages

  bool ok_for_optimization() const {
    return degenerate_triangles == 0 && nonmanifold_edges == 0 && nonmanifold_vertices == 0;
  }
  /// One line, e.g. "1200 vertices, 2396 triangles, 1 boundary loop, 2 degenerate triangles (7, 9)".
  std::string describe() const;
};

/// Checks `mesh` (with its topology, if already built). Zero area means |cross| <= 1e-14 · diag².
MeshReport check_mesh(const TriMesh& mesh, const Topology& topo);
MeshReport check_mesh(const TriMesh& mesh);

}  // namespace sm
