#include "massage/correspondence.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "geometry/surface_walk.hpp"

namespace sm {

int update_correspondences(const SurfaceView& surface, const Positions& points, bool exact,
                           int max_steps, std::vector<SurfacePoint>& corr,
                           const std::function<void()>& before_exact) {
  const int count = static_cast<int>(points.rows());
  corr.resize(count);
  // Pass 1: the local answers. corr[i] keeps a bound (the best point seen, or none) where the
  // exact query is still needed.
  std::vector<unsigned char> pending(count, 0);
  // The walks read the frames at random (the crane's triangle order is not spatial): fetch the
  // start triangle's frame a few queries ahead, and its edge neighbours' too where no bends
  // spare their tests (M's frames). The answers do not depend on it.
  constexpr int kAhead = 8;
  const TrianglePlanes* ahead = exact ? nullptr : surface.planes;
  const bool neighbours_ahead = ahead && !ahead->has_bends();
  tbb::parallel_for(tbb::blocked_range<int>(0, count, 1024), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) {
      if (ahead && i + kAhead < r.end()) {
        if (const int t = corr[i + kAhead].triangle; t >= 0) {
          ahead->prefetch(t);
          if (neighbours_ahead)
            for (const int u : surface.topology->triangle_neighbours[t])
              if (u >= 0) ahead->prefetch(u);
        }
      }
      const Vec3 p = points.row(i).transpose();
      SurfacePoint& c = corr[i];
      if (c.triangle >= 0) {
        if (!exact) {
          if (walk_closest(*surface.V, *surface.F, *surface.topology, p, c.triangle, max_steps, c,
                           surface.planes))
            continue;
        } else {
          // The full test (not the projection frames): a query on a corner gets distance 0
          // exactly, which needs no BVH query at all.
          const int t = c.triangle;
          const Positions& V = *surface.V;
          const Triangles& F = *surface.F;
          const TrianglePoint tp =
              closest_point_on_triangle(p, V.row(F(t, 0)).transpose(), V.row(F(t, 1)).transpose(),
                                        V.row(F(t, 2)).transpose());
          c.bary = tp.bary;
          c.point = tp.point;
          c.dist2 = tp.dist2;
        }
        if (c.dist2 == 0.0) continue;  // nothing is strictly closer
      } else {
        c = SurfacePoint{};
      }
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
