#pragma once
/// Meshes generated in code for the single-mesh jobs' tests: remesh pairs whose remesh vertices
// lie on the source surface, a box with irregular triangles on its flat faces, a template and a
// tangentially distorted target with its connectivity.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "geometry/bvh.hpp"
#include "mesh/mesh.hpp"
#include "mesh/primitives.hpp"

namespace sm::test {

// Deterministic uniform numbers in [-1, 1] (mt19937's raw output is specified by the standard).
class Jitter {
 public:
  explicit Jitter(uint32_t seed) : engine_(seed) {}
  double operator()() { return 2.0 * (double(engine_()) / 4294967295.0) - 1.0; }

 private:
  std::mt19937 engine_;
};

// Moves every vertex of `mesh` to its closest point on `surface`.
inline void project_onto(TriMesh& mesh, const TriMesh& surface) {
  const TriangleBvh bvh(surface);
  for (int i = 0; i < mesh.num_vertices(); ++i)
    mesh.V.row(i) = bvh.closest(mesh.vertex(i)).point.transpose();
}

inline Eigen::Matrix3d rotation(double ax, double ay) {
  return (Eigen::AngleAxisd(ax, Vec3::UnitX()) * Eigen::AngleAxisd(ay, Vec3::UnitY()))
      .toRotationMatrix();
}

struct RemeshPair {
  TriMesh source;  // N
  TriMesh remesh;  // M: another connectivity, vertices on N's surface
};

// Source: a fine icosphere; remesh: a coarse, rotated icosphere projected onto the source.
inline RemeshPair sphere_remesh_pair() {
  RemeshPair p;
  p.source = make_icosphere(4, 1.0);
  p.remesh = make_icosphere(2, 1.0);
  p.remesh.V = (p.remesh.V * rotation(0.3, 0.5).transpose()).eval();
  project_onto(p.remesh, p.source);
  return p;
}

// Source: a fine torus; remesh: a coarse torus turned about its axis, projected onto the source.
inline RemeshPair torus_remesh_pair() {
  RemeshPair p;
  p.source = make_torus(96, 48, 2.0, 0.7);
  p.remesh = make_torus(30, 14, 2.0, 0.7);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.07, Vec3::UnitZ()).toRotationMatrix();
  p.remesh.V = (p.remesh.V * turn.transpose()).eval();
  project_onto(p.remesh, p.source);
  return p;
}

struct Box {
  double sx = 2.0, sy = 1.0, sz = 1.5;
  double diagonal() const { return std::sqrt(sx * sx + sy * sy + sz * sz); }
  // Distance of p to the surface of the box [0,sx]×[0,sy]×[0,sz].
  double distance(const Vec3& p) const {
    const Vec3 hi(sx, sy, sz);
    const Vec3 outside = p.cwiseMax(Vec3::Zero()).cwiseMin(hi) - p;
    if (outside.norm() > 0.0) return outside.norm();
    return std::min(p.minCoeff(), (hi - p).minCoeff());
  }
};

// A closed box with n×n cells per face whose vertices slid along its faces (face vertices) and
// edges (edge vertices) by up to `amount` cell sizes: flat faces, sharp edges and corners,
// irregular triangles.
inline TriMesh jittered_box(const Box& box, int n, double amount, uint32_t seed) {
  TriMesh mesh = make_box(n, box.sx, box.sy, box.sz);
  Jitter jitter(seed);
  const Vec3 hi(box.sx, box.sy, box.sz);
  const Vec3 cell = hi / n;
  const double eps = 1e-9;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    Vec3 p = mesh.vertex(i);
    int on_bound = 0;
    bool free_axis[3];
    for (int a = 0; a < 3; ++a) {
      const bool bound = std::abs(p[a]) < eps || std::abs(p[a] - hi[a]) < eps;
      free_axis[a] = !bound;
      on_bound += bound;
    }
    for (int a = 0; a < 3; ++a) {
      const double d = jitter();
      if (on_bound < 3 && free_axis[a]) p[a] += amount * cell[a] * d;
    }
    mesh.V.row(i) = p.transpose();
  }
  return mesh;
}

// A template (icosphere) and a target with its connectivity: the template's vertices slid along
// the sphere by a smooth field, then the sphere stretched into an ellipsoid.
struct CrossparamPair {
  TriMesh templ;
  TriMesh target;
};

inline CrossparamPair crossparam_pair() {
  CrossparamPair p;
  p.templ = make_icosphere(3, 1.0);
  p.target = p.templ;
  const double h = mean_edge_length(p.templ);
  for (int i = 0; i < p.target.num_vertices(); ++i) {
    const Vec3 x = p.templ.vertex(i);
    // A tangential field: the gradient of a smooth function, projected onto the tangent plane.
    Vec3 g(std::cos(3 * x.y() + 1), std::sin(2 * x.z()), std::cos(4 * x.x() - x.z()));
    g -= g.dot(x) * x;
    Vec3 y = (x + 0.6 * h * g).normalized();
    y = y.cwiseProduct(Vec3(1.3, 1.0, 0.8));
    p.target.V.row(i) = y.transpose();
  }
  return p;
}

}  // namespace sm::test
