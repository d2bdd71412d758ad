#include "geometry/surface_walk.hpp"

#include <sstream>

#include "geometry/closest_point.hpp"
#include "mesh/errors.hpp"

namespace sm {
namespace {

// The local corner (0, 1, 2) of a vertex region, or the first corner of an edge region.
int region_corner(TriangleRegion region) {
  switch (region) {
    case TriangleRegion::Vertex0:
    case TriangleRegion::Edge01:
      return 0;
    case TriangleRegion::Vertex1:
    case TriangleRegion::Edge12:
      return 1;
    case TriangleRegion::Vertex2:
    case TriangleRegion::Edge20:
      return 2;
    case TriangleRegion::Face:
      break;
  }
  return -1;
}

bool is_edge(TriangleRegion region) {
  return region == TriangleRegion::Edge01 || region == TriangleRegion::Edge12 ||
         region == TriangleRegion::Edge20;
}

}  // namespace

bool walk_closest(const Positions& V, const Triangles& F, const Topology& topo, const Vec3& p,
                  int start, int max_steps, SurfacePoint& out, const TrianglePlanes* planes) {
  if (start < 0 || start >= F.rows() || topo.num_triangles != F.rows() ||
      (planes && planes->size() != F.rows())) {
    std::ostringstream msg;
    msg << "walk_closest: start triangle " << start << " for a mesh of " << F.rows()
        << " triangles (topology of " << topo.num_triangles << ", planes of "
        << (planes ? planes->size() : -1) << ")";
    throw InputError(msg.str());
  }
  auto test = [&](int t) {
    if (planes) return planes->closest(t, p, V, F);
    return closest_point_on_triangle(p, V.row(F(t, 0)).transpose(), V.row(F(t, 1)).transpose(),
                                     V.row(F(t, 2)).transpose());
  };
  auto settle = [&](int t, const TrianglePoint& tp) {
    out.triangle = t;
    out.bary = tp.bary;
    out.point = tp.point;
    out.dist2 = tp.dist2;
  };

  int current = start;
  TrianglePoint here = test(current);
  for (int steps = 0;; ++steps) {
    int next = -1;
    TrianglePoint best = here;
    TrianglePoint tp;
    auto consider = [&](int t) {
      if (t == current) return;
      if (planes) {
        if (!planes->closer_than(t, p, best.dist2, V, F, tp)) return;
      } else {
        tp = test(t);
        if (!(tp.dist2 < best.dist2)) return;
      }
      best = tp;
      next = t;
    };
    auto consider_fan = [&](int v) {
      const Csr& fan = topo.vertex_triangles;
      for (int i = fan.begin(v); i < fan.end(v); ++i) consider(fan.data[i]);
    };

    const int k = region_corner(here.region);
    if (k < 0) {
      // Inside the face: a point just inside a convex edge also projects into the face across
      // it, which may be closer. Trying the three edge neighbours catches that case.
      for (int e = 0; e < 3; ++e)
        if (const int across = topo.triangle_neighbours[current][e]; across >= 0) consider(across);
    } else {
      if (!is_edge(here.region)) {
        consider_fan(F(current, k));
      } else if (const int across = topo.triangle_neighbours[current][k]; across >= 0) {
        consider(across);
      } else {
        consider_fan(F(current, k));
        consider_fan(F(current, (k + 1) % 3));
      }
    }

    if (next < 0) {
      settle(current, here);
      return true;
    }
    if (steps >= max_steps) {
      settle(next, best);  // the closest point seen: an upper bound for the exact query
      return false;
    }
    current = next;
    here = best;
  }
}

}  // namespace sm
