#include "geometry/distance.hpp"
#include "geometry/distance_meter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "geometry/distance_keys.hpp"
#include "geometry/sample_budget.hpp"
#include "geometry/triangle_grid.hpp"
#include "core/errors.hpp"

namespace sm {
namespace {

// Samples of the adaptive coarse pass per task, in index order (fixed, so that nothing depends
// on the number of threads).
constexpr int kCoarseChunk = 512;
// How many points ahead the coarse pass fetches grid cells.
constexpr int kFetchAhead = 4;

struct Partial {
  double max = 0.0, sum = 0.0, sum2 = 0.0;
  long count = 0;
};

// In floating point, then clamped (sample_budget.hpp): length / h may exceed any integer.
long divisions(double length, double h, long cap) {
  return sample_divisions(length, h, cap);
}

// The grid's cell: the mean edge length of B's triangles (each triangle's three edges).
double cell_size(const Positions& V, const Triangles& F) {
  double sum = 0.0;
  for (int t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) sum += (V.row(F(t, k)) - V.row(F(t, (k + 1) % 3))).norm();
  const double mean = sum / (3.0 * static_cast<double>(F.rows()));
  return mean > 0.0 && std::isfinite(mean) ? mean : 1.0;
}

// Exact squared distance from q to B: the grid answers near B, the BVH elsewhere. `hint` is the
// triangle tried first (or −1) and becomes the closest one.
struct ExactQuery {
  const TriangleGrid& grid;
  const TriangleBvh& B;
  double operator()(const Vec3& q, int& hint) const {
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
    return best2;
  }
};

// The points of triangle p at spacing h: the interior points of the edges k → k+1 whose bit
// (8 << k) is set in `edges`, then, with `faces`, the interior lattice points, visited row by row
// in a serpentine order so that consecutive samples stay neighbours, or the centroid when the
// lattice has none (and `centroid`).
template <class Sample>
void sample_triangle(const Vec3 (&p)[3], unsigned edges, bool faces, bool centroid, double h,
                     Sample&& sample) {
  for (int k = 0; k < 3; ++k) {
    if (!(edges & (8u << k))) continue;
    const Vec3& a = p[k];
    const Vec3 e = p[(k + 1) % 3] - a;
    const long segments = divisions(e.norm(), h, kMaxEdgeSegments);
    for (long j = 1; j < segments; ++j) sample(a + (double(j) / double(segments)) * e);
  }
  if (!faces) return;
  const double longest =
      std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
  const long n = divisions(longest, h, kMaxFaceDivisions);
  if (n < 3) {
    if (centroid) sample((p[0] + p[1] + p[2]) / 3.0);
    return;
  }
  // Interior lattice points (i, j, n − i − j) / n with all three coordinates ≥ 1/n.
  for (long i = 1; i <= n - 2; ++i) {
    const long count = n - 1 - i;
    for (long s = 0; s < count; ++s) {
      const long j = (i % 2 == 1) ? 1 + s : count - s;
      const double u = double(i) / double(n), v = double(j) / double(n);
      sample(u * p[0] + v * p[1] + (1.0 - u - v) * p[2]);
    }
  }
}

DistanceStats uniform_distance(const TriMesh& A, const ExactQuery& query,
                               const DistanceLayout& layout, const DistanceOptions& options,
                               int triangles_b) {
  const int m = A.num_triangles();
  const std::vector<uint8_t>& owns = layout.owns();
  const double h = options.spacing * layout.mean_edge_length(A.V);
  std::vector<Partial> partial(m);
  tbb::parallel_for(tbb::blocked_range<int>(0, m, 256), [&](const tbb::blocked_range<int>& r) {
    for (int t = r.begin(); t != r.end(); ++t) {
      Partial& acc = partial[t];
      const Vec3 p[3] = {A.vertex(A.F(t, 0)), A.vertex(A.F(t, 1)), A.vertex(A.F(t, 2))};
      // Consecutive samples are close: the previous one's triangle is tried first (the first
      // sample tries the corresponding triangle of B, if there is one).
      int hint = options.corresponding_triangles && t < triangles_b ? t : -1;
      auto sample = [&](const Vec3& q) {
        const double d2 = query(q, hint);
        const double d = std::sqrt(d2);
        acc.max = std::max(acc.max, d);
        acc.sum += d;
        acc.sum2 += d2;
        ++acc.count;
      };
      for (int k = 0; k < 3; ++k)
        if (owns[t] & (1u << k)) sample(p[k]);
      sample_triangle(p, options.sample_edges ? owns[t] : 0u, options.sample_faces, true, h,
                      sample);
    }
  });
  DistanceStats stats;
  double sum = 0.0, sum2 = 0.0;
  for (const Partial& acc : partial) {
    stats.max = std::max(stats.max, acc.max);
    sum += acc.sum;
    sum2 += acc.sum2;
    stats.samples += acc.count;
  }
  stats.mean = sum / static_cast<double>(stats.samples);
  stats.rms = std::sqrt(sum2 / static_cast<double>(stats.samples));
  return stats;
}

// Exact distances of `count` points, in fixed chunks of consecutive indices; point(i) gives the
// i-th point and its first triangle to try (or −1: the previous point's closest triangle).
template <class Point>
void coarse_samples(int count, std::vector<double>& out, const ExactQuery& query, Point&& point) {
  out.resize(count);
  const int chunks = (count + kCoarseChunk - 1) / kCoarseChunk;
  tbb::parallel_for(tbb::blocked_range<int>(0, chunks), [&](const tbb::blocked_range<int>& r) {
    for (int c = r.begin(); c != r.end(); ++c) {
      int previous = -1;
      const int first = c * kCoarseChunk, end = std::min(count, first + kCoarseChunk);
      // The grid cells of the points a few steps ahead are fetched while this one is answered
      // (first their offsets, then, two steps later, their entries).
      const auto fetch = [&](int i, bool entries) {
        Vec3 q;
        int ignored = -1;
        if (i < end && point(i, q, ignored)) query.grid.prefetch(q, entries);
      };
      for (int i = first; i < std::min(end, first + kFetchAhead); ++i) fetch(i, false);
      for (int i = first; i < end; ++i) {
        fetch(i + kFetchAhead, false);
        fetch(i + kFetchAhead / 2, true);
        Vec3 q;
        int hint = previous;
        if (!point(i, q, hint)) {
          out[i] = 0.0;
          continue;
        }
        out[i] = std::sqrt(query(q, hint));
        previous = hint;
      }
    }
  });
}

// The exact distances of A's vertices (those in a triangle) and triangle centroids, into
// work.vertex_distance and work.centroid_distance.
void coarse_distances(const TriMesh& A, const ExactQuery& query, const DistanceLayout& layout,
                      bool corresponding, int triangles_b, DistanceWorkspace& work) {
  const auto first_try = [&](int t, int& hint) {
    if (corresponding && t < triangles_b) hint = t;
  };
  const std::vector<int>& vertex_owner = layout.vertex_owner();
  coarse_samples(A.num_vertices(), work.vertex_distance, query, [&](int v, Vec3& q, int& hint) {
    if (vertex_owner[v] < 0) return false;  // in no triangle: not on A's surface
    q = A.vertex(v);
    first_try(vertex_owner[v], hint);
    return true;
  });
  coarse_samples(A.num_triangles(), work.centroid_distance, query, [&](int t, Vec3& q, int& hint) {
    q = (A.vertex(A.F(t, 0)) + A.vertex(A.F(t, 1)) + A.vertex(A.F(t, 2))) / 3.0;
    first_try(t, hint);
    return true;
  });
}

// The rule of degree 2 on every triangle (1/12 at each corner, 3/4 at the centroid), weighted
// by the triangle's area; the triangles count alike if they are all degenerate. Each triangle's
// largest sample goes to work.triangle_max.
DistanceStats quadrature(const TriMesh& A, const DistanceLayout& layout, DistanceWorkspace& work) {
  const int m = A.num_triangles();
  const std::vector<double>& dv = work.vertex_distance;
  const std::vector<double>& dc = work.centroid_distance;
  DistanceStats stats;
  std::vector<double>& triangle_max = work.triangle_max;
  triangle_max.resize(m);
  double area = 0.0, sum = 0.0, sum2 = 0.0, plain = 0.0, plain2 = 0.0;
  for (int t = 0; t < m; ++t) {
    const double a = dv[A.F(t, 0)], b = dv[A.F(t, 1)], c = dv[A.F(t, 2)], d = dc[t];
    const double q1 = (a + b + c) / 12.0 + 0.75 * d;
    const double q2 = (a * a + b * b + c * c) / 12.0 + 0.75 * d * d;
    const Vec3 p0 = A.vertex(A.F(t, 0));
    const double at = 0.5 * (A.vertex(A.F(t, 1)) - p0).cross(A.vertex(A.F(t, 2)) - p0).norm();
    area += at;
    sum += at * q1;
    sum2 += at * q2;
    plain += q1;
    plain2 += q2;
    triangle_max[t] = std::max({a, b, c, d});
    stats.max = std::max(stats.max, triangle_max[t]);
  }
  if (area > 0.0 && std::isfinite(area)) {
    stats.mean = sum / area;
    stats.rms = std::sqrt(sum2 / area);
  } else {
    stats.mean = plain / m;
    stats.rms = std::sqrt(plain2 / m);
  }
  for (int v = 0; v < A.num_vertices(); ++v) stats.samples += layout.vertex_owner()[v] >= 0;
  stats.samples += m;
  return stats;
}

// One level of refinement: the triangles whose largest sample reaches `threshold` are sampled
// at `spacing` (the edge midpoints if options.sample_edges); stats.max and samples grow.
void refine_level(const TriMesh& A, const ExactQuery& query, const DistanceOptions& options,
                  double spacing, double threshold, int triangles_b, DistanceWorkspace& work,
                  DistanceStats& stats) {
  const unsigned edges = options.sample_edges ? 0x38u : 0u;
  std::vector<double>& triangle_max = work.triangle_max;
  std::vector<int>& refine = work.refine;
  std::vector<long>& count = work.count;
  refine.clear();
  for (int t = 0; t < A.num_triangles(); ++t)
    if (triangle_max[t] >= threshold && triangle_max[t] > 0.0) refine.push_back(t);
  count.assign(refine.size(), 0);
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, refine.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
          const int t = refine[i];
          const Vec3 p[3] = {A.vertex(A.F(t, 0)), A.vertex(A.F(t, 1)), A.vertex(A.F(t, 2))};
          int hint = options.corresponding_triangles && t < triangles_b ? t : -1;
          double& most = triangle_max[t];
          sample_triangle(p, edges, options.sample_faces, false, spacing, [&](const Vec3& q) {
            most = std::max(most, std::sqrt(query(q, hint)));
            ++count[i];
          });
        }
      });
  for (size_t i = 0; i < refine.size(); ++i) {
    stats.samples += count[i];
    stats.max = std::max(stats.max, triangle_max[refine[i]]);
  }
}

DistanceStats adaptive_distance(const TriMesh& A, const ExactQuery& query,
                                const DistanceLayout& layout, const DistanceOptions& options,
                                int triangles_b, DistanceWorkspace& work) {
  coarse_distances(A, query, layout, options.corresponding_triangles, triangles_b, work);
  DistanceStats stats = quadrature(A, layout, work);
  // Refinement in two levels: at twice the spacing, the triangles whose samples reach
  // refine_above times the largest sample; then at the spacing, those whose samples so far reach
  // sqrt(refine_above) times the largest so far (the samples at twice the spacing tell better
  // where the maximum is than the vertices and centroids).
  if (!(options.sample_edges || options.sample_faces)) return stats;
  const double h = options.spacing * layout.mean_edge_length(A.V);
  for (const double spacing : {2.0 * h, h}) {
    const double threshold =
        (spacing > h ? options.refine_above : std::sqrt(options.refine_above)) * stats.max;
    refine_level(A, query, options, spacing, threshold, triangles_b, work, stats);
  }
  stats.refined = static_cast<long>(work.refine.size());
  return stats;
}

// one_sided_distance with the sampling layout of A's triangles and the scratch memory lent
// (the same results as without them).
DistanceStats measure(const TriMesh& A, const TriangleBvh& B, const DistanceOptions& options,
                      const TrianglePlanes* planes_b, const Topology* topology_b,
                      const DistanceLayout* layout, DistanceWorkspace* work) {
  validate_mesh(A, "one_sided_distance (A)");
  check_option_ranges(options);  // the ranges of fields_of<DistanceOptions>()
  const int m = A.num_triangles();
  if (m == 0) return DistanceStats{};
  if (B.empty()) throw InputError("one_sided_distance: the mesh B has no triangles");
  const Positions& VB = B.positions();
  const Triangles& FB = B.triangles();
  TrianglePlanes own_planes;
  if (!planes_b || planes_b->size() != FB.rows()) {
    own_planes.update(VB, FB, topology_b);
    planes_b = &own_planes;
  }
  DistanceWorkspace own_work;
  if (!work) work = &own_work;
  work->grid.build(VB, FB, *planes_b, cell_size(VB, FB), topology_b);
  const ExactQuery query{work->grid, B};

  DistanceLayout own_layout;
  if (!layout || !layout->fits(A.F, A.num_vertices())) {
    own_layout = DistanceLayout(A.F, A.num_vertices());
    layout = &own_layout;
  }
  // Refused before any sample is taken when the spacing asks for more than the budget.
  check_distance_samples(A, *layout, options, "the sampled mesh");
  const int triangles_b = static_cast<int>(FB.rows());
  DistanceStats stats = options.adaptive
                            ? adaptive_distance(A, query, *layout, options, triangles_b, *work)
                            : uniform_distance(A, query, *layout, options, triangles_b);

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

}  // namespace

DistanceStats one_sided_distance(const TriMesh& A, const TriangleBvh& B,
                                 const DistanceOptions& options, const TrianglePlanes* planes_b,
                                 const Topology* topology_b) {
  return measure(A, B, options, planes_b, topology_b, nullptr, nullptr);
}

DistanceMeter::DistanceMeter(const Triangles& F, int num_vertices,
                             std::shared_ptr<const Topology> topology, DistanceOptions options)
    : layout_(F, num_vertices),
      topology_(std::move(topology)),
      options_(options),
      pool_(std::make_unique<DistanceWorkspaces>()) {}

FrameDistances DistanceMeter::measure(const TriMesh& original, const TriangleBvh& original_bvh,
                                      const TrianglePlanes& original_planes,
                                      const Positions& moved) const {
  const DistanceWorkspaces::Lease lease = pool_->acquire();
  DistanceWorkspace& work = *lease.get();
  const Topology* topology = topology_.get();
  FrameDistances d;
  const TriMesh output{moved, original.F};
  d.moved_to_original =
      sm::measure(output, original_bvh, options_, &original_planes, topology, &layout_, &work);
  work.bvh = original_bvh;  // same triangles: refit, no rebuild
  work.bvh.refit(moved);
  work.planes.update(moved, original.F, topology);
  d.original_to_moved =
      sm::measure(original, work.bvh, options_, &work.planes, topology, &layout_, &work);
  return d;
}

double symmetric_hausdorff(const DistanceStats& a_to_b, const DistanceStats& b_to_a) {
  return std::max(a_to_b.max, b_to_a.max);
}

}  // namespace sm
