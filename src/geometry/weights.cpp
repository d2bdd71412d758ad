#include "geometry/weights.hpp"

#include <vector>

namespace sm {

ShapeWeights compute_weights(const TriMesh& templ, WeightKind kind) {
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
