#pragma once
/// Exact closest point on one triangle, with the Voronoi region it falls in (Ericson,
/// Real-Time Collision Detection §5.1.5). Used by every point-to-surface query (paper §2.2.1).
#include <cstdint>

#include "mesh/mesh.hpp"

namespace sm {

/// Where on the triangle (a, b, c) the closest point lies.
enum class TriangleRegion : uint8_t { Face, Edge01, Edge12, Edge20, Vertex0, Vertex1, Vertex2 };

struct TrianglePoint {
  Vec3 point;            ///< the closest point
  Vec3 bary;             ///< its barycentric coordinates (u, v, w), u·a + v·b + w·c = point, sum 1
  TriangleRegion region;
  double dist2;          ///< squared distance from the query
};

/// A triangle whose doubled area |ab × ac| is at most this fraction of its longest edge squared
/// (height below ~1e-8 of its length) is handled as the union of its three edges. Above the
/// threshold the face case is accurate to about 1e-8 of the edge length; below it, the closest
/// point on the edges is at most the inradius (< 1e-8 of the edge length) from the face's.
inline constexpr double kDegenerateRatio2 = 1e-16;

/// Closest point of triangle (a, b, c) to p. Degenerate triangles (collinear or coincident
/// corners) are handled: the answer is then the closest point on their edges.
TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace sm
