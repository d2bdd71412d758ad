#include "geometry/weights.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace sm {
namespace {

// Boundary vertices get weights over their two boundary neighbours p, q only:
// λ_p = |t_q − t_i| / (|t_p − t_i| + |t_q − t_i|), λ_q likewise; the other entries stay in the
// pattern with weight 0.
void apply_curve_weights(const TriMesh& templ, ShapeWeights& w) {
  const int n = templ.num_vertices();
  // Boundary half-edges (a→b) are those without a twin (b→a).
  std::vector<std::pair<uint64_t, int>> half;
  half.reserve(static_cast<size_t>(templ.num_triangles()) * 3);
  for (int t = 0; t < templ.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = templ.F(t, k), b = templ.F(t, (k + 1) % 3);
      half.emplace_back((uint64_t(a) << 32) | b, 0);
    }
  std::vector<uint64_t> keys;
  keys.reserve(half.size());
  for (auto& h : half) keys.push_back(h.first);
  std::sort(keys.begin(), keys.end());
  std::vector<std::vector<int>> bnb(n);
  for (uint64_t k : keys) {
    const uint32_t a = k >> 32, b = k & 0xffffffffu;
    const uint64_t twin = (uint64_t(b) << 32) | a;
    if (!std::binary_search(keys.begin(), keys.end(), twin)) {
      bnb[a].push_back(static_cast<int>(b));
      bnb[b].push_back(static_cast<int>(a));
    }
  }
  for (int i = 0; i < n; ++i) {
    if (bnb[i].size() != 2 || bnb[i][0] == bnb[i][1]) continue;
    const int p = bnb[i][0], q = bnb[i][1];
    const double lp = (templ.vertex(p) - templ.vertex(i)).norm();
    const double lq = (templ.vertex(q) - templ.vertex(i)).norm();
    if (!(lp > 0.0) || !(lq > 0.0)) continue;
    for (SparseMatrixR::InnerIterator it(w.lambda, i); it; ++it)
      it.valueRef() = it.col() == p ? lq / (lp + lq) : it.col() == q ? lp / (lp + lq) : 0.0;
  }
}

}  // namespace

ShapeWeights compute_weights(const TriMesh& templ, WeightKind kind, BoundaryWeights boundary) {
  const int n = templ.num_vertices(), m = templ.num_triangles();
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(m) * 6);
  std::vector<uint8_t> degenerate(n, 0);
  for (int t = 0; t < m; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int i = templ.F(t, k), j = templ.F(t, (k + 1) % 3), l = templ.F(t, (k + 2) % 3);
      if (kind == WeightKind::Uniform) {
        // Each undirected neighbour counted once later: store 1 per half-edge (i→j), and sum
        // duplicates into a flag below.
        trip.emplace_back(i, j, 1.0);
        trip.emplace_back(i, l, 1.0);
        continue;
      }
      const Vec3 ti = templ.vertex(i);
      const Vec3 e1 = templ.vertex(j) - ti, e2 = templ.vertex(l) - ti;
      const double l1 = e1.norm(), l2 = e2.norm();
      const double cross = e1.cross(e2).norm();
      const double denom = l1 * l2 + e1.dot(e2);
      // Degenerate corner: coincident vertices, zero area (collinear), or an angle of π.
      if (!(l1 > 0.0) || !(l2 > 0.0) || !(cross > 1e-12 * l1 * l2) || !(denom > 0.0)) {
        degenerate[i] = 1;
        trip.emplace_back(i, j, 0.0);  // keep the neighbour in the pattern
        trip.emplace_back(i, l, 0.0);
        continue;
      }
      const double tan_half = cross / denom;
      trip.emplace_back(i, j, tan_half / l1);
      trip.emplace_back(i, l, tan_half / l2);
    }
  }
  ShapeWeights out;
  out.lambda.resize(n, n);
  out.lambda.setFromTriplets(trip.begin(), trip.end());
  out.lambda.makeCompressed();
  for (int i = 0; i < n; ++i) {
    const bool uniform = kind == WeightKind::Uniform || degenerate[i];
    if (kind == WeightKind::MeanValue && degenerate[i]) ++out.fallback_vertices;
    double sum = 0.0;
    for (SparseMatrixR::InnerIterator it(out.lambda, i); it; ++it) {
      if (uniform) it.valueRef() = 1.0;  // one per neighbour, however many triangles share it
      sum += it.value();
    }
    if (sum > 0.0)
      for (SparseMatrixR::InnerIterator it(out.lambda, i); it; ++it) it.valueRef() /= sum;
  }
  if (boundary == BoundaryWeights::Curve) apply_curve_weights(templ, out);
  return out;
}

SparseMatrixR shape_matrix(const ShapeWeights& weights) {
  const int n = static_cast<int>(weights.lambda.rows());
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(weights.lambda.nonZeros() + n);
  for (int i = 0; i < n; ++i) {
    double row_sum = 0.0;
    for (SparseMatrixR::InnerIterator it(weights.lambda, i); it; ++it) {
      trip.emplace_back(i, it.col(), -it.value());
      row_sum += it.value();
    }
    trip.emplace_back(i, i, row_sum > 0.0 ? 1.0 : 0.0);
  }
  SparseMatrixR A(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  A.makeCompressed();
  return A;
}

}  // namespace sm
