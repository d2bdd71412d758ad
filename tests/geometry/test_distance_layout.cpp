#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>

#include "geometry/distance.hpp"
#include "geometry/distance_layout.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

TEST_CASE("distance layout: every vertex and edge owned once, by its first triangle",
          "[distance]") {
  for (const TriMesh& mesh : {make_icosphere(2, 1.0), make_grid(5, 3, 2.0, 1.0)}) {
    const DistanceLayout layout(mesh.F, mesh.num_vertices());
    CHECK(layout.fits(mesh.F, mesh.num_vertices()));
    CHECK_FALSE(layout.fits(mesh.F, mesh.num_vertices() + 1));
    std::set<std::pair<int, int>> edges;
    std::vector<int> first(mesh.num_vertices(), -1);
    long owned_edges = 0;
    for (int t = 0; t < mesh.num_triangles(); ++t)
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.F(t, k), b = mesh.F(t, (k + 1) % 3);
        const bool new_edge = edges.insert({std::min(a, b), std::max(a, b)}).second;
        const bool owns_edge = layout.owns()[t] & (8u << k);
        CHECK(owns_edge == new_edge);
        owned_edges += owns_edge;
        if (first[a] < 0) first[a] = t;
        CHECK(bool(layout.owns()[t] & (1u << k)) ==
              (first[a] == t && layout.vertex_owner()[a] == t));
      }
    CHECK(layout.vertex_owner() == first);
    CHECK(layout.num_edges() == static_cast<int>(edges.size()));
    CHECK(owned_edges == layout.num_edges());
    // Sorted, and the mean edge length is mean_edge_length's, bit for bit.
    CHECK(std::is_sorted(layout.edges().begin(), layout.edges().end()));
    CHECK(layout.mean_edge_length(mesh.V) == mean_edge_length(mesh));
  }
}

TEST_CASE(
    "distance layout and workspace given or not: the same distances; another mesh's "
    "layout is not used",
    "[distance]") {
  const TriMesh a = make_torus(30, 12, 2.0, 0.5);
  TriMesh b = a;
  for (int i = 0; i < b.num_vertices(); ++i)
    b.V.row(i) += 0.02 * Eigen::RowVector3d(std::sin(3.0 * i), std::cos(5.0 * i), std::sin(i));
  const TriangleBvh bvh(b);
  const DistanceLayout layout(a.F, a.num_vertices());
  const TriMesh other = make_icosphere(2, 1.0);
  const DistanceLayout wrong(other.F, other.num_vertices());
  DistanceWorkspace work;  // reused across meshes and options
  for (bool adaptive : {false, true}) {
    DistanceOptions o;
    o.adaptive = adaptive;
    const DistanceStats built = one_sided_distance(a, bvh, o);
    for (const DistanceLayout* given : {&layout, &wrong}) {
      for (DistanceWorkspace* w : {static_cast<DistanceWorkspace*>(nullptr), &work}) {
        const DistanceStats d = one_sided_distance(a, bvh, o, nullptr, nullptr, given, w);
        CHECK(d.samples == built.samples);
        CHECK(d.refined == built.refined);
        CHECK(d.max == built.max);
        CHECK(d.mean == built.mean);
        CHECK(d.rms == built.rms);
      }
      // The workspace, used for another mesh in between, still gives the same.
      const DistanceStats x =
          one_sided_distance(other, TriangleBvh(b), o, nullptr, nullptr, nullptr, &work);
      const DistanceStats y = one_sided_distance(other, TriangleBvh(b), o);
      CHECK(x.samples == y.samples);
      CHECK(x.max == y.max);
      CHECK(x.rms == y.rms);
    }
  }
}
