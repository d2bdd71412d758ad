#include "pipeline/sequence/fold_check.hpp"

#include <algorithm>

#include "io/csv.hpp"

namespace sm {

namespace {

// Twice the area vector of triangle t.
Vec3 area_normal(const Positions& V, const Triangles& F, int t) {
  const Vec3 p0 = V.row(F(t, 0)).transpose();
  return (V.row(F(t, 1)).transpose() - p0).cross(V.row(F(t, 2)).transpose() - p0);
}

double longest_edge2(const Positions& V, const Triangles& F, int t) {
  double l2 = 0.0;
  for (int k = 0; k < 3; ++k)
    l2 = std::max(l2, (V.row(F(t, k)) - V.row(F(t, (k + 1) % 3))).squaredNorm());
  return l2;
}

}  // namespace

FoldCount count_folded_triangles(const Triangles& F, const Topology& topology,
                                 const Positions& input, const Positions& output,
                                 std::vector<int>* folded) {
  if (folded) folded->clear();
  const int m = static_cast<int>(F.rows());
  Positions unit(m, 3);  // unit input normals, zero for degenerate input triangles
  std::vector<char> degenerate(size_t(m), 0);
  for (int t = 0; t < m; ++t) {
    const Vec3 n = area_normal(input, F, t);
    const double len = n.norm();
    degenerate[size_t(t)] = !(len > 1e-12 * longest_edge2(input, F, t));
    const Vec3 u = degenerate[size_t(t)] ? Vec3::Zero() : Vec3(n / len);
    unit.row(t) = u.transpose();
  }
  FoldCount count;
  for (int t = 0; t < m; ++t) {
    if (degenerate[size_t(t)]) {
      ++count.degenerate_input;
      continue;
    }
    Vec3 around = Vec3::Zero();
    for (int nb : topology.triangle_neighbours[size_t(t)])
      if (nb >= 0) around += unit.row(nb).transpose();
    const Vec3 n_in = unit.row(t).transpose();
    if (n_in.dot(around) < 0.0) {
      ++count.folded_input;
      continue;
    }
    if (area_normal(output, F, t).dot(n_in) < 0.0) {
      ++count.folded;
      if (folded) folded->push_back(t);
    }
  }
  return count;
}

std::string non_finite_positions(const Positions& V) {
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    if (!V.row(i).allFinite())
      return "vertex " + std::to_string(i) + " has a non-finite coordinate (" +
             format_number(V(i, 0)) + ", " + format_number(V(i, 1)) + ", " +
             format_number(V(i, 2)) + ")";
  return "";
}

}  // namespace sm
