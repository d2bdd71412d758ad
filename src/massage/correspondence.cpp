#include "massage/correspondence.hpp"

#include <tbb/parallel_for.h>

#include "geometry/surface_walk.hpp"

namespace sm {

int update_correspondences(const SurfaceView& surface, const Positions& points, bool exact,
                           int max_steps, std::vector<SurfacePoint>& corr) {
  const int count = static_cast<int>(points.rows());
  corr.resize(count);
  std::vector<unsigned char> used_exact(count, 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, count, 1024), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) {
      const Vec3 p = points.row(i).transpose();
      SurfacePoint& c = corr[i];
      if (!exact && c.triangle >= 0) {
        SurfacePoint walked;
        if (walk_closest(*surface.V, *surface.F, *surface.topology, p, c.triangle, max_steps,
                         walked)) {
          c = walked;
          continue;
        }
      }
      c = surface.bvh->closest(p);
      used_exact[i] = 1;
    }
  });
  int exact_count = 0;
  for (unsigned char u : used_exact) exact_count += u;
  return exact_count;
}

}  // namespace sm
