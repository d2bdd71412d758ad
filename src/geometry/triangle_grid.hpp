#pragma once
/// Uniform grid over a mesh's triangles for exact closest-point queries near the surface (the
/// structure of the Metro tool behind the paper's Tables 1–3): a query tests the triangles of its
/// own cell, with the projection frames' cheap face case and lower bound, and is exact as soon
/// as the ball through the best point found stays within the cells it tested.
#include <array>
#include <vector>

#include "geometry/triangle_planes.hpp"
#include "mesh/mesh.hpp"

namespace sm {

class TriangleGrid {
 public:
  TriangleGrid() = default;
  /// Grid over the triangles F (m×3) of positions V (n×3), whose frames `planes` must be (and
  /// stay) those of (V, F); V, F and planes must outlive the grid. Cells are cubes of side about
  /// `cell` (> 0), enlarged if the mesh's box would need more than 8 cells per triangle. A
  /// triangle is listed in every cell its bounding box overlaps; one spanning more than 64 cells
  /// is tested by every query instead. With `topo` (F's connectivity; it must outlive the grid),
  /// a hint that settles in its face (TrianglePlanes::face_settles) spares the tests of its edge
  /// neighbours.
  TriangleGrid(const Positions& V, const Triangles& F, const TrianglePlanes& planes, double cell,
               const Topology* topo = nullptr) {
    build(V, F, planes, cell, topo);
  }

  /// Rebuilds the grid as the constructor does, reusing this grid's memory (a frame after frame
  /// allocates nothing once its arrays are large enough).
  void build(const Positions& V, const Triangles& F, const TrianglePlanes& planes, double cell,
             const Topology* topo = nullptr);

  /// Lowers best2 to the squared distance of the closest triangle of the mesh to p, and sets
  /// best_triangle to it, when one is strictly closer than sqrt(best2); `hint`, if >= 0, is
  /// tested first (e.g. the answer for a neighbouring query). Returns true when that answer is
  /// exact, false when it could not be decided within p's cell and its neighbours (p outside the
  /// grid, or farther from the mesh than a cell): the caller then asks an exact structure, such
  /// as TriangleBvh::closest with bound best2. Thread-safe: const, allocation-free.
  bool closest(const Vec3& p, double& best2, int& best_triangle, int hint = -1) const;

  /// Hints the processor to bring what closest(p) reads first into the cache, for a query a few
  /// steps ahead: `entries` false, the cell's offsets (p's cell is read at random); true, its
  /// first entries (read through the offsets, so after those have been fetched).
  void prefetch(const Vec3& p, bool entries) const;

  bool empty() const { return cells_.empty(); }
  double cell_size() const { return cell_; }

 private:
  int cell_index(int x, int y, int z) const { return (z * dims_[1] + y) * dims_[0] + x; }
  void scan(int cell, const Vec3& p, double& best2, int& best_triangle, const int* skip) const;
  // Steps of build(): the grid's cells over `box`, each triangle's cell range and float box with
  // the cells' entry counts, then the entries.
  void lay_out_cells(const Eigen::AlignedBox3d& box, double cell, int m);
  void count_entries(const Positions& V, const Triangles& F);
  void fill_entries();

  const Positions* V_ = nullptr;
  const Triangles* F_ = nullptr;
  const TrianglePlanes* planes_ = nullptr;
  const Topology* topo_ = nullptr;
  Vec3 origin_ = Vec3::Zero();
  double cell_ = 1.0, inv_cell_ = 1.0;
  int dims_[3] = {0, 0, 0};
  std::vector<int> cells_;  ///< CSR offsets, one more than there are cells
  /// Per entry of the cells: the triangle and its bounding box as centre and half extent (floats,
  /// the extent rounded up so that the box contains the triangle), one array per coordinate so
  /// that a cell's boxes are tested with SIMD before any triangle.
  std::vector<int> triangle_;
  std::vector<float> box_[6];
  double margin_ = 0.0;   ///< bound on the float box test's rounding error
  std::vector<int> big_;  ///< triangles tested by every query
  // Scratch of build(): each triangle's cell range and float box, the CSR fill cursors.
  std::vector<std::array<int, 6>> range_;
  std::vector<std::array<float, 6>> boxes_;
  std::vector<int> fill_;
};

}  // namespace sm
