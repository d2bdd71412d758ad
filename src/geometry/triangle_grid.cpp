#include "geometry/triangle_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "geometry/float_bounds.hpp"
#include "core/errors.hpp"

namespace sm {
namespace {

constexpr double kMaxCellsPerTriangle = 8.0;
constexpr long kMaxCellsPerEntry = 64;
constexpr int kChunk = 64;  // boxes tested per SIMD pass

}  // namespace

void TriangleGrid::build(const Positions& V, const Triangles& F, const TrianglePlanes& planes,
                         double cell, const Topology* topo) {
  const int m = static_cast<int>(F.rows());
  if (planes.size() != m || !(cell > 0.0) || !std::isfinite(cell)) {
    std::ostringstream msg;
    msg << "TriangleGrid: " << planes.size() << " frames for " << m << " triangles, cell " << cell;
    throw InputError(msg.str());
  }
  V_ = &V;
  F_ = &F;
  planes_ = &planes;
  topo_ = topo && topo->num_triangles == F.rows() ? topo : nullptr;
  cells_.clear();
  big_.clear();
  if (m == 0) return;
  Eigen::AlignedBox3d box;
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) box.extend(V.row(F(t, k)).transpose());
  lay_out_cells(box, cell, m);
  count_entries(V, F);
  fill_entries();
  // The float box distance is off by a few units in the last place of the coordinates.
  const double scale = std::max(box.min().cwiseAbs().maxCoeff(), box.max().cwiseAbs().maxCoeff());
  margin_ = 1e-6 * (scale + cell_);
}

void TriangleGrid::lay_out_cells(const Eigen::AlignedBox3d& box, double cell, int m) {
  // One cell of margin on every side, so that queries just off the mesh's box have a cell.
  const Vec3 extent = box.sizes();
  // Enlarge the cells while the grid would be too large for the mesh.
  for (;;) {
    double count = 1.0;
    for (int a = 0; a < 3; ++a) count *= std::floor(extent[a] / cell) + 3.0;
    if (count <= kMaxCellsPerTriangle * m + 4096.0) break;
    cell *= std::cbrt(count / (kMaxCellsPerTriangle * m + 4096.0)) * 1.01;
  }
  cell_ = cell;
  inv_cell_ = 1.0 / cell;
  origin_ = box.min().array() - cell;
  for (int a = 0; a < 3; ++a) dims_[a] = static_cast<int>(std::floor(extent[a] * inv_cell_)) + 3;
}

void TriangleGrid::count_entries(const Positions& V, const Triangles& F) {
  // Cell ranges of every triangle's box; counting sort into CSR, triangles in index order.
  const int m = static_cast<int>(F.rows());
  std::vector<std::array<int, 6>>& range = range_;
  range.resize(m);
  cells_.assign(long(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
  std::vector<std::array<float, 6>>& boxes = boxes_;
  boxes.resize(m);
  for (int t = 0; t < m; ++t) {
    Eigen::AlignedBox3d tb;
    for (int k = 0; k < 3; ++k) tb.extend(V.row(F(t, k)).transpose());
    for (int a = 0; a < 3; ++a) {  // [centre − half, centre + half] contains the box
      const double lo = tb.min()[a], hi = tb.max()[a];
      const float centre = static_cast<float>(0.5 * (lo + hi));
      boxes[t][a] = centre;
      boxes[t][3 + a] = float_at_least(std::max(hi - centre, centre - lo));
    }
    long count = 1;
    for (int a = 0; a < 3; ++a) {
      range[t][a] = std::clamp(static_cast<int>(std::floor((tb.min()[a] - origin_[a]) * inv_cell_)),
                               0, dims_[a] - 1);
      range[t][3 + a] = std::clamp(
          static_cast<int>(std::floor((tb.max()[a] - origin_[a]) * inv_cell_)), 0, dims_[a] - 1);
      count *= range[t][3 + a] - range[t][a] + 1;
    }
    if (count > kMaxCellsPerEntry) {
      big_.push_back(t);
      range[t][0] = -1;
      continue;
    }
    for (int z = range[t][2]; z <= range[t][5]; ++z)
      for (int y = range[t][1]; y <= range[t][4]; ++y)
        for (int x = range[t][0]; x <= range[t][3]; ++x) ++cells_[cell_index(x, y, z) + 1];
  }
}

void TriangleGrid::fill_entries() {
  const long num_cells = static_cast<long>(cells_.size()) - 1;
  const std::vector<std::array<int, 6>>& range = range_;
  for (long c = 0; c < num_cells; ++c) cells_[c + 1] += cells_[c];
  const int entries = cells_[num_cells];
  triangle_.resize(entries);
  for (std::vector<float>& b : box_) b.resize(entries);
  std::vector<int>& fill = fill_;
  fill.assign(cells_.begin(), cells_.end() - 1);
  // Scatter the triangles into their cells, then copy their boxes in entry order (one scattered
  // write per entry instead of seven).
  for (size_t t = 0; t < range.size(); ++t) {
    if (range[t][0] < 0) continue;
    for (int z = range[t][2]; z <= range[t][5]; ++z)
      for (int y = range[t][1]; y <= range[t][4]; ++y)
        for (int x = range[t][0]; x <= range[t][3]; ++x)
          triangle_[fill[cell_index(x, y, z)]++] = static_cast<int>(t);
  }
  for (int e = 0; e < entries; ++e) {
    const std::array<float, 6>& b = boxes_[triangle_[e]];
    for (int a = 0; a < 6; ++a) box_[a][e] = b[a];
  }
}

void TriangleGrid::scan(int cell, const Vec3& p, double& best2, int& best_triangle,
                        const int* skip) const {
  const float px = static_cast<float>(p.x()), py = static_cast<float>(p.y()),
              pz = static_cast<float>(p.z());
  // A box farther than the best distance (plus the float test's error) cannot hold a closer point.
  auto threshold = [&] {
    const double r = std::sqrt(best2) + margin_;
    return r * r < 3e38 ? static_cast<float>(r * r) : std::numeric_limits<float>::infinity();
  };
  float limit = threshold();
  float d2[kChunk];
  TrianglePoint tp;
  for (int begin = cells_[cell], end = cells_[cell + 1]; begin < end; begin += kChunk) {
    const int count = std::min(kChunk, end - begin);
    const float *cx = &box_[0][begin], *cy = &box_[1][begin], *cz = &box_[2][begin];
    const float *hx = &box_[3][begin], *hy = &box_[4][begin], *hz = &box_[5][begin];
    // Distance beyond the box along an axis: (d + |d|) / 2 with d = |p − centre| − half,
    // branch-free so that the loop vectorizes.
#pragma omp simd
    for (int i = 0; i < count; ++i) {
      const float dx = std::fabs(px - cx[i]) - hx[i];
      const float dy = std::fabs(py - cy[i]) - hy[i];
      const float dz = std::fabs(pz - cz[i]) - hz[i];
      const float ox = 0.5f * (dx + std::fabs(dx)), oy = 0.5f * (dy + std::fabs(dy)),
                  oz = 0.5f * (dz + std::fabs(dz));
      d2[i] = ox * ox + oy * oy + oz * oz;
    }
    // The boxes within reach, then their frames fetched together: the frames are read at
    // random, and waiting for one cache miss after the other dominated the scan. The limit only
    // shrinks, so testing it again below tests exactly the triangles tested one by one.
    int near[kChunk];
    int num_near = 0;
    for (int i = 0; i < count; ++i) {
      near[num_near] = i;
      num_near += d2[i] < limit;
    }
    for (int k = 0; k < num_near; ++k) planes_->prefetch(triangle_[begin + near[k]]);
    for (int k = 0; k < num_near; ++k) {
      const int i = near[k];
      if (!(d2[i] < limit)) continue;
      const int t = triangle_[begin + i];
      if (t == best_triangle || t == skip[0] || t == skip[1] || t == skip[2]) continue;
      if (planes_->closer_than(t, p, best2, *V_, *F_, tp)) {
        best2 = tp.dist2;
        best_triangle = t;
        limit = threshold();
      }
    }
  }
}

void TriangleGrid::prefetch(const Vec3& p, bool entries) const {
  if (cells_.empty()) return;
  int c[3];
  for (int a = 0; a < 3; ++a) {
    const double g = (p[a] - origin_[a]) * inv_cell_;
    if (!(g >= 0.0 && g < dims_[a])) return;
    c[a] = static_cast<int>(g);
  }
  const int cell = cell_index(c[0], c[1], c[2]);
  if (!entries) {
    __builtin_prefetch(&cells_[cell]);
    return;
  }
  const int begin = cells_[cell];
  if (begin == cells_[cell + 1]) return;
  __builtin_prefetch(&triangle_[begin]);
  for (const std::vector<float>& b : box_) __builtin_prefetch(&b[begin]);
}

bool TriangleGrid::closest(const Vec3& p, double& best2, int& best_triangle, int hint) const {
  if (cells_.empty()) return false;
  TrianglePoint tp;
  int skip[3] = {-1, -1, -1};  // edge neighbours of a hint that settles in its face
  if (hint >= 0 && hint != best_triangle && planes_->closer_than(hint, p, best2, *V_, *F_, tp)) {
    best2 = tp.dist2;
    best_triangle = hint;
    if (topo_ && tp.region == TriangleRegion::Face && planes_->face_settles(hint, p, tp.bary))
      for (int k = 0; k < 3; ++k) skip[k] = topo_->triangle_neighbours[hint][k];
  }
  for (int t : big_)
    if (t != best_triangle && planes_->closer_than(t, p, best2, *V_, *F_, tp)) {
      best2 = tp.dist2;
      best_triangle = t;
    }
  int c[3];
  double g[3];
  for (int a = 0; a < 3; ++a) {
    g[a] = (p[a] - origin_[a]) * inv_cell_;
    if (!(g[a] >= 0.0 && g[a] < dims_[a])) return false;  // outside the grid (or NaN)
    c[a] = static_cast<int>(g[a]);
  }
  scan(cell_index(c[0], c[1], c[2]), p, best2, best_triangle, skip);
  // The ball through the best point within p's cell: nothing else to test.
  double wall = 1.0;
  for (int a = 0; a < 3; ++a) wall = std::min({wall, g[a] - c[a], c[a] + 1.0 - g[a]});
  const double in_cell = (wall - 1e-9) * cell_;
  if (in_cell > 0.0 && best2 < in_cell * in_cell) return true;
  // Every triangle with a point strictly inside the ball of radius sqrt(best2) around p is
  // listed in a cell the ball overlaps: test those cells too, if they are p's neighbours. When
  // the ball still reaches beyond them, testing all the neighbours may shrink it enough.
  int lo[3], hi[3];
  auto ball_cells = [&] {
    const double r = std::sqrt(best2);
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      // Padded by 1e-9 cells against rounding; beyond the grid there are no triangles.
      const double glo = (p[a] - r - origin_[a]) * inv_cell_ - 1e-9;
      const double ghi = (p[a] + r - origin_[a]) * inv_cell_ + 1e-9;
      lo[a] = glo > 0.0 ? (glo < c[a] ? static_cast<int>(glo) : c[a]) : 0;
      hi[a] = ghi < dims_[a] ? (ghi > c[a] ? static_cast<int>(ghi) : c[a]) : dims_[a] - 1;
      if (lo[a] < c[a] - 1 || hi[a] > c[a] + 1) {
        inside = false;
        lo[a] = std::max(c[a] - 1, 0);
        hi[a] = std::min(c[a] + 1, dims_[a] - 1);
      }
    }
    return inside;
  };
  const bool inside = ball_cells();
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x)
        if (x != c[0] || y != c[1] || z != c[2])
          scan(cell_index(x, y, z), p, best2, best_triangle, skip);
  return inside || ball_cells();
}

}  // namespace sm
