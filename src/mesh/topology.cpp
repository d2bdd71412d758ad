#include "mesh/topology.hpp"

#include <algorithm>
#include <numeric>

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

}  // namespace

Topology build_topology(const TriMesh& mesh) {
  Topology topo;
  const int n = mesh.num_vertices(), m = mesh.num_triangles();
  topo.num_vertices = n;
  topo.num_triangles = m;
  topo.triangle_neighbours.assign(m, {-1, -1, -1});
  topo.is_boundary_vertex.assign(n, 0);

  // Undirected edges: sort half-edges by (min, max) and pair them.
  std::vector<HalfEdge> he;
  he.reserve(static_cast<size_t>(m) * 3);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) he.push_back({mesh.F(t, k), mesh.F(t, (k + 1) % 3), t, k});
  auto key = [](const HalfEdge& h) {
    return std::make_pair(std::min(h.from, h.to), std::max(h.from, h.to));
  };
  std::vector<int> order(he.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const auto ka = key(he[a]), kb = key(he[b]);
    return ka != kb ? ka < kb : a < b;
  });
  // A boundary half-edge h (from→to) has no twin; remember it to trace the loops.
  std::vector<int> boundary_next(n, -1);  // boundary half-edge leaving each vertex
  std::vector<int> boundary_he;
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j < order.size() && key(he[order[j]]) == key(he[order[i]])) ++j;
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

  topo.vertex_triangles = build_vertex_triangles(mesh);

  // Ordered one-rings. Around vertex v in triangle t (v at local k), the counter-clockwise next
  // triangle shares edge (v, F(t,k+2)); we walk clockwise first to find the fan's start.
  topo.one_ring.offsets.assign(1, 0);
  std::vector<int> fan_tris, ring;
  Csr ordered_vt;
  ordered_vt.offsets.assign(1, 0);
  for (int v = 0; v < n; ++v) {
    const int b = topo.vertex_triangles.begin(v), e = topo.vertex_triangles.end(v);
    if (b == e) ++topo.num_isolated_vertices;
    fan_tris.clear();
    ring.clear();
    if (b != e) {
      // Walk clockwise from the first triangle until a boundary or back at the start.
      int start = topo.vertex_triangles.data[b];
      for (int steps = 0; steps < e - b; ++steps) {
        const int k = local_index(mesh, start, v);
        const int prev = topo.triangle_neighbours[start][k];  // across edge (v, F(k+1))
        if (prev < 0 || prev == topo.vertex_triangles.data[b]) break;
        start = prev;
      }
      // Walk counter-clockwise from start, collecting the fan.
      int t = start;
      for (int steps = 0; steps < e - b; ++steps) {
        const int k = local_index(mesh, t, v);
        if (fan_tris.empty()) ring.push_back(mesh.F(t, (k + 1) % 3));
        fan_tris.push_back(t);
        const int next = topo.triangle_neighbours[t][(k + 2) % 3];  // across edge (F(k+2), v)
        if (next < 0) {
          ring.push_back(mesh.F(t, (k + 2) % 3));
          break;
        }
        if (next == start) break;
        ring.push_back(mesh.F(t, (k + 2) % 3));
        t = next;
      }
      if (static_cast<int>(fan_tris.size()) != e - b) {
        // Several fans (a "bowtie"): keep every incident triangle and the distinct neighbours.
        ++topo.num_nonmanifold_vertices;
        topo.is_boundary_vertex[v] = 1;
        fan_tris.assign(topo.vertex_triangles.data.begin() + b,
                        topo.vertex_triangles.data.begin() + e);
        ring.clear();
        for (int tt : fan_tris) {
          const int k = local_index(mesh, tt, v);
          ring.push_back(mesh.F(tt, (k + 1) % 3));
          ring.push_back(mesh.F(tt, (k + 2) % 3));
        }
        std::sort(ring.begin(), ring.end());
        ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
      }
    }
    topo.one_ring.data.insert(topo.one_ring.data.end(), ring.begin(), ring.end());
    topo.one_ring.offsets.push_back(static_cast<int>(topo.one_ring.data.size()));
    ordered_vt.data.insert(ordered_vt.data.end(), fan_tris.begin(), fan_tris.end());
    ordered_vt.offsets.push_back(static_cast<int>(ordered_vt.data.size()));
  }
  topo.vertex_triangles = std::move(ordered_vt);

  // Boundary loops: follow boundary half-edges from vertex to vertex.
  for (int h : boundary_he) boundary_next[he[h].from] = h;
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
    topo.boundary_loops.push_back(std::move(loop));
  }
  return topo;
}

}  // namespace sm
