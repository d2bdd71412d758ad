#pragma once
/// Closest points found by trying every triangle: the reference that the BVH, the triangle grid
/// and the surface walk are checked against.
#include "geometry/bvh.hpp"
#include "geometry/closest_point.hpp"
#include "mesh/mesh.hpp"

namespace sm::test {

/// The closest point of the triangles (V, F) to `p` (the first triangle of least distance).
inline SurfacePoint brute_force_closest(const Positions& V, const Triangles& F, const Vec3& p) {
  SurfacePoint best;
  for (int t = 0; t < F.rows(); ++t) {
    const TrianglePoint tp = closest_point_on_triangle(
        p, V.row(F(t, 0)).transpose(), V.row(F(t, 1)).transpose(), V.row(F(t, 2)).transpose());
    if (tp.dist2 < best.dist2) {
      best.triangle = t;
      best.dist2 = tp.dist2;
      best.point = tp.point;
      best.bary = tp.bary;
    }
  }
  return best;
}

/// The squared distance from `p` to `mesh`.
inline double brute_force_dist2(const TriMesh& mesh, const Vec3& p) {
  return brute_force_closest(mesh.V, mesh.F, p).dist2;
}

}  // namespace sm::test
