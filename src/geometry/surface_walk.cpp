#include "geometry/surface_walk.hpp"

#include <array>
#include <limits>
#include <sstream>
#include <utility>

#include "geometry/closest_point.hpp"
#include "core/errors.hpp"

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

[[noreturn]] void throw_bad_walk_start(const Triangles& F, const Topology& topo, int start,
                                       const TrianglePlanes* planes) {
  std::ostringstream msg;
  msg << "walk_closest: start triangle " << start << " for a mesh of " << F.rows()
      << " triangles (topology of " << topo.num_triangles << ", planes of "
      << (planes ? planes->size() : -1) << ")";
  throw InputError(msg.str());
}

void set_surface_point(SurfacePoint& out, int t, const TrianglePoint& tp) {
  out.triangle = t;
  out.bary = tp.bary;
  out.point = tp.point;
  out.dist2 = tp.dist2;
}

// One walk's query point p on the mesh (V, F, topo), with the triangles' frames if given.
struct WalkQuery {
  const Positions& V;
  const Triangles& F;
  const Topology& topo;
  const Vec3& p;
  const TrianglePlanes* planes;

  // Whether triangle t is strictly closer than `best`; if so `best` becomes its closest point.
  bool closer(int t, TrianglePoint& best) const {
    if (planes) return planes->closer_than(t, p, best.dist2, V, F, best);
    const TrianglePoint tp = closest_point_on_triangle(
        p, V.row(F(t, 0)).transpose(), V.row(F(t, 1)).transpose(), V.row(F(t, 2)).transpose());
    if (!(tp.dist2 < best.dist2)) return false;
    best = tp;
    return true;
  }

  // The closest point on the start triangle t into `here`. True when it settles in t's face (the
  // walk ends there); `unsettled`: in the face without face_settles holding.
  bool start_on(int t, TrianglePoint& here, bool& unsettled) const {
    if (!planes) {
      closer(t, here);
      return false;
    }
    // Most walks end where they start, inside the face: closer_than's face case and
    // face_settles, sharing the height, without a step into the loop.
    const TrianglePlane& f = (*planes)[t];
    const Vec3 r = p - f.origin;
    const double beta = r.dot(f.dual1), gamma = r.dot(f.dual2), h = r.dot(f.normal);
    const double alpha = 1.0 - beta - gamma;
    if (!(beta >= 0.0 && gamma >= 0.0 && alpha >= 0.0 && h * h < here.dist2)) {
      closer(t, here);
      return false;
    }
    here.point = p - h * f.normal;
    here.bary = Vec3(alpha, beta, gamma);
    here.dist2 = h * h;
    if (TrianglePlanes::face_settles(f, h, here.bary)) return true;
    unsettled = true;
    return false;
  }

  // The neighbour of `current` strictly closer than `here` (its closest point into `best`, whose
  // dist2 starts at here's), or -1.
  int step(int current, const TrianglePoint& here, bool unsettled, TrianglePoint& best) const {
    int next = -1;
    const auto consider = [&](int t) {
      if (t != current && closer(t, best)) next = t;
    };
    const auto consider_fan = [&](int v) {
      const Csr& fan = topo.vertex_triangles;
      for (int i = fan.begin(v); i < fan.end(v); ++i) consider(fan.data[i]);
    };
    const int k = region_corner(here.region);
    if (k < 0) {
      // Inside the face: a point just inside a convex edge also projects into the face across
      // it, which may be closer. Trying the three edge neighbours catches that case.
      // The bends of the projection frames can tell that none of them is closer.
      if (!planes || unsettled || !planes->face_settles(current, p, here.bary)) {
        const std::array<int, 3>& across = topo.triangle_neighbours[current];
        for (int e = 0; e < 3; ++e)
          if (across[e] >= 0 && closer(across[e], best)) next = across[e];
      }
    } else if (!is_edge(here.region)) {
      consider_fan(F(current, k));
    } else if (const int across = topo.triangle_neighbours[current][k]; across >= 0) {
      consider(across);
    } else {
      consider_fan(F(current, k));
      consider_fan(F(current, (k + 1) % 3));
    }
    return next;
  }
};

}  // namespace

bool walk_closest(const Positions& V, const Triangles& F, const Topology& topo, const Vec3& p,
                  int start, int max_steps, SurfacePoint& out, const TrianglePlanes* planes) {
  if (start < 0 || start >= F.rows() || topo.num_triangles != F.rows() ||
      (planes && planes->size() != F.rows()))
    throw_bad_walk_start(F, topo, start, planes);
  const WalkQuery query{V, F, topo, p, planes};
  int current = start;
  TrianglePoint here{Vec3::Zero(), Vec3::Zero(), TriangleRegion::Face,
                     std::numeric_limits<double>::infinity()};
  bool unsettled = false;
  if (query.start_on(current, here, unsettled)) {
    set_surface_point(out, current, here);
    return true;
  }
  TrianglePoint best;
  for (int steps = 0;; ++steps) {
    best.dist2 = here.dist2;
    const int next = query.step(current, here, unsettled, best);
    if (next < 0 || steps >= max_steps) {
      // Settled; or out of steps, and the closest point seen bounds the exact query.
      set_surface_point(out, next < 0 ? current : next, next < 0 ? here : best);
      return next < 0;
    }
    current = next;
    std::swap(here, best);
    unsettled = false;
  }
}

}  // namespace sm
