#include "geometry/closest_point.hpp"

#include <algorithm>

namespace sm {
namespace {

TrianglePoint make_point(const Vec3& p, const Vec3& q, double u, double v, double w,
                         TriangleRegion region) {
  return TrianglePoint{q, Vec3(u, v, w), region, (p - q).squaredNorm()};
}

// Closest point of segment (a, b) to p as the parameter t in [0, 1]; a zero-length segment
// gives t = 0.
double segment_parameter(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0.0)) return 0.0;
  return std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
}

// Degenerate triangle (collinear or coincident corners): the closest point on its three edges.
TrianglePoint closest_on_edges(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3* corner[3] = {&a, &b, &c};
  static constexpr TriangleRegion kEdge[3] = {TriangleRegion::Edge01, TriangleRegion::Edge12,
                                              TriangleRegion::Edge20};
  static constexpr TriangleRegion kVertex[3] = {TriangleRegion::Vertex0, TriangleRegion::Vertex1,
                                                TriangleRegion::Vertex2};
  TrianglePoint best{a, Vec3(1.0, 0.0, 0.0), TriangleRegion::Vertex0, (p - a).squaredNorm()};
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    const double t = segment_parameter(p, *corner[k], *corner[k1]);
    const Vec3 q = *corner[k] + t * (*corner[k1] - *corner[k]);
    const double d2 = (p - q).squaredNorm();
    if (d2 < best.dist2) {
      Vec3 bary = Vec3::Zero();
      bary[k] = 1.0 - t;
      bary[k1] = t;
      const TriangleRegion region = t == 0.0 ? kVertex[k] : (t == 1.0 ? kVertex[k1] : kEdge[k]);
      best = TrianglePoint{q, bary, region, d2};
    }
  }
  return best;
}

}  // namespace

TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                        const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, bc = c - b;
  const Vec3 n = ab.cross(ac);
  const double l2 = std::max({ab.squaredNorm(), ac.squaredNorm(), bc.squaredNorm()});
  if (!(n.squaredNorm() > kDegenerateRatio2 * l2 * l2)) return closest_on_edges(p, a, b, c);

  // Ericson §5.1.5: test the Voronoi regions of the corners, then of the edges, then the face.
  const Vec3 ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return make_point(p, a, 1.0, 0.0, 0.0, TriangleRegion::Vertex0);

  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return make_point(p, b, 0.0, 1.0, 0.0, TriangleRegion::Vertex1);

  // The barycentric numerators va, vb, vc equal Ericson's d3·d6 − d5·d4 etc. (Lagrange's
  // identity) but are computed as n · (edge × (p − corner)), which cancels far less for thin
  // triangles and distant queries. They sum to |n|².
  const double vc = n.dot(ab.cross(ap));
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return make_point(p, a + v * ab, 1.0 - v, v, 0.0, TriangleRegion::Edge01);
  }

  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return make_point(p, c, 0.0, 0.0, 1.0, TriangleRegion::Vertex2);

  const double vb = n.dot(ap.cross(ac));
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return make_point(p, a + w * ac, 1.0 - w, 0.0, w, TriangleRegion::Edge20);
  }

  const double va = n.dot(bc.cross(bp));
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return make_point(p, b + w * bc, 0.0, 1.0 - w, w, TriangleRegion::Edge12);
  }

  // Inside the face. Rounding can leave a numerator marginally negative next to an edge: clamp.
  const double u0 = std::max(va, 0.0), v0 = std::max(vb, 0.0), w0 = std::max(vc, 0.0);
  const double inv = 1.0 / (u0 + v0 + w0);
  const double v = v0 * inv, w = w0 * inv;
  return make_point(p, a + v * ab + w * ac, 1.0 - v - w, v, w, TriangleRegion::Face);
}

}  // namespace sm
