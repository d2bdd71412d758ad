#include <catch2/catch.hpp>

#include <random>

#include <Eigen/Geometry>

#include "geometry/weights.hpp"
#include "mesh/primitives.hpp"
#include "mesh/topology.hpp"

using namespace sm;

namespace {

// A planar grid with its interior vertices jittered (still a valid triangulation).
TriMesh jittered_grid(int n, unsigned seed, double amount) {
  TriMesh m = make_grid(n, n, 1.0, 1.0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  const Topology t = build_topology(m);
  for (int i = 0; i < m.num_vertices(); ++i)
    if (!t.is_boundary_vertex[i]) m.V.row(i) += Vec3(u(rng), u(rng), 0.0).transpose() / n;
  return m;
}

// Weights are convex: non-negative, summing to one; `strict`: every neighbour weighs > 0.
void check_convex(const ShapeWeights& w, int n, bool strict = true) {
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    int count = 0;
    for (SparseMatrixR::InnerIterator it(w.lambda, i); it; ++it) {
      if (strict)
        CHECK(it.value() > 0.0);
      else
        CHECK(it.value() >= 0.0);
      CHECK(it.col() != i);
      sum += it.value();
      ++count;
    }
    if (count > 0) CHECK(sum == Approx(1.0).epsilon(1e-12));
  }
}

}  // namespace

TEST_CASE("mean value weights are positive and sum to one", "[weights]") {
  const std::vector<TriMesh> meshes = {make_icosphere(2, 1.0), make_torus(20, 10, 2.0, 0.6),
                                       make_box(3, 1.0, 2.0, 0.5), jittered_grid(8, 1, 0.3),
                                       make_cylinder(12, 5, 1.0, 2.0)};
  for (const TriMesh& m : meshes) {
    const ShapeWeights w = compute_weights(m, WeightKind::MeanValue, BoundaryWeights::OneSided);
    CHECK(w.fallback_vertices == 0);
    check_convex(w, m.num_vertices());
    check_convex(compute_weights(m, WeightKind::Uniform, BoundaryWeights::OneSided),
                 m.num_vertices());
    // Curve weights give boundary vertices' interior neighbours weight 0.
    check_convex(compute_weights(m, WeightKind::MeanValue), m.num_vertices(), false);
  }
}

TEST_CASE("mean value weights reproduce planar interior one-rings", "[weights]") {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    TriMesh m = jittered_grid(10, seed, 0.35);
    // Tilt the plane: reproduction must not depend on the plane's orientation.
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
    m.V = (m.V * R.transpose()).eval();
    const Topology t = build_topology(m);
    const ShapeWeights w = compute_weights(m, WeightKind::MeanValue);
    const Positions centre = w.lambda * m.V;
    for (int i = 0; i < m.num_vertices(); ++i)
      if (!t.is_boundary_vertex[i])
        CHECK((centre.row(i) - m.V.row(i)).norm() < 1e-12);
  }
}

TEST_CASE("uniform weights are one over the valence", "[weights]") {
  const TriMesh m = make_icosphere(1, 1.0);
  const ShapeWeights w = compute_weights(m, WeightKind::Uniform);  // closed: no boundary rule
  const Topology t = build_topology(m);
  for (int i = 0; i < m.num_vertices(); ++i)
    for (SparseMatrixR::InnerIterator it(w.lambda, i); it; ++it)
      CHECK(it.value() == Approx(1.0 / t.one_ring.size(i)));
}

TEST_CASE("degenerate template corners fall back to uniform weights", "[weights]") {
  TriMesh m = make_grid(2, 2, 1.0, 1.0);
  m.V.row(4) = m.V.row(1);  // centre vertex collapses onto an edge vertex: zero-length edge
  const ShapeWeights w = compute_weights(m, WeightKind::MeanValue, BoundaryWeights::OneSided);
  CHECK(w.fallback_vertices >= 1);
  check_convex(w, m.num_vertices());
}

TEST_CASE("A = I - Lambda annihilates constants", "[weights]") {
  const TriMesh m = make_torus(12, 8, 2.0, 0.5);
  const SparseMatrixR A = shape_matrix(compute_weights(m, WeightKind::MeanValue));
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(m.num_vertices());
  CHECK((A * ones).cwiseAbs().maxCoeff() < 1e-13);
  for (int i = 0; i < m.num_vertices(); ++i) CHECK(A.coeff(i, i) == 1.0);
}

TEST_CASE("curve weights reproduce straight boundaries, one-sided weights do not", "[weights]") {
  const TriMesh m = make_grid(8, 6, 8.0, 6.0);
  const Topology t = build_topology(m);
  const ShapeWeights curve = compute_weights(m, WeightKind::MeanValue, BoundaryWeights::Curve);
  const ShapeWeights one_sided =
      compute_weights(m, WeightKind::MeanValue, BoundaryWeights::OneSided);
  const Positions c = curve.lambda * m.V, o = one_sided.lambda * m.V;
  double one_sided_max = 0.0;
  for (int i = 0; i < m.num_vertices(); ++i) {
    if (!t.is_boundary_vertex[i]) {
      CHECK((c.row(i) - m.V.row(i)).norm() < 1e-12);  // interior: the same mean value weights
      CHECK((c.row(i) - o.row(i)).norm() < 1e-12);
      continue;
    }
    const bool corner = (m.V(i, 0) == 0.0 || m.V(i, 0) == 8.0) && (m.V(i, 1) == 0.0 || m.V(i, 1) == 6.0);
    if (!corner) CHECK((c.row(i) - m.V.row(i)).norm() < 1e-12);
    one_sided_max = std::max(one_sided_max, (o.row(i) - m.V.row(i)).norm());
  }
  CHECK(one_sided_max > 0.3);  // the inward pull the curve weights remove
  check_convex(one_sided, m.num_vertices());
  // Curve weights leave interior neighbours of boundary vertices at 0 (kept in the pattern).
  for (int i = 0; i < m.num_vertices(); ++i) {
    double sum = 0.0;
    for (SparseMatrixR::InnerIterator it(curve.lambda, i); it; ++it) {
      CHECK(it.value() >= 0.0);
      sum += it.value();
    }
    CHECK(sum == Approx(1.0));
  }
}
