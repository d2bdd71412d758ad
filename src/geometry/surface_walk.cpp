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
                  int start, int max_steps, SurfacePoint& out) {
  if (start < 0 || start >= F.rows() || topo.num_triangles != F.rows()) {
    std::ostringstream msg;
    msg << "walk_closest: start triangle " << start << " for a mesh of " << F.rows()
        << " triangles (topology of " << topo.num_triangles << ")";
    throw InputError(msg.str());
  }
  auto test = [&](int t) {
    return closest_point_on_triangle(p, V.row(F(t, 0)).transpose(), V.row(F(t, 1)).transpose(),
                                     V.row(F(t, 2)).transpose());
  };

  int current = start;
  TrianglePoint here = test(current);
  for (int steps = 0;; ++steps) {
    int next = -1;
    TrianglePoint best = here;
    auto consider = [&](int t) {
      if (t == current) return;
      const TrianglePoint tp = test(t);
      if (tp.dist2 < best.dist2) {
        best = tp;
        next = t;
      }
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
      out.triangle = current;
      out.bary = here.bary;
      out.point = here.point;
      out.dist2 = here.dist2;
      return true;
    }
    if (steps >= max_steps) return false;
    current = next;
    here = best;
  }
}

}  // namespace sm
