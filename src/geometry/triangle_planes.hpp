#pragma once
/// Per-triangle projection frames: the face case of the closest point on a triangle (paper
/// §2.2.1) in about 30 flops instead of the full Voronoi-region test, for the local search and the
/// sampled distances, which mostly land inside a face.
///
/// For triangle (a, b, c) with n = (b − a) × (c − a) and a point p, the projection of p onto the
/// triangle's plane is a + β (b − a) + γ (c − a) with
///   β = (p − a) · (c − a) × n / |n|²,   γ = (p − a) · n × (b − a) / |n|²,
/// and its signed height is h = (p − a) · n / |n|. When β, γ ≥ 0 and β + γ ≤ 1 the projection is
/// the closest point and the squared distance is h²; otherwise closest_point_on_triangle decides,
/// and h² + s², with s the distance of the projection to the farthest edge line it lies beyond
/// (barycentric coordinate × altitude), is a lower bound that usually makes that test unneeded.
///
/// With the connectivity, each edge also gets the bend θ of the triangle across it (0 where it
/// continues the plane, > 0 where it rises to the side of the normal): that neighbour lies in a
/// half-plane at distance ≥ |h| from a point inside the face whose projection is at least
/// |h| · tan(θ/2) from the edge, or that lies on the side the neighbour bends away from. So a
/// point well inside a face is certainly no closer to the three neighbours (face_settles), which
/// the local search would otherwise have to test.
#include <algorithm>
#include <vector>

#include "geometry/closest_point.hpp"
#include "mesh/mesh.hpp"
#include "mesh/topology.hpp"

namespace sm {

/// The frame of one triangle: corner 0, the two dual vectors giving β and γ, the unit normal, the
/// squared altitudes over the edges opposite each corner (rounded down) and the bends tan(θ/2) of
/// the neighbours across the edges k → k+1 (rounded away from 0; 0 without a neighbour, NaN when
/// unknown). A degenerate triangle (closest_point_on_triangle's criterion) has NaN dual vectors,
/// so that no point is ever inside it, a zero normal and altitudes, so that its lower bound is 0,
/// and NaN bends.
struct TrianglePlane {
  Vec3 origin;
  Vec3 dual1;
  Vec3 dual2;
  Vec3 normal;
  float altitude2[3];
  float bend[3];
};

class TrianglePlanes {
 public:
  TrianglePlanes() = default;
  TrianglePlanes(const Positions& V, const Triangles& F, const Topology* topo = nullptr) {
    update(V, F, topo);
  }

  /// Recomputes every frame for positions V (n×3) and triangles F (m×3), in parallel. Indices
  /// must be in range (validate_mesh). With `topo` (F's connectivity) the bends are computed too,
  /// otherwise they are unknown and face_settles never holds.
  void update(const Positions& V, const Triangles& F, const Topology* topo = nullptr);

  int size() const { return static_cast<int>(planes_.size()); }
  /// Whether the last update() computed the bends (was given the connectivity).
  bool has_bends() const { return has_bends_; }
  const TrianglePlane& operator[](int t) const { return planes_[t]; }

  /// Hints the processor to bring triangle t's frame into the cache (for a query a few steps
  /// ahead: the frames are read at random and a walk is short).
  void prefetch(int t) const {
    const char* a = reinterpret_cast<const char*>(&planes_[t]);
    __builtin_prefetch(a);  // a frame spans up to three cache lines
    __builtin_prefetch(a + 64);
    __builtin_prefetch(a + sizeof(TrianglePlane) - 1);
  }

  /// If the projection of p onto triangle t's plane lies in the (closed) triangle, writes the
  /// closest point (region Face, bary = (1 − β − γ, β, γ), point = p − h·normal, dist2 = h²) to
  /// `out` and returns true; otherwise returns false and leaves `out` alone.
  bool closest_in_face(int t, const Vec3& p, TrianglePoint& out) const {
    const TrianglePlane& f = planes_[t];
    const Vec3 r = p - f.origin;
    const double beta = r.dot(f.dual1), gamma = r.dot(f.dual2);
    if (!(beta >= 0.0 && gamma >= 0.0 && beta + gamma <= 1.0)) return false;
    const double h = r.dot(f.normal);
    out.point = p - h * f.normal;
    out.bary = Vec3(1.0 - beta - gamma, beta, gamma);
    out.region = TriangleRegion::Face;
    out.dist2 = h * h;
    return true;
  }

  /// Closest point of triangle t (with corners from V and F, the ones given to update()) to p:
  /// closest_in_face when it applies, closest_point_on_triangle otherwise.
  TrianglePoint closest(int t, const Vec3& p, const Positions& V, const Triangles& F) const {
    TrianglePoint tp;
    if (closest_in_face(t, p, tp)) return tp;
    return closest_point_on_triangle(p, V.row(F(t, 0)).transpose(), V.row(F(t, 1)).transpose(),
                                     V.row(F(t, 2)).transpose());
  }

  /// Whether triangle t is strictly closer to p than sqrt(bound2); if so, its closest point goes
  /// to `out` (which is left alone otherwise). Decided by the face case or, outside the face, by
  /// the lower bound h² + s² where it suffices, by closest_point_on_triangle otherwise.
  bool closer_than(int t, const Vec3& p, double bound2, const Positions& V, const Triangles& F,
                   TrianglePoint& out) const {
    const TrianglePlane& f = planes_[t];
    const Vec3 r = p - f.origin;
    const double h = r.dot(f.normal);
    // No point of the triangle is closer than its plane (h² + s² >= h², rounded too).
    if (!(h * h < bound2)) return false;
    const double beta = r.dot(f.dual1), gamma = r.dot(f.dual2);
    const double alpha = 1.0 - beta - gamma;
    if (beta >= 0.0 && gamma >= 0.0 && alpha >= 0.0) {
      out.point = p - h * f.normal;
      out.bary = Vec3(alpha, beta, gamma);
      out.region = TriangleRegion::Face;
      out.dist2 = h * h;
      return true;
    }
    double s2 = 0.0;  // NaN coordinates (a degenerate triangle) leave the bound at 0
    if (alpha < 0.0) s2 = std::max(s2, alpha * alpha * double(f.altitude2[0]));
    if (beta < 0.0) s2 = std::max(s2, beta * beta * double(f.altitude2[1]));
    if (gamma < 0.0) s2 = std::max(s2, gamma * gamma * double(f.altitude2[2]));
    if (!(h * h + s2 < bound2)) return false;
    const TrianglePoint full = closest_point_on_triangle(
        p, V.row(F(t, 0)).transpose(), V.row(F(t, 1)).transpose(), V.row(F(t, 2)).transpose());
    if (!(full.dist2 < bound2)) return false;
    out = full;
    return true;
  }

  /// For p whose projection lies in triangle t with barycentric coordinates `bary` (the face
  /// case): whether none of t's three edge neighbours can be strictly closer to p than t, by the
  /// bends (see above). False when a bend is unknown.
  bool face_settles(int t, const Vec3& p, const Vec3& bary) const {
    const TrianglePlane& f = planes_[t];
    return face_settles(f, (p - f.origin).dot(f.normal), bary);
  }

  /// face_settles for the frame f and the signed height h = (p − f.origin) · f.normal of p.
  static bool face_settles(const TrianglePlane& f, double h, const Vec3& bary) {
    for (int k = 0; k < 3; ++k) {
      const double b = f.bend[k];
      if (b * h <= 0.0) continue;  // flat, no neighbour, or bending away from p
      const int o = (k + 2) % 3;   // the corner opposite edge k → k+1
      if (!(bary[o] * bary[o] * double(f.altitude2[o]) >= h * h * b * b)) return false;
    }
    return true;
  }

 private:
  std::vector<TrianglePlane> planes_;
  bool has_bends_ = false;
};

}  // namespace sm
