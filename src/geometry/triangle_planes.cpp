#include "geometry/triangle_planes.hpp"

#include "geometry/closest_point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sm {
namespace {

// closest_point_on_triangle's threshold (kDegenerateRatio2, closest_point.hpp): a triangle with
// |n|² <= it times its longest edge to the fourth power is handled as its three edges.
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Float bounds for the certificate's values: never larger (altitudes), never smaller in magnitude
// (bends) than the double ones. Rounding to the nearest float changes a value by at most 2^-24
// of it, so scaling by 1 ∓ 2^-22 first is enough.
float shrink_to_float(double x) {
  return static_cast<float>(
      std::min(x * (1.0 - 0x1p-22), double(std::numeric_limits<float>::max())));
}
float grow_to_float(double x) {
  return static_cast<float>(x * (1.0 + 0x1p-22));
}

}  // namespace

void TrianglePlanes::update(const Positions& V, const Triangles& F, const Topology* topo) {
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
        f.altitude2[0] = f.altitude2[1] = f.altitude2[2] = 0.0f;
        f.bend[0] = f.bend[1] = f.bend[2] = kNaN;
        continue;
      }
      const double inv_n2 = 1.0 / n2;
      f.dual1 = ac.cross(n) * inv_n2;
      f.dual2 = n.cross(ab) * inv_n2;
      f.normal = n * (1.0 / std::sqrt(n2));
      // altitude over an edge = |n| / edge length
      f.altitude2[0] = shrink_to_float(n2 / bc2);
      f.altitude2[1] = shrink_to_float(n2 / ac2);
      f.altitude2[2] = shrink_to_float(n2 / ab2);
      f.bend[0] = f.bend[1] = f.bend[2] = kNaN;
    }
  });
  has_bends_ = topo && topo->num_triangles == m;
  if (!has_bends_) return;
  // Bends: for edge k from a to b, with ê = (b − a)/|b − a|, t's inward direction m = n_t × ê and
  // the neighbour's d = ê × n_u (consistent orientation: the topology gives no neighbour across
  // an edge whose triangles disagree), sin θ = d · n_t, cos θ = −d · m, tan(θ/2) = sin/(1 + cos).
  tbb::parallel_for(tbb::blocked_range<int>(0, m, 4096), [&](const tbb::blocked_range<int>& r) {
    for (int t = r.begin(); t != r.end(); ++t) {
      TrianglePlane& f = planes_[t];
      if (f.normal.squaredNorm() == 0.0) continue;  // degenerate: stays unknown
      for (int k = 0; k < 3; ++k) {
        const int u = topo->triangle_neighbours[t][k];
        if (u < 0) {
          f.bend[k] = 0.0f;  // nothing across to test
          continue;
        }
        const Vec3& nu = planes_[u].normal;
        const Vec3 e = V.row(F(t, (k + 1) % 3)) - V.row(F(t, k));
        const double len = e.norm();
        if (nu.squaredNorm() == 0.0 || !(len > 0.0)) continue;  // unknown
        const Vec3 ehat = e / len;
        const Vec3 d = ehat.cross(nu);
        const double sin_t = d.dot(f.normal), cos_t = -d.dot(f.normal.cross(ehat));
        if (!(1.0 + cos_t > 1e-6)) continue;  // folded back onto t: unknown
        f.bend[k] = grow_to_float(sin_t / (1.0 + cos_t));
      }
    }
  });
}

}  // namespace sm
