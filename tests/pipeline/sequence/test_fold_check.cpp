// The exact fold check of the sequence job (output triangle against the same input triangle) and
// the non-finite position check, on generated meshes.
#include <catch2/catch.hpp>
#include <cmath>

#include "mesh/primitives.hpp"
#include "mesh/topology.hpp"
#include "pipeline/sequence/fold_check.hpp"

using namespace sm;

namespace {

FoldCount folds(const TriMesh& input, const Positions& output) {
  return count_folded_triangles(input.F, build_topology(input), input.V, output);
}

}  // namespace

TEST_CASE("no fold: the same positions, a small rigid motion, a scaling, sharp creases") {
  const TriMesh box = make_box(4, 1.0, 2.0, 0.5);  // 90 degree creases everywhere
  CHECK(folds(box, box.V).folded == 0);
  CHECK(folds(box, box.V).degenerate_input == 0);
  CHECK(folds(box, box.V).folded_input == 0);
  // The output lies on the input's surface: it may turn a little, never half a turn.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Positions moved = (box.V * R.transpose()).rowwise() + Eigen::RowVector3d(5, -1, 2);
  CHECK(folds(box, moved).folded == 0);
  CHECK(folds(box, 3.0 * box.V).folded == 0);
}

TEST_CASE("a vertex pushed through the surface folds its triangles, and only those") {
  const TriMesh grid = make_grid(6, 6, 1.0, 1.0);  // in the plane z = 0
  Positions out = grid.V;
  // An interior vertex moved past its neighbours in the plane: the triangles on one side flip.
  const int v = 3 * 7 + 3;
  out(v, 0) += 0.5;
  const FoldCount count = folds(grid, out);
  CHECK(count.folded > 0);
  CHECK(count.folded <= 6);  // its one-ring
  // Mirroring the whole grid flips every triangle.
  Positions mirrored = grid.V;
  mirrored.col(0) *= -1.0;
  CHECK(folds(grid, mirrored).folded == grid.num_triangles());
}

TEST_CASE("triangles degenerate or folded in the input are not judged") {
  TriMesh grid = make_grid(4, 4, 1.0, 1.0);
  // Collapse vertex 6 onto vertex 5: the triangles with both are degenerate in the input.
  TriMesh collapsed = grid;
  collapsed.V.row(6) = collapsed.V.row(5);
  const FoldCount c = folds(collapsed, grid.V);
  CHECK(c.degenerate_input > 0);
  CHECK(c.folded == 0);
  // An input with a fold (interior vertex pushed across its neighbours): an output that unfolds
  // it (the flat grid) flips those triangles back, which is no fault.
  TriMesh folded = grid;
  folded.V(6, 0) += 0.5;
  const FoldCount back = folds(folded, grid.V);
  CHECK(back.folded_input > 0);
  CHECK(back.folded == 0);
}

TEST_CASE("non-finite positions are named by vertex") {
  Positions V = Positions::Zero(3, 3);
  CHECK(non_finite_positions(V).empty());
  V(2, 1) = std::nan("");
  CHECK(non_finite_positions(V) == "vertex 2 has a non-finite coordinate (0, nan, 0)");
  V(1, 2) = INFINITY;
  CHECK(non_finite_positions(V) == "vertex 1 has a non-finite coordinate (0, 0, inf)");
}
