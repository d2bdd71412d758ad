#pragma once
/// Welding the glTF vertices that are split along UV and normal seams (or at every corner of a
/// non-indexed mesh) into one connectivity, by exactly equal rest positions.
#include <vector>

#include "mesh/mesh.hpp"

namespace sm {

struct GltfWeld {
  TriMesh mesh;               ///< welded vertices (rest positions) and welded triangles
  std::vector<int> map;       ///< glTF vertex -> welded vertex, -1 for a vertex in no triangle
  int merged = 0;             ///< referenced glTF vertices merged into an earlier copy
  int unreferenced = 0;       ///< glTF vertices in no triangle (left out of the welded mesh)
  int dropped_triangles = 0;  ///< triangles with a repeated welded vertex (zero area), left out
};

/// Welds the vertices of triangles F (glTF vertex ids into V) whose positions are equal
/// coordinate by coordinate (as decoded; -0 equals +0). Welded vertices are numbered in the order
/// of their first glTF copy.
GltfWeld weld_by_position(const Positions& V, const Triangles& F);

/// Positions of one frame on the welded vertices.
struct WeldedFrame {
  Positions V;                 ///< num_welded × 3: the mean of each vertex's glTF copies
  int separated_vertices = 0;  ///< welded vertices whose copies lie farther than the tolerance
  double max_separation = 0;   ///< largest distance of a copy from its welded vertex
};

/// Welds the positions of every glTF vertex (`map` from weld_by_position). Copies should coincide;
/// those farther than `tolerance` from their mean are counted, never fatal.
WeldedFrame weld_frame(const std::vector<int>& map, int num_welded, const Positions& gltf_positions,
                       double tolerance);

/// Positions of every glTF vertex from welded positions: each copy gets its welded vertex's
/// position; a vertex in no triangle gets its row of `fallback`.
Positions unweld_frame(const std::vector<int>& map, const Positions& welded,
                       const Positions& fallback);

}  // namespace sm
