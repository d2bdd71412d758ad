// Fold repair (checks.repair_folds, docs/fold-repair.md) on generated meshes: a template with a
// vertex pushed across its neighbour makes the massage (with the template's shapes as target)
// fold the output there; the repair removes the fold and leaves the rest of the frame's result.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "massage/massage.hpp"
#include "mesh/primitives.hpp"
#include "mesh/topology.hpp"
#include "pipeline/sequence/fold_check.hpp"
#include "pipeline/sequence/fold_repair.hpp"

using namespace sm;

namespace {

struct FoldCase {
  TriMesh templ;    // a flat grid with a few vertices pushed across a neighbour
  TriMesh input;    // the flat grid, its vertices slid at random in the plane
  Topology topology;
  std::vector<int> pushed;
};

// A 16×16-cell grid; the template has the vertices `pushed` moved by `push` cells in x, past their
// right neighbour, so the template's triangles there are folded; the input frame is clean.
FoldCase fold_case(const std::vector<int>& pushed, double push) {
  FoldCase c;
  const TriMesh grid = make_grid(16, 16, 16.0, 16.0);
  c.templ = grid;
  for (int v : pushed) c.templ.V(v, 0) += push;
  c.input = grid;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  for (int i = 0; i < grid.num_vertices(); ++i) {
    if (grid.V(i, 0) <= 0 || grid.V(i, 0) >= 16 || grid.V(i, 1) <= 0 || grid.V(i, 1) >= 16)
      continue;  // the boundary stays where it is
    c.input.V(i, 0) += jitter(rng);
    c.input.V(i, 1) += jitter(rng);
  }
  c.topology = build_topology(grid);
  c.pushed = pushed;
  return c;
}

int vertex_at(int x, int y) { return 17 * y + x; }

MassageOptions template_target() {
  MassageOptions o;
  o.shape_target = ShapeTargetKind::Template;
  return o;
}

// The massage of a fold case's input against the template's shapes, and the triangles it folds.
struct Massaged {
  Massager massager;
  Reference reference;
  MassageResult first;
  std::vector<int> folded;
  Massaged(const FoldCase& c, const MassageOptions& o)
      : massager(c.templ, o),
        reference(c.input, o.samples, "input", massager.shared_topology()),
        first(massager.run(c.input.V, reference)) {
    if (first.ok) count_folded_triangles(c.templ.F, c.topology, c.input.V, first.V, &folded);
  }
};

}  // namespace

TEST_CASE("ring distances and repair weights ramp from the folds") {
  const TriMesh grid = make_grid(8, 8, 1.0, 1.0);
  const Topology topo = build_topology(grid);
  std::vector<unsigned char> seeds(size_t(grid.num_vertices()), 0);
  const int centre = 9 * 4 + 4;
  seeds[size_t(centre)] = 1;
  const std::vector<int> d = ring_distance(topo, seeds, 2);
  CHECK(d[size_t(centre)] == 0);
  for (int p = topo.one_ring.begin(centre); p < topo.one_ring.end(centre); ++p)
    CHECK(d[size_t(topo.one_ring.data[size_t(p)])] == 1);
  CHECK(d[0] == 3);  // a corner, beyond the limit
  const std::vector<double> w = repair_weights(topo, seeds, 2, {});
  CHECK(w[size_t(centre)] == 0.0);
  CHECK(w[size_t(topo.one_ring.data[size_t(topo.one_ring.begin(centre))])] == Approx(1.0 / 3));
  CHECK(w[0] == 1.0);
  std::vector<double> base(w.size(), 0.5);
  CHECK(repair_weights(topo, seeds, 2, base)[0] == 0.5);  // capped by the user's weights
}

TEST_CASE("the repair removes a fold the massage makes and keeps the result elsewhere") {
  const FoldCase c = fold_case({vertex_at(8, 8)}, 1.6);
  const MassageOptions o = template_target();
  const Massaged m(c, o);
  const MassageResult& first = m.first;
  const Reference& reference = m.reference;
  const std::vector<int>& folded = m.folded;
  REQUIRE(first.ok);
  const int before = static_cast<int>(folded.size());
  INFO("folded before the repair: " << before);
  REQUIRE(before > 0);

  const FoldRepair fix =
      repair_folds(c.templ, o, c.topology, c.input.V, reference, folded, 2, 4);
  REQUIRE(fix.repaired);
  CHECK(fix.folded_left == 0);
  CHECK(count_folded_triangles(c.templ.F, c.topology, c.input.V, fix.V).folded == 0);
  CHECK(fix.pinned >= 3);
  // Far from the fold (more than 5 rings away) the vertices keep the first result, to a small
  // part of how far the massage moved them (the re-solve is global: measured 14 % on this
  // 289-vertex grid).
  std::vector<unsigned char> seeds(size_t(c.input.num_vertices()), 0);
  for (int t : folded)
    for (int a = 0; a < 3; ++a) seeds[size_t(c.templ.F(t, a))] = 1;
  const std::vector<int> d = ring_distance(c.topology, seeds, 5);
  double moved = 0.0, changed = 0.0;
  int far = 0;
  for (int i = 0; i < c.input.num_vertices(); ++i) {
    if (d[size_t(i)] <= 5) continue;
    moved += (first.V.row(i) - c.input.V.row(i)).norm();
    changed += (fix.V.row(i) - first.V.row(i)).norm();
    ++far;
  }
  INFO(far << " far vertices: mean move of the massage " << moved / far
           << ", mean change by the repair " << changed / far);
  REQUIRE(far > 100);
  CHECK(moved / far > 0.02);
  CHECK(changed < 0.25 * moved);
}

TEST_CASE("with 0 rings the repair keeps just the folds' corners at the input") {
  // 35 vertices pushed five cells across their neighbours: over a hundred folded triangles.
  // (Tried as a case where the repair fails, with 1 round and no ramp: the repair still
  // succeeds, so the unrepaired path is covered by the frame checks' tests only.)
  std::vector<int> pushed;
  for (int y = 5; y <= 11; ++y)
    for (int x = 4; x <= 12; x += 2) pushed.push_back(vertex_at(x, y));
  const FoldCase c = fold_case(pushed, 5.0);
  const MassageOptions o = template_target();
  const Massaged m(c, o);
  const MassageResult& first = m.first;
  const Reference& reference = m.reference;
  const std::vector<int>& folded = m.folded;
  REQUIRE(first.ok);
  const int before = static_cast<int>(folded.size());
  INFO("folded before the repair: " << before);
  REQUIRE(before > 50);
  std::vector<unsigned char> corner(size_t(c.input.num_vertices()), 0);
  for (int t : folded)
    for (int a = 0; a < 3; ++a) corner[size_t(c.templ.F(t, a))] = 1;

  const FoldRepair fix = repair_folds(c.templ, o, c.topology, c.input.V, reference, folded, 0, 1);
  REQUIRE(fix.repaired);
  CHECK(fix.failure.empty());
  CHECK(fix.rounds == 1);
  CHECK(fix.weighted == 0);  // no ramp
  CHECK(fix.pinned == std::count(corner.begin(), corner.end(), 1));
  for (int i = 0; i < c.input.num_vertices(); ++i)
    if (corner[size_t(i)]) REQUIRE(fix.V.row(i) == c.input.V.row(i));
  CHECK(count_folded_triangles(c.templ.F, c.topology, c.input.V, fix.V).folded == 0);
}
