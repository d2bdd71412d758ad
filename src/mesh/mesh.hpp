#pragma once
/// The plain triangle mesh every module works on: positions (n×3) and triangles (m×3).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

namespace sm {

using Vec3 = Eigen::Vector3d;
/// n×3 vertex positions, one row per vertex (row-major: x, y, z of a vertex are contiguous).
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// m×3 vertex indices, one row per triangle, counter-clockwise seen from outside.
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

struct TriMesh {
  Positions V;  ///< n×3
  Triangles F;  ///< m×3, indices into V

  int num_vertices() const { return static_cast<int>(V.rows()); }
  int num_triangles() const { return static_cast<int>(F.rows()); }
  Vec3 vertex(int i) const { return V.row(i).transpose(); }
};

/// Length of the diagonal of the axis-aligned bounding box of the vertices (0 for an empty mesh).
double bounding_box_diagonal(const Positions& V);

/// Mean length of the mesh's edges, each undirected edge counted once (0 for no triangles).
double mean_edge_length(const TriMesh& mesh);

/// Every undirected edge of F (m×3) once, as (lower vertex, higher vertex), in increasing order.
std::vector<std::array<int, 2>> unique_edges(const Triangles& F);

/// Mean length at positions V (n×3) of `edges`, summed in their order (with unique_edges(F):
/// mean_edge_length of (V, F), bit for bit); 0 without edges.
double mean_edge_length(const Positions& V, const std::vector<std::array<int, 2>>& edges);

/// Area of every triangle (m).
Eigen::VectorXd triangle_areas(const TriMesh& mesh);

/// Unit normal of every triangle (m×3); a degenerate triangle gets a zero row.
Positions triangle_normals(const TriMesh& mesh);

/// Area-weighted vertex normals (n×3), unit length; a vertex without area gets a zero row.
Positions vertex_normals(const TriMesh& mesh);

/// Throws InputError naming `what` if a triangle index is out of range or a coordinate is not
/// finite. Cheap (linear); called at every boundary where meshes enter the library.
void validate_mesh(const TriMesh& mesh, const char* what);

}  // namespace sm
