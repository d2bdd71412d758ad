#include "massage/plane_term.hpp"

#include <algorithm>
#include <cmath>

namespace sm {
namespace {

double triangle_area(const Positions& V, const Triangles& F, int t) {
  const Vec3 a = V.row(F(t, 0)).transpose();
  return 0.5 * (V.row(F(t, 1)).transpose() - a).cross(V.row(F(t, 2)).transpose() - a).norm();
}

}  // namespace

Eigen::VectorXd tangential_stiffness(const Positions& T, const Positions& S, const Triangles& F,
                                     const Topology& topology, double stiffness, double adapt,
                                     int passes) {
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
    for (int pass = 0; pass < passes; ++pass) {  // Jacobi passes of 1-ring averaging
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

namespace {

// Adds d (I − n nᵀ) to a block, in the order xx, yy, zz, xy, xz, yz; returns the block applied to
// the point p, (d (I − n nᵀ)) p.
Vec3 add_projector(std::array<double, 6>& block, double d, const Vec3& nrm, const Vec3& p) {
  block[0] += d * (1.0 - nrm.x() * nrm.x());
  block[1] += d * (1.0 - nrm.y() * nrm.y());
  block[2] += d * (1.0 - nrm.z() * nrm.z());
  block[3] -= d * nrm.x() * nrm.y();
  block[4] -= d * nrm.x() * nrm.z();
  block[5] -= d * nrm.y() * nrm.z();
  return d * (p - nrm * nrm.dot(p));
}

}  // namespace

void plane_blocks(const PlaneInputs& in, VertexBlocks& D, Positions& rhs) {
  const SystemPattern& pattern = in.pattern;
  const std::vector<unsigned char>& pinned = in.pinned;
  const Eigen::VectorXd& eps = in.epsilon;
  D.assign(pattern.shape_matrix().nonZeros(), {0.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  const int n = pattern.size();
  for (int i = 0; i < n; ++i) {
    const SurfacePoint& sp = in.v_hat[i];
    const double d = (1.0 - in.mu) * in.alpha[i] * (1.0 - eps[i]);
    if (pinned[i] || sp.triangle < 0 || !(d > 0.0)) continue;
    Vec3 nrm = Vec3::Zero();
    for (int a = 0; a < 3; ++a)
      nrm += sp.bary[a] * in.normals_n.row(in.N_F(sp.triangle, a)).transpose();
    if (!(nrm.norm() > 0.0)) continue;  // no normal: point-to-point
    nrm.normalize();
    rhs.row(i) -= add_projector(D[pattern.diagonal_slot(i)], d, nrm, sp.point).transpose();
  }
  const Triangles& F = in.F;
  const Positions& V = in.V;
  for (size_t j = 0; j < in.w_hat.size(); ++j) {
    const SurfacePoint& sp = in.w_hat[j];
    if (sp.triangle < 0) continue;
    const int t = sp.triangle;
    const Vec3 p0 = V.row(F(t, 0)).transpose();
    Vec3 nrm = (V.row(F(t, 1)).transpose() - p0).cross(V.row(F(t, 2)).transpose() - p0);
    if (!(nrm.norm() > 0.0)) continue;
    nrm.normalize();
    const double e = (eps[F(t, 0)] + eps[F(t, 1)] + eps[F(t, 2)]) / 3.0;
    const double d = (1.0 - in.mu) * in.beta[static_cast<int>(j)] * (1.0 - e);
    if (!(d > 0.0)) continue;
    const Vec3 w = in.samples.row(static_cast<int>(j)).transpose();
    const std::array<int, 9>& slot = pattern.triangle_slots(t);
    for (int a = 0; a < 3; ++a) {
      if (pinned[F(t, a)]) continue;
      for (int b = 0; b < 3; ++b) {
        const double dab = d * sp.bary[a] * sp.bary[b];
        if (dab != 0.0) add_projector(D[slot[3 * a + b]], dab, nrm, Vec3::Zero());
      }
      rhs.row(F(t, a)) -= (d * sp.bary[a] * (w - nrm * nrm.dot(w))).transpose();
    }
  }
}

}  // namespace sm
