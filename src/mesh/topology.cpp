#include "mesh/topology.hpp"

#include <algorithm>
#include <numeric>
#include <utility>

namespace sm {
namespace {

struct HalfEdge {
  int from, to, tri, local;
};

Csr build_vertex_triangles(const TriMesh& mesh) {
  const int n = mesh.num_vertices(), m = mesh.num_triangles();
  Csr c;
  c.offsets.assign(n + 1, 0);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) ++c.offsets[mesh.F(t, k) + 1];
  std::partial_sum(c.offsets.begin(), c.offsets.end(), c.offsets.begin());
  c.data.resize(c.offsets[n]);
  std::vector<int> fill(c.offsets.begin(), c.offsets.end() - 1);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) c.data[fill[mesh.F(t, k)]++] = t;
  return c;
}

int local_index(const TriMesh& mesh, int t, int v) {
  for (int k = 0; k < 3; ++k)
    if (mesh.F(t, k) == v) return k;
  return -1;
}

std::pair<int, int> edge_key(const HalfEdge& h) {
  return std::make_pair(std::min(h.from, h.to), std::max(h.from, h.to));
}

std::vector<HalfEdge> half_edges(const TriMesh& mesh) {
  std::vector<HalfEdge> he;
  he.reserve(static_cast<size_t>(mesh.num_triangles()) * 3);
  for (int t = 0; t < mesh.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) he.push_back({mesh.F(t, k), mesh.F(t, (k + 1) % 3), t, k});
  return he;
}

// Half-edge indices sorted by undirected edge, so that each edge's half-edges are adjacent.
std::vector<int> sorted_by_edge(const std::vector<HalfEdge>& he) {
  std::vector<int> order(he.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const auto ka = edge_key(he[a]), kb = edge_key(he[b]);
    return ka != kb ? ka < kb : a < b;
  });
  return order;
}

// Pairs the half-edges of each undirected edge into triangle neighbours and counts the edges;
// returns the boundary half-edges (those without a twin), to trace the loops.
std::vector<int> pair_half_edges(const std::vector<HalfEdge>& he, Topology& topo) {
  const std::vector<int> order = sorted_by_edge(he);
  std::vector<int> boundary_he;
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j < order.size() && edge_key(he[order[j]]) == edge_key(he[order[i]])) ++j;
    const size_t count = j - i;
    ++topo.num_edges;
    if (count == 1) {
      const HalfEdge& h = he[order[i]];
      ++topo.num_boundary_edges;
      topo.is_boundary_vertex[h.from] = topo.is_boundary_vertex[h.to] = 1;
      boundary_he.push_back(order[i]);
    } else if (count == 2 && he[order[i]].from == he[order[i + 1]].to) {
      const HalfEdge& a = he[order[i]];
      const HalfEdge& b = he[order[i + 1]];
      topo.triangle_neighbours[a.tri][a.local] = b.tri;
      topo.triangle_neighbours[b.tri][b.local] = a.tri;
    } else {
      // More than two triangles, or two with the same orientation: no neighbours across it.
      ++topo.num_nonmanifold_edges;
      for (size_t q = i; q < j; ++q) {
        const HalfEdge& h = he[order[q]];
        topo.is_boundary_vertex[h.from] = topo.is_boundary_vertex[h.to] = 1;
      }
    }
    i = j;
  }
  return boundary_he;
}

// The fan of vertex v, the triangles of vertex_triangles [b, e), in counter-clockwise order into
// `fan` and its neighbours into `ring`. Around v in triangle t (v at local k), the
// counter-clockwise next triangle shares edge (v, F(t,k+2)); the walk goes clockwise first to
// find the fan's start (a boundary, or back at the first triangle).
void walk_fan(const TriMesh& mesh, const Topology& topo, int v, int b, int e, std::vector<int>& fan,
              std::vector<int>& ring) {
  int start = topo.vertex_triangles.data[b];
  for (int steps = 0; steps < e - b; ++steps) {
    const int k = local_index(mesh, start, v);
    const int prev = topo.triangle_neighbours[start][k];  // across edge (v, F(k+1))
    if (prev < 0 || prev == topo.vertex_triangles.data[b]) break;
    start = prev;
  }
  int t = start;
  for (int steps = 0; steps < e - b; ++steps) {
    const int k = local_index(mesh, t, v);
    if (fan.empty()) ring.push_back(mesh.F(t, (k + 1) % 3));
    fan.push_back(t);
    const int next = topo.triangle_neighbours[t][(k + 2) % 3];  // across edge (F(k+2), v)
    if (next < 0) {
      ring.push_back(mesh.F(t, (k + 2) % 3));
      break;
    }
    if (next == start) break;
    ring.push_back(mesh.F(t, (k + 2) % 3));
    t = next;
  }
}

// Several fans (a "bowtie"): every incident triangle and the distinct neighbours, unordered.
void bowtie_fan(const TriMesh& mesh, const Topology& topo, int v, int b, int e,
                std::vector<int>& fan, std::vector<int>& ring) {
  fan.assign(topo.vertex_triangles.data.begin() + b, topo.vertex_triangles.data.begin() + e);
  ring.clear();
  for (int t : fan) {
    const int k = local_index(mesh, t, v);
    ring.push_back(mesh.F(t, (k + 1) % 3));
    ring.push_back(mesh.F(t, (k + 2) % 3));
  }
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
}

// Orders each vertex's triangles into its fan and fills the one-rings (needs the neighbours).
void order_one_rings(const TriMesh& mesh, Topology& topo) {
  topo.one_ring.offsets.assign(1, 0);
  std::vector<int> fan, ring;
  Csr ordered_vt;
  ordered_vt.offsets.assign(1, 0);
  for (int v = 0; v < topo.num_vertices; ++v) {
    const int b = topo.vertex_triangles.begin(v), e = topo.vertex_triangles.end(v);
    if (b == e) ++topo.num_isolated_vertices;
    fan.clear();
    ring.clear();
    if (b != e) walk_fan(mesh, topo, v, b, e, fan, ring);
    if (b != e && static_cast<int>(fan.size()) != e - b) {
      ++topo.num_nonmanifold_vertices;
      topo.is_boundary_vertex[v] = 1;
      bowtie_fan(mesh, topo, v, b, e, fan, ring);
    }
    topo.one_ring.data.insert(topo.one_ring.data.end(), ring.begin(), ring.end());
    topo.one_ring.offsets.push_back(static_cast<int>(topo.one_ring.data.size()));
    ordered_vt.data.insert(ordered_vt.data.end(), fan.begin(), fan.end());
    ordered_vt.offsets.push_back(static_cast<int>(ordered_vt.data.size()));
  }
  topo.vertex_triangles = std::move(ordered_vt);
}

// Boundary loops: follow boundary half-edges from vertex to vertex.
std::vector<std::vector<int>> trace_boundary_loops(const std::vector<HalfEdge>& he,
                                                   const std::vector<int>& boundary_he, int n) {
  std::vector<int> boundary_next(n, -1);  // boundary half-edge leaving each vertex
  for (int h : boundary_he) boundary_next[he[h].from] = h;
  std::vector<std::vector<int>> loops;
  std::vector<uint8_t> used(he.size(), 0);
  for (int h0 : boundary_he) {
    if (used[h0]) continue;
    std::vector<int> loop;
    int h = h0;
    while (h >= 0 && !used[h]) {
      used[h] = 1;
      loop.push_back(he[h].from);
      h = boundary_next[he[h].to];
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

}  // namespace

Topology build_topology(const TriMesh& mesh) {
  Topology topo;
  const int n = mesh.num_vertices(), m = mesh.num_triangles();
  topo.num_vertices = n;
  topo.num_triangles = m;
  topo.triangle_neighbours.assign(m, {-1, -1, -1});
  topo.is_boundary_vertex.assign(n, 0);
  const std::vector<HalfEdge> he = half_edges(mesh);
  const std::vector<int> boundary_he = pair_half_edges(he, topo);
  topo.vertex_triangles = build_vertex_triangles(mesh);
  order_one_rings(mesh, topo);
  topo.boundary_loops = trace_boundary_loops(he, boundary_he, n);
  return topo;
}

}  // namespace sm
