#include "massage/correspondence.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "geometry/closest_point.hpp"
#include "geometry/surface_walk.hpp"

namespace sm {
namespace {

// The local answer for the query p from c's triangle: true when it is final; otherwise c holds
// the bound for the exact query (the best point seen, or none).
inline bool local_answer(const SurfaceView& surface, const Vec3& p, bool exact, int max_steps,
                         SurfacePoint& c) {
  if (c.triangle < 0) {
    c = SurfacePoint{};
    return false;
  }
  const Positions& V = *surface.V;
  const Triangles& F = *surface.F;
  if (!exact) {
    if (walk_closest(V, F, *surface.topology, p, c.triangle, max_steps, c, surface.planes))
      return true;
  } else {
    // The full test (not the projection frames): a query on a corner gets distance 0 exactly,
    // which needs no BVH query at all.
    const int t = c.triangle;
    const TrianglePoint tp = closest_point_on_triangle(
        p, V.row(F(t, 0)).transpose(), V.row(F(t, 1)).transpose(), V.row(F(t, 2)).transpose());
    c.bary = tp.bary;
    c.point = tp.point;
    c.dist2 = tp.dist2;
  }
  return c.dist2 == 0.0;  // nothing is strictly closer
}

}  // namespace

int update_correspondences(const SurfaceView& surface, const Positions& points, bool exact,
                           int max_steps, std::vector<SurfacePoint>& corr,
                           const std::function<void()>& before_exact) {
  const int count = static_cast<int>(points.rows());
  corr.resize(count);
  // Pass 1: the local answers. corr[i] keeps a bound (the best point seen, or none) where the
  // exact query is still needed.
  std::vector<unsigned char> pending(count, 0);
  // The queries come in vertex order, not triangle order (the crane's is not spatial), so the
  // walks' reads are random: fetch them ahead, in two stages. 2·kAhead queries ahead, the start
  // triangle's corners (a row of F) and neighbours (of the topology); kAhead ahead, its frame and
  // corner positions, for the full test when the query is not over its face, and its edge
  // neighbours' frames where no bends spare their tests (M's frames). Answers do not depend on it.
  constexpr int kAhead = 8;
  const Positions& V = *surface.V;
  const Triangles& F = *surface.F;
  const auto& across = surface.topology->triangle_neighbours;
  const int m = static_cast<int>(F.rows());
  const TrianglePlanes* ahead =
      !exact && surface.planes && surface.planes->size() == m && across.size() == size_t(m)
          ? surface.planes
          : nullptr;  // (a mismatch throws in the walk)
  const bool neighbours_ahead = ahead && !ahead->has_bends();
  auto start_of = [&](int i) {  // the triangle a walk will start on, -1 for none or a bad one
    const int t = corr[i].triangle;
    return t < m ? t : -1;
  };
  tbb::parallel_for(tbb::blocked_range<int>(0, count, 1024), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) {
      if (ahead && i + 2 * kAhead < r.end()) {
        if (const int t = start_of(i + 2 * kAhead); t >= 0) {
          __builtin_prefetch(&F(t, 0));
          __builtin_prefetch(&across[t]);
        }
      }
      if (ahead && i + kAhead < r.end()) {
        if (const int t = start_of(i + kAhead); t >= 0) {
          ahead->prefetch(t);
          for (int k = 0; k < 3; ++k) __builtin_prefetch(&V(F(t, k), 0));
          if (neighbours_ahead)
            for (const int u : across[t])
              if (u >= 0) ahead->prefetch(u);
        }
      }
      if (!local_answer(surface, points.row(i).transpose(), exact, max_steps, corr[i]))
        pending[i] = 1;
    }
  });
  int exact_count = 0;
  for (unsigned char u : pending) exact_count += u;
  if (exact_count == 0) return 0;

  // Pass 2: the exact queries, pruned by the bound; a bound that nothing beats is the answer.
  if (before_exact) before_exact();
  tbb::parallel_for(tbb::blocked_range<int>(0, count, 1024), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) {
      if (!pending[i]) continue;
      SurfacePoint& c = corr[i];
      const SurfacePoint sp = surface.bvh->closest(points.row(i).transpose(), c.dist2);
      if (sp.triangle >= 0) c = sp;
    }
  });
  return exact_count;
}

}  // namespace sm
