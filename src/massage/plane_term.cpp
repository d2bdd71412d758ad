#include "massage/plane_term.hpp"

#include <algorithm>
#include <cmath>

namespace sm {
namespace {

constexpr int kSmoothingPasses = 4;  // rings the area change is averaged over (about)

double triangle_area(const Positions& V, const Triangles& F, int t) {
  const Vec3 a = V.row(F(t, 0)).transpose();
  return 0.5 * (V.row(F(t, 1)).transpose() - a).cross(V.row(F(t, 2)).transpose() - a).norm();
}

}  // namespace

Eigen::VectorXd tangential_stiffness(const Positions& T, const Positions& S, const Triangles& F,
                                     const Topology& topology, double stiffness, double adapt) {
  const int n = topology.num_vertices;
  Eigen::VectorXd eps = Eigen::VectorXd::Constant(n, stiffness);
  if (adapt > 0.0) {
    Eigen::VectorXd change = Eigen::VectorXd::Zero(n);  // signed log area ratio per vertex
    for (int v = 0; v < n; ++v) {
      const Csr& vt = topology.vertex_triangles;
      for (int p = vt.begin(v); p < vt.end(v); ++p) {
        const int t = vt.data[p];
        const double at = triangle_area(T, F, t), as = triangle_area(S, F, t);
        if (at > 0.0 && as > 0.0) change[v] += std::log(as / at);
      }
      if (vt.size(v) > 0) change[v] /= vt.size(v);
    }
    Eigen::VectorXd next(n);
    for (int pass = 0; pass < kSmoothingPasses; ++pass) {
      const Csr& ring = topology.one_ring;
      for (int v = 0; v < n; ++v) {
        double sum = change[v];
        for (int p = ring.begin(v); p < ring.end(v); ++p) sum += change[ring.data[p]];
        next[v] = sum / (1 + ring.size(v));
      }
      change.swap(next);
    }
    for (int v = 0; v < n; ++v) eps[v] = std::min(1.0, stiffness + adapt * std::abs(change[v]));
  }
  for (int v = 0; v < n; ++v)
    if (topology.is_boundary_vertex[v]) eps[v] = 1.0;
  return eps;
}

void plane_blocks(const std::vector<SurfacePoint>& v_hat, const Triangles& N_F,
                  const Positions& normals, const Eigen::VectorXd& alpha,
                  const Eigen::VectorXd& epsilon, double mu,
                  const std::vector<unsigned char>& pinned, VertexBlocks& D) {
  const int n = static_cast<int>(v_hat.size());
  D.assign(n, {0.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  for (int i = 0; i < n; ++i) {
    const SurfacePoint& sp = v_hat[i];
    const double d = (1.0 - mu) * alpha[i] * (1.0 - epsilon[i]);
    if (pinned[i] || sp.triangle < 0 || !(d > 0.0)) continue;
    Vec3 nrm = Vec3::Zero();
    for (int a = 0; a < 3; ++a) nrm += sp.bary[a] * normals.row(N_F(sp.triangle, a)).transpose();
    const double len = nrm.norm();
    if (!(len > 0.0)) continue;  // no normal: point-to-point
    nrm /= len;
    // d (I − n nᵀ), in the order xx, yy, zz, xy, xz, yz.
    D[i] = {d * (1.0 - nrm.x() * nrm.x()), d * (1.0 - nrm.y() * nrm.y()),
            d * (1.0 - nrm.z() * nrm.z()), -d * nrm.x() * nrm.y(),
            -d * nrm.x() * nrm.z(),        -d * nrm.y() * nrm.z()};
  }
}

}  // namespace sm
