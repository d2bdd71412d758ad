#include "geometry/distance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "geometry/triangle_grid.hpp"
#include "mesh/errors.hpp"

namespace sm {
namespace {

// Bounds on the subdivisions of one edge and one triangle, so that a single huge triangle in a
// finely meshed model cannot ask for billions of samples.
constexpr long kMaxEdgeSegments = 1 << 20;
constexpr long kMaxFaceDivisions = 1 << 12;

struct Partial {
  double max = 0.0, sum = 0.0, sum2 = 0.0;
  long count = 0;
};

long divisions(double length, double h, long cap) {
  if (!(h > 0.0)) return 1;
  return std::clamp(static_cast<long>(std::ceil(length / h)), 1L, cap);
}

// Which corners (bits 0–2) and edges k → k+1 (bits 3–5) each triangle samples: every vertex and
// every undirected edge belongs to the first triangle (lowest index, then lowest corner) using it.
// Also the mean edge length, each undirected edge once, summed in the order of (lower vertex,
// higher vertex) as mean_edge_length does (so the value is the same, bit for bit). Linear: the
// half-edges are bucketed by their lower vertex, and each (small) bucket sorted.
struct Sampling {
  std::vector<uint8_t> owns;
  double mean_edge = 0.0;
};

Sampling sampling(const TriMesh& A, bool edges) {
  const int n = A.num_vertices(), m = A.num_triangles();
  Sampling out;
  out.owns.assign(m, 0);
  std::vector<uint8_t> seen(n, 0);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k)
      if (!seen[A.F(t, k)]) {
        seen[A.F(t, k)] = 1;
        out.owns[t] |= uint8_t(1u << k);
      }
  std::vector<int> start(n + 1, 0);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) ++start[std::min(A.F(t, k), A.F(t, (k + 1) % 3)) + 1];
  for (int v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<std::pair<int, int>> entries(3 * static_cast<size_t>(m));  // (higher vertex, 3t+k)
  std::vector<int> cursor(start.begin(), start.end() - 1);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = A.F(t, k), b = A.F(t, (k + 1) % 3);
      entries[cursor[std::min(a, b)]++] = {std::max(a, b), 3 * t + k};
    }
  double sum = 0.0;
  long count = 0;
  for (int a = 0; a < n; ++a) {
    const auto first = entries.begin() + start[a], last = entries.begin() + start[a + 1];
    std::sort(first, last);
    for (auto e = first; e != last; ++e) {
      if (e != first && (e - 1)->first == e->first) continue;
      if (edges) out.owns[e->second / 3] |= uint8_t(8u << (e->second % 3));
      sum += (A.V.row(a) - A.V.row(e->first)).norm();
      ++count;
    }
  }
  out.mean_edge = count > 0 ? sum / static_cast<double>(count) : 0.0;
  return out;
}

// The grid's cell: the mean edge length of B's triangles (each triangle's three edges).
double cell_size(const Positions& V, const Triangles& F) {
  double sum = 0.0;
  for (int t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) sum += (V.row(F(t, k)) - V.row(F(t, (k + 1) % 3))).norm();
  const double mean = sum / (3.0 * static_cast<double>(F.rows()));
  return mean > 0.0 && std::isfinite(mean) ? mean : 1.0;
}

}  // namespace

DistanceStats one_sided_distance(const TriMesh& A, const TriangleBvh& B,
                                 const DistanceOptions& options, const TrianglePlanes* planes_b,
                                 const Topology* topology_b) {
  validate_mesh(A, "one_sided_distance (A)");
  if (!(options.spacing > 0.0) || !std::isfinite(options.spacing)) {
    std::ostringstream msg;
    msg << "DistanceOptions::spacing must be a positive number, not " << options.spacing;
    throw ConfigError(msg.str());
  }
  DistanceStats stats;
  const int m = A.num_triangles();
  if (m == 0) return stats;
  if (B.empty()) throw InputError("one_sided_distance: the mesh B has no triangles");
  const Positions& VB = B.positions();
  const Triangles& FB = B.triangles();
  TrianglePlanes own_planes;
  if (!planes_b || planes_b->size() != FB.rows()) {
    own_planes.update(VB, FB, topology_b);
    planes_b = &own_planes;
  }
  const TriangleGrid grid(VB, FB, *planes_b, cell_size(VB, FB), topology_b);

  const Sampling layout = sampling(A, options.sample_edges);
  const std::vector<uint8_t>& owns = layout.owns;
  const double h = options.spacing * layout.mean_edge;
  std::vector<Partial> partial(m);

  tbb::parallel_for(tbb::blocked_range<int>(0, m, 256), [&](const tbb::blocked_range<int>& r) {
    for (int t = r.begin(); t != r.end(); ++t) {
      Partial& acc = partial[t];
      const Vec3 p[3] = {A.vertex(A.F(t, 0)), A.vertex(A.F(t, 1)), A.vertex(A.F(t, 2))};
      // Consecutive samples are close: the previous one's triangle is tried first (the first
      // sample tries the corresponding triangle of B, if there is one).
      int hint = options.corresponding_triangles && t < FB.rows() ? t : -1;
      auto sample = [&](const Vec3& q) {
        double best2 = std::numeric_limits<double>::infinity();
        int best = -1;
        if (!grid.closest(q, best2, best, hint)) {
          const SurfacePoint sp = B.closest(q, best2);
          if (sp.triangle >= 0) {
            best2 = sp.dist2;
            best = sp.triangle;
          }
        }
        hint = best;
        const double d = std::sqrt(best2);
        acc.max = std::max(acc.max, d);
        acc.sum += d;
        acc.sum2 += best2;
        ++acc.count;
      };
      for (int k = 0; k < 3; ++k)
        if (owns[t] & (1u << k)) sample(p[k]);
      for (int k = 0; k < 3; ++k) {
        if (!(owns[t] & (8u << k))) continue;
        const Vec3& a = p[k];
        const Vec3 e = p[(k + 1) % 3] - a;
        const long segments = divisions(e.norm(), h, kMaxEdgeSegments);
        for (long j = 1; j < segments; ++j) sample(a + (double(j) / double(segments)) * e);
      }
      if (!options.sample_faces) continue;
      const double longest =
          std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
      const long n = divisions(longest, h, kMaxFaceDivisions);
      if (n < 3) {
        sample((p[0] + p[1] + p[2]) / 3.0);
        continue;
      }
      // Interior lattice points (i, j, n − i − j) / n with all three coordinates ≥ 1/n, visited
      // row by row in a serpentine order so that consecutive samples stay neighbours.
      for (long i = 1; i <= n - 2; ++i) {
        const long count = n - 1 - i;
        for (long s = 0; s < count; ++s) {
          const long j = (i % 2 == 1) ? 1 + s : count - s;
          const double u = double(i) / double(n), v = double(j) / double(n);
          sample(u * p[0] + v * p[1] + (1.0 - u - v) * p[2]);
        }
      }
    }
  });

  double sum = 0.0, sum2 = 0.0;
  for (const Partial& acc : partial) {
    stats.max = std::max(stats.max, acc.max);
    sum += acc.sum;
    sum2 += acc.sum2;
    stats.samples += acc.count;
  }
  stats.mean = sum / static_cast<double>(stats.samples);
  stats.rms = std::sqrt(sum2 / static_cast<double>(stats.samples));

  Eigen::RowVector3d lo = A.V.colwise().minCoeff(), hi = A.V.colwise().maxCoeff();
  if (VB.rows() > 0) {
    lo = lo.cwiseMin(VB.colwise().minCoeff());
    hi = hi.cwiseMax(VB.colwise().maxCoeff());
  }
  const double diagonal = (hi - lo).norm();
  if (diagonal > 0.0) {
    stats.max_rel = stats.max / diagonal;
    stats.mean_rel = stats.mean / diagonal;
    stats.rms_rel = stats.rms / diagonal;
  }
  return stats;
}

double symmetric_hausdorff(const DistanceStats& a_to_b, const DistanceStats& b_to_a) {
  return std::max(a_to_b.max, b_to_a.max);
}

}  // namespace sm
