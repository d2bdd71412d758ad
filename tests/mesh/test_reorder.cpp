#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <random>
#include <set>

#include "mesh/primitives.hpp"
#include "mesh/reorder.hpp"

using namespace sm;

namespace {

// The mesh with its vertices and triangles shuffled (corners rotated, orientation kept).
TriMesh shuffled(const TriMesh& mesh, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<int> perm(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) perm[i] = i;
  std::shuffle(perm.begin(), perm.end(), rng);  // old i -> new perm[i]
  std::vector<int> tris(mesh.num_triangles());
  for (int t = 0; t < mesh.num_triangles(); ++t) tris[t] = t;
  std::shuffle(tris.begin(), tris.end(), rng);
  TriMesh out{Positions(mesh.V.rows(), 3), Triangles(mesh.F.rows(), 3)};
  for (int i = 0; i < mesh.num_vertices(); ++i) out.V.row(perm[i]) = mesh.V.row(i);
  for (int k = 0; k < mesh.num_triangles(); ++k) {
    const int rot = static_cast<int>(rng() % 3);
    for (int c = 0; c < 3; ++c) out.F(k, c) = perm[mesh.F(tris[k], (c + rot) % 3)];
  }
  return out;
}

// Each triangle as its cyclic rotation starting at its lowest label (orientation kept).
std::multiset<std::array<int, 3>> oriented_triangles(const Triangles& F) {
  std::multiset<std::array<int, 3>> out;
  for (int t = 0; t < F.rows(); ++t) {
    int r = 0;
    for (int c = 1; c < 3; ++c)
      if (F(t, c) < F(t, r)) r = c;
    out.insert({F(t, r), F(t, (r + 1) % 3), F(t, (r + 2) % 3)});
  }
  return out;
}

int bandwidth(const Triangles& F) {
  int b = 0;
  for (int t = 0; t < F.rows(); ++t) b = std::max(b, F.row(t).maxCoeff() - F.row(t).minCoeff());
  return b;
}

}  // namespace

TEST_CASE("banded_order is a relabelling that keeps every triangle and its orientation",
          "[mesh][reorder]") {
  TriMesh two = make_torus(30, 12, 2.0, 0.5);
  const TriMesh sphere = make_icosphere(2, 1.0);
  // Two components and an isolated vertex.
  const int offset = two.num_vertices();
  two.V.conservativeResize(offset + sphere.num_vertices() + 1, 3);
  two.V.bottomRows(sphere.num_vertices() + 1).setZero();
  two.V.middleRows(offset, sphere.num_vertices()) = sphere.V;
  const int m0 = two.num_triangles();
  two.F.conservativeResize(m0 + sphere.num_triangles(), 3);
  two.F.bottomRows(sphere.num_triangles()) = sphere.F.array() + offset;
  for (const TriMesh& mesh :
       {make_grid(20, 9, 1.0, 1.0), shuffled(make_torus(40, 20, 2.0, 0.5), 3), shuffled(two, 5)}) {
    const MeshOrder o = banded_order(mesh);
    const int n = mesh.num_vertices(), m = mesh.num_triangles();
    REQUIRE(static_cast<int>(o.vertex_order.size()) == n);
    REQUIRE(static_cast<int>(o.triangle_order.size()) == m);
    for (int k = 0; k < n; ++k) CHECK(o.vertex_rank[o.vertex_order[k]] == k);
    std::vector<int> seen = o.triangle_order;
    std::sort(seen.begin(), seen.end());
    for (int t = 0; t < m; ++t) CHECK(seen[t] == t);
    // The same oriented triangles, under the new labels.
    Triangles relabelled_old(m, 3);
    for (int t = 0; t < m; ++t)
      for (int c = 0; c < 3; ++c) relabelled_old(t, c) = o.vertex_rank[mesh.F(t, c)];
    CHECK(oriented_triangles(to_new_order(o, mesh.F)) == oriented_triangles(relabelled_old));
    // Positions go there and back unchanged.
    CHECK(to_old_order(o, to_new_order(o, mesh.V)) == mesh.V);
    CHECK(to_new_order(o, mesh.V).row(0) == mesh.V.row(o.vertex_order[0]));
    // Deterministic.
    const MeshOrder again = banded_order(mesh);
    CHECK(again.vertex_order == o.vertex_order);
    CHECK(again.triangle_order == o.triangle_order);
  }
}

TEST_CASE("banded_order narrows a shuffled mesh's bands to about a ring", "[mesh][reorder]") {
  // A torus of 40 × 20 (800 vertices): a breadth-first level on it holds at most about 2 · 20
  // vertices, and a triangle spans at most two adjacent levels, so under 4 · 20 labels; shuffled,
  // the span is most of the mesh.
  const TriMesh torus = make_torus(40, 20, 2.0, 0.5);
  const TriMesh mixed = shuffled(torus, 11);
  CHECK(bandwidth(mixed.F) > 400);
  const MeshOrder o = banded_order(mixed);
  const Triangles F = to_new_order(o, mixed.F);
  CHECK(bandwidth(F) <= 4 * 20);
  // Triangles follow their lowest corner.
  for (int t = 1; t < F.rows(); ++t) CHECK(F.row(t - 1).minCoeff() <= F.row(t).minCoeff());
}
