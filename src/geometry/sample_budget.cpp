#include "geometry/sample_budget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/errors.hpp"

namespace sm {
namespace {

// The samples sample_triangle (distance.cpp) takes on triangle p at spacing h: the interior
// points of the edges whose bit (8 << k) is set in `edges`, then, with `faces`, the
// (n − 1)(n − 2)/2 interior lattice points of n divisions, or the centroid when there are none.
double triangle_samples(const Vec3 (&p)[3], unsigned edges, bool faces, bool centroid,
                        double h) {
  double n = 0.0;
  for (int k = 0; k < 3; ++k)
    if (edges & (8u << k))
      n += double(sample_divisions((p[(k + 1) % 3] - p[k]).norm(), h, kMaxEdgeSegments) - 1);
  if (!faces) return n;
  const double longest =
      std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
  const double d = double(sample_divisions(longest, h, kMaxFaceDivisions));
  return n + (d < 3.0 ? (centroid ? 1.0 : 0.0) : (d - 1.0) * (d - 2.0) / 2.0);
}

std::string integer_text(double x) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.0f", x);
  return buffer;
}

}  // namespace

double distance_sample_count(const TriMesh& A, const DistanceLayout& layout,
                             const DistanceOptions& options) {
  const int m = A.num_triangles();
  if (m == 0) return 0.0;
  const std::vector<uint8_t>& owns = layout.owns();
  const double h = options.spacing * layout.mean_edge_length(A.V);
  const auto corners = [&](int t, Vec3 (&p)[3]) {
    for (int k = 0; k < 3; ++k) p[k] = A.vertex(A.F(t, k));
  };
  double count = 0.0;
  if (!options.adaptive) {
    for (int t = 0; t < m; ++t) {
      Vec3 p[3];
      corners(t, p);
      for (int k = 0; k < 3; ++k) count += (owns[size_t(t)] >> k) & 1u;
      count += triangle_samples(p, options.sample_edges ? owns[size_t(t)] : 0u,
                                options.sample_faces, true, h);
    }
    return count;
  }
  // The coarse pass (every vertex in a triangle, every centroid), then both levels of
  // refinement on every triangle: the most the data can ask for.
  for (int owner : layout.vertex_owner()) count += owner >= 0 ? 1.0 : 0.0;
  count += double(m);
  if (!(options.sample_edges || options.sample_faces)) return count;
  const unsigned edges = options.sample_edges ? 0x38u : 0u;
  for (int t = 0; t < m; ++t) {
    Vec3 p[3];
    corners(t, p);
    for (const double spacing : {2.0 * h, h})
      count += triangle_samples(p, edges, options.sample_faces, false, spacing);
  }
  return count;
}

double distance_sample_budget(long triangles) {
  return std::max(kDistanceSampleBudget, kDistanceSamplesPerTriangle * double(triangles));
}

void check_sample_budget(double samples, long triangles, double spacing, bool up_to,
                         const std::string& what) {
  const double budget = distance_sample_budget(triangles);
  if (!(samples > budget)) return;
  char value[32];
  std::snprintf(value, sizeof value, "%.9g", spacing);
  throw OptionError("spacing", std::string(value) + " would take " + (up_to ? "up to " : "") +
                                   integer_text(samples) + " samples on " + what + " (" +
                                   std::to_string(triangles) +
                                   " triangles), more than the budget of " +
                                   integer_text(budget) +
                                   " (50 million, or 100 per triangle); choose a larger spacing");
}

void check_distance_samples(const TriMesh& A, const DistanceLayout& layout,
                            const DistanceOptions& options, const std::string& what) {
  // Most meshes are far within the budget: a bound from the longest edge (every triangle counted
  // as one with three edges that long, which takes at least as many samples) settles it without
  // the exact count, which costs a square root per edge and per level. Refused only by the
  // exact count, as before.
  const int m = A.num_triangles();
  double longest2 = 0.0;
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k)
      longest2 = std::max(longest2,
                          (A.vertex(A.F(t, (k + 1) % 3)) - A.vertex(A.F(t, k))).squaredNorm());
  if (m > 0 && std::isfinite(longest2)) {
    const double h = options.spacing * layout.mean_edge_length(A.V);
    const double l = std::sqrt(longest2);
    const auto per_triangle = [&](double spacing, bool centroid) {
      const double edge = double(sample_divisions(l, spacing, kMaxEdgeSegments) - 1);
      const double d = double(sample_divisions(l, spacing, kMaxFaceDivisions));
      return (options.sample_edges ? 3.0 * edge : 0.0) +
             (!options.sample_faces ? 0.0
                                    : d < 3.0 ? (centroid ? 1.0 : 0.0) : (d - 1.0) * (d - 2.0) / 2.0);
    };
    const double bound = options.adaptive
                             ? double(A.num_vertices()) + double(m) +
                                   (options.sample_edges || options.sample_faces
                                        ? double(m) * (per_triangle(2.0 * h, false) +
                                                       per_triangle(h, false))
                                        : 0.0)
                             : double(A.num_vertices()) + double(m) * per_triangle(h, true);
    if (bound <= distance_sample_budget(m)) return;
  }
  check_sample_budget(distance_sample_count(A, layout, options), A.num_triangles(),
                      options.spacing, options.adaptive, what);
}

void check_distance_samples(const TriMesh& A, const DistanceOptions& options,
                            const std::string& what) {
  check_distance_samples(A, DistanceLayout(A.F, A.num_vertices()), options, what);
}

}  // namespace sm
