// The rotated template target δ_i = R_i (A T)_i (massage/shape_target.hpp): frames with the
// template's shapes are fixed points of the optimizer, which the paper's δ = 0 does not give on
// curved templates.
#include <catch2/catch.hpp>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "geometry/shear.hpp"
#include "io/mesh_file.hpp"
#include "massage/linear_solver.hpp"
#include "massage/massage.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

namespace {

// An icosphere with radial bumps: curved everywhere, irregular curvature and triangle shapes.
TriMesh bumpy_sphere() {
  TriMesh m = make_icosphere(3, 1.0);
  for (int i = 0; i < m.num_vertices(); ++i) {
    const Vec3 p = m.vertex(i);
    const double r =
        1.0 + 0.15 * std::sin(3 * p.x()) * std::cos(2 * p.y()) + 0.1 * std::sin(5 * p.z());
    m.V.row(i) = (r * p).transpose();
  }
  return m;
}

// An open cylinder with bumps: two boundary loops, whose curve weights form closed classes of Λ.
TriMesh bumpy_tube() {
  TriMesh m = make_cylinder(20, 12, 1.0, 3.0);
  for (int i = 0; i < m.num_vertices(); ++i) {
    const double z = m.V(i, 2), a = std::atan2(m.V(i, 1), m.V(i, 0));
    const double r = 1.0 + 0.2 * std::sin(2 * z) * std::cos(3 * a);
    m.V(i, 0) *= r;
    m.V(i, 1) *= r;
  }
  return m;
}

// Two components side by side: the bumpy sphere and a torus.
TriMesh two_components() {
  const TriMesh a = bumpy_sphere(), b = make_torus(24, 12, 1.5, 0.5);
  TriMesh m;
  m.V.resize(a.num_vertices() + b.num_vertices(), 3);
  m.V << a.V, (b.V.rowwise() + Eigen::RowVector3d(4.0, 0.5, 0.0));
  m.F.resize(a.num_triangles() + b.num_triangles(), 3);
  m.F << a.F, (b.F.array() + a.num_vertices()).matrix();
  return m;
}

Eigen::Matrix3d rotation(double ax, double ay, double az) {
  return (Eigen::AngleAxisd(az, Vec3::UnitZ()) * Eigen::AngleAxisd(ay, Vec3::UnitY()) *
          Eigen::AngleAxisd(ax, Vec3::UnitX()))
      .toRotationMatrix();
}

Positions rigid(const Positions& V, const Eigen::Matrix3d& R, const Vec3& t) {
  return ((V * R.transpose()).rowwise() + t.transpose()).eval();
}

// The optimizer started on `frame` with `frame` as its reference surface: how far the result is
// from the frame, relative to the frame's bounding-box diagonal.
double drift(const Massager& m, const TriMesh& frame) {
  const Reference ref(frame, m.options().samples, "frame", m.shared_topology());
  const MassageResult r = m.run(frame.V, ref);
  REQUIRE(r.ok);
  return (r.V - frame.V).rowwise().norm().maxCoeff() / bounding_box_diagonal(frame.V);
}

MassageOptions with_target(ShapeTargetKind k) {
  MassageOptions o;
  o.shape_target = k;
  return o;
}

}  // namespace

TEST_CASE("the template, a rigid copy and a frame with its shapes on another pose are fixed points",
          "[massage][shape_target]") {
  const std::vector<std::pair<const char*, TriMesh>> meshes = {
      {"bumpy sphere", bumpy_sphere()},
      {"torus", make_torus(30, 14, 2.0, 0.7)},
      {"bumpy open tube", bumpy_tube()}};
  for (const auto& [name, T] : meshes) {
    INFO(name);
    const Massager templ(T, with_target(ShapeTargetKind::Template));
    const Massager zero(T, with_target(ShapeTargetKind::Zero));
    const double h = mean_edge_length(T) / bounding_box_diagonal(T.V);
    // T itself.
    CHECK(drift(templ, T) <= 1e-9);
    // A rigid copy.
    const TriMesh moved{rigid(T.V, rotation(0.7, -1.9, 2.4), Vec3(3.0, -1.0, 0.5)), T.F};
    CHECK(drift(templ, moved) <= 1e-9);
    // The paper's δ = 0 drifts both (tangential part of the curved template's Laplacian).
    CHECK(drift(zero, T) > 1e-3 * h);
    CHECK(drift(zero, moved) > 1e-3 * h);
  }
  // Another pose: each component moved by its own rigid motion (one-rings congruent to T's).
  const TriMesh T = two_components();
  const int na = bumpy_sphere().num_vertices();
  TriMesh pose = T;
  pose.V.topRows(na) = rigid(T.V.topRows(na), rotation(0.3, 0.2, -0.4), Vec3(0.0, 0.0, 1.0));
  pose.V.bottomRows(T.num_vertices() - na) =
      rigid(T.V.bottomRows(T.num_vertices() - na), rotation(-1.2, 0.8, 2.0), Vec3(-1.0, 2.0, 0.0));
  CHECK(drift(Massager(T, with_target(ShapeTargetKind::Template)), pose) <= 1e-9);
  CHECK(drift(Massager(T, with_target(ShapeTargetKind::Zero)), pose) >
        1e-3 * mean_edge_length(T) / bounding_box_diagonal(T.V));
}

TEST_CASE("the target is T's Laplacian for T and turns with a rigid motion", "[shape_target]") {
  for (const TriMesh& T : {bumpy_sphere(), bumpy_tube(), make_grid(6, 5, 1.0, 1.0)}) {
    const Topology topo = build_topology(T);
    const ShapeWeights w = compute_weights(T, WeightKind::MeanValue);
    const ShapeTarget target(T, w.lambda, topo);
    Positions AT, delta;
    multiply(shape_matrix(w), T.V, AT);
    CHECK(target.evaluate(T.V, T.F, w.lambda, topo, delta) == 0);
    const double scale = AT.rowwise().norm().maxCoeff() + mean_edge_length(T);
    CHECK((delta - AT).cwiseAbs().maxCoeff() <= 1e-12 * scale);
    const Eigen::Matrix3d R = rotation(2.1, 0.4, -0.9);
    target.evaluate(rigid(T.V, R, Vec3(1, 2, 3)), T.F, w.lambda, topo, delta);
    CHECK((delta - AT * R.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * scale);
  }
}

TEST_CASE("a vertex without a normal in the start keeps the paper's target", "[shape_target]") {
  // An interior vertex of the open tube (not in a closed class of Λ, whose targets are shifted
  // together), with its neighbours collapsed onto it: no area around it.
  const TriMesh T = bumpy_tube();
  const Topology topo = build_topology(T);
  const ShapeWeights w = compute_weights(T, WeightKind::MeanValue);
  const ShapeTarget target(T, w.lambda, topo);
  CHECK(target.projected_classes() == 2);  // the two boundary loops
  const int v = T.num_vertices() / 2;      // on the middle ring
  REQUIRE_FALSE(topo.is_boundary_vertex[v]);
  Positions S = T.V;
  for (int p = topo.one_ring.begin(v); p < topo.one_ring.end(v); ++p)
    S.row(topo.one_ring.data[p]) = S.row(v);
  Positions delta;
  // v, and neighbours whose every triangle also collapsed.
  CHECK(target.evaluate(S, T.F, w.lambda, topo, delta) >= 1);
  CHECK(delta.row(v).isZero(0.0));
  CHECK(delta.allFinite());
}

TEST_CASE("the target is the same for 1 and N threads", "[shape_target]") {
  const TriMesh T = two_components();
  const Topology topo = build_topology(T);
  const ShapeWeights w = compute_weights(T, WeightKind::MeanValue);
  const ShapeTarget target(T, w.lambda, topo);
  Positions S = rigid(T.V, rotation(0.1, 0.2, 0.3), Vec3::Zero());
  for (int i = 0; i < S.rows(); ++i)
    S.row(i) += 0.01 * Eigen::RowVector3d(std::sin(i), std::cos(3 * i), 0);
  Positions one, many;
  {
    tbb::task_arena arena(1);
    arena.execute([&] { target.evaluate(S, T.F, w.lambda, topo, one); });
  }
  target.evaluate(S, T.F, w.lambda, topo, many);
  CHECK(one == many);
}

TEST_CASE("the target is consistent on a small boundary loop", "[shape_target]") {
  // A wavy grid with one triangle removed: its three corners form a boundary loop whose rows of
  // A (curve weights) reference only each other, a singular 3×3 block. The frame bends the grid
  // onto a cylinder and slides it, so the rings turn by different rotations.
  TriMesh T = make_grid(12, 12, 12.0, 12.0);
  for (int i = 0; i < T.num_vertices(); ++i)
    T.V(i, 2) = 0.8 * std::sin(0.5 * T.V(i, 0)) * std::cos(0.4 * T.V(i, 1));
  const int removed = T.num_triangles() / 2 + 6;
  Triangles F(T.num_triangles() - 1, 3);
  F << T.F.topRows(removed), T.F.bottomRows(T.num_triangles() - removed - 1);
  const std::array<int, 3> hole = {T.F(removed, 0), T.F(removed, 1), T.F(removed, 2)};
  T.F = F;
  Positions S = T.V;
  for (int i = 0; i < S.rows(); ++i) {
    const double x = T.V(i, 0) - 6 + 0.3 * std::sin(0.9 * T.V(i, 1)), y = T.V(i, 1),
                 r = 2 + T.V(i, 2);
    S.row(i) << r * std::sin(x / 2), y + 0.2 * std::cos(0.7 * x), r * std::cos(x / 2);
  }
  const Topology topo = build_topology(T);
  const ShapeWeights w = compute_weights(T, WeightKind::MeanValue);
  const ShapeTarget target(T, w.lambda, topo);
  REQUIRE(target.projected_classes() == 2);  // the outer boundary and the hole
  Positions delta;
  target.evaluate(S, T.F, w.lambda, topo, delta);
  // A_CC y = δ_C is solvable iff δ_C is orthogonal to the kernel of A_CCᵀ.
  Eigen::Matrix3d A_CC = Eigen::Matrix3d::Identity();
  for (int a = 0; a < 3; ++a)
    for (SparseMatrixR::InnerIterator it(w.lambda, hole[a]); it; ++it) {
      const auto b = std::find(hole.begin(), hole.end(), static_cast<int>(it.col())) - hole.begin();
      if (it.value() != 0.0) {
        REQUIRE(b < 3);  // the loop's rows reference only the loop
        A_CC(a, b) -= it.value();
      }
    }
  const Eigen::MatrixXd kernel = Eigen::FullPivLU<Eigen::Matrix3d>(A_CC.transpose()).kernel();
  REQUIRE(kernel.cols() == 1);
  Eigen::Matrix3d delta_C;
  for (int a = 0; a < 3; ++a) delta_C.row(a) = delta.row(hole[a]);
  CHECK((kernel.transpose() * delta_C).norm() <= 1e-12 * delta_C.norm());
  CHECK(delta_C.norm() > 0.1);  // not trivially consistent
}

TEST_CASE("horse gallop: frames with the template's shapes stay, needles and a small hole survive",
          "[massage][shape_target][data]") {
  const std::filesystem::path dir =
      std::filesystem::path(SEQMASSAGE_SHARED_DATA_DIR) / "sequences/sumner_horse_gallop";
  if (!std::filesystem::exists(dir / "frame_0003.obj")) {
    WARN("shared data not found under " << dir.string() << ": test skipped");
    return;
  }
  const TriMesh T = read_mesh(dir / "frame_0000.obj");
  const Massager m(T, MassageOptions{});
  for (const char* name : {"frame_0003.obj", "frame_0006.obj"}) {
    INFO(name);
    const TriMesh S = read_mesh(dir / name);
    const Reference ref(S, SampleKind::Vertices, "frame", m.shared_topology());
    const MassageResult r = m.run(S.V, ref);
    REQUIRE(r.ok);
    const Eigen::VectorXd before = shear_distortion(T.V, S.V, T.F);
    const Eigen::VectorXd after = shear_distortion(T.V, r.V, T.F);
    INFO("shear max " << before.maxCoeff() << " -> " << after.maxCoeff() << ", mean "
                      << before.mean() << " -> " << after.mean());
    // Frame 6 has frame 0's shapes (mean shear 4e-8): it stays. Frame 3 has needles (radius
    // ratio down to 3e-4) and a three-vertex hole; with δ = 0 its maximum shear went 62 -> 860,
    // with the target but without the hole's consistency 62 -> 72.
    CHECK(after.mean() <= before.mean());
    CHECK(after.maxCoeff() <= before.maxCoeff());
  }
}
