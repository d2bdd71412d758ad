#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>

#include "geometry/distance.hpp"
#include "geometry/distance_layout.hpp"
#include "geometry/distance_meter.hpp"
#include "mesh/topology.hpp"
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

namespace {

void check_same(const DistanceStats& d, const DistanceStats& built) {
  CHECK(d.samples == built.samples);
  CHECK(d.refined == built.refined);
  CHECK(d.max == built.max);
  CHECK(d.mean == built.mean);
  CHECK(d.rms == built.rms);
}

}  // namespace

TEST_CASE("distance meter: the same distances both ways as one_sided_distance, frame after frame",
          "[distance]") {
  const TriMesh a = make_torus(30, 12, 2.0, 0.5);
  const auto topology = std::make_shared<const Topology>(build_topology(a));
  const TriangleBvh bvh(a);
  const TrianglePlanes planes(a.V, a.F, topology.get());
  for (bool adaptive : {false, true}) {
    DistanceOptions o;
    o.adaptive = adaptive;
    const DistanceMeter meter(a.F, a.num_vertices(), topology, o);
    for (double amount : {0.02, 0.05, 0.02}) {  // the workspace reused from frame to frame
      Positions moved = a.V;
      for (int i = 0; i < a.num_vertices(); ++i)
        moved.row(i) +=
            amount * Eigen::RowVector3d(std::sin(3.0 * i), std::cos(5.0 * i), std::sin(i));
      const TriMesh b{moved, a.F};
      const FrameDistances d = meter.measure(a, bvh, planes, moved);
      check_same(d.moved_to_original, one_sided_distance(b, bvh, o, &planes, topology.get()));
      TriangleBvh refit = bvh;  // the meter's BVH of the moved copy
      refit.refit(moved);
      const TrianglePlanes moved_planes(moved, a.F, topology.get());
      check_same(d.original_to_moved,
                 one_sided_distance(a, refit, o, &moved_planes, topology.get()));
    }
  }
}
