#include "geometry/triangle_planes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sm {
namespace {

// closest_point_on_triangle's threshold: a triangle with |n|² <= this times its longest edge to
// the fourth power is handled as its three edges.
constexpr double kDegenerateRatio2 = 1e-16;

}  // namespace

void TrianglePlanes::update(const Positions& V, const Triangles& F) {
  const int m = static_cast<int>(F.rows());
  planes_.resize(m);
  tbb::parallel_for(tbb::blocked_range<int>(0, m, 4096), [&](const tbb::blocked_range<int>& r) {
    for (int t = r.begin(); t != r.end(); ++t) {
      const Vec3 a = V.row(F(t, 0)).transpose();
      const Vec3 ab = V.row(F(t, 1)).transpose() - a;
      const Vec3 ac = V.row(F(t, 2)).transpose() - a;
      const Vec3 n = ab.cross(ac);
      const double n2 = n.squaredNorm();
      const double ab2 = ab.squaredNorm(), ac2 = ac.squaredNorm(), bc2 = (ac - ab).squaredNorm();
      const double l2 = std::max({ab2, ac2, bc2});
      TrianglePlane& f = planes_[t];
      f.origin = a;
      if (!(n2 > kDegenerateRatio2 * l2 * l2)) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        f.dual1 = f.dual2 = Vec3::Constant(nan);
        f.normal = Vec3::Zero();
        f.altitude2[0] = f.altitude2[1] = f.altitude2[2] = 0.0;
        continue;
      }
      const double inv_n2 = 1.0 / n2;
      f.dual1 = ac.cross(n) * inv_n2;
      f.dual2 = n.cross(ab) * inv_n2;
      f.normal = n * (1.0 / std::sqrt(n2));
      // altitude over an edge = |n| / edge length
      f.altitude2[0] = n2 / bc2;
      f.altitude2[1] = n2 / ac2;
      f.altitude2[2] = n2 / ab2;
    }
  });
}

}  // namespace sm
