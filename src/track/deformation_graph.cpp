#include "track/deformation_graph.hpp"

#include <algorithm>
#include <cstdint>
#include <queue>
#include <random>
#include <utility>

#include "core/errors.hpp"

namespace sm {

namespace {

// Dijkstra over the template's edges from `source`, up to `radius`; calls visit(vertex,
// distance) once per reached vertex in increasing distance. `dist` (n, +inf outside a call) is
// scratch, restored on return.
template <class Visit>
void bounded_dijkstra(const Positions& V, const Csr& ring, int source, double radius,
                      std::vector<double>& dist, std::vector<int>& touched, Visit&& visit) {
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  dist[source] = 0.0;
  touched.push_back(source);
  queue.push({0.0, source});
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[v]) continue;
    visit(v, d);
    for (int k = ring.begin(v); k < ring.end(v); ++k) {
      const int u = ring.data[k];
      const double du = d + (V.row(u) - V.row(v)).norm();
      if (du <= radius && du < dist[u]) {
        if (dist[u] == std::numeric_limits<double>::infinity()) touched.push_back(u);
        dist[u] = du;
        queue.push({du, u});
      }
    }
  }
  for (int v : touched) dist[v] = std::numeric_limits<double>::infinity();
  touched.clear();
}

}  // namespace

DeformationGraph::DeformationGraph(const TriMesh& templ, const Topology& topology, double spacing,
                                   int max_influences) {
  const int n = templ.num_vertices();
  if (!(spacing > 0)) throw InputError("deformation graph: the node spacing must be positive");
  const Positions& V = templ.V;
  std::vector<double> dist(n, std::numeric_limits<double>::infinity());
  std::vector<int> touched;

  // Poisson-disk sampling: a fixed pseudo-random order (mt19937 is specified bit for bit).
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::mt19937 random(12345u);
  for (int i = n - 1; i > 0; --i) {
    const int j = static_cast<int>(random() % static_cast<uint32_t>(i + 1));
    std::swap(order[i], order[j]);
  }
  std::vector<uint8_t> covered(n, 0);
  for (int v : order) {
    if (covered[v] || topology.vertex_triangles.size(v) == 0) continue;
    node_vertex_.push_back(v);
    bounded_dijkstra(V, topology.one_ring, v, spacing, dist, touched,
                     [&](int u, double) { covered[u] = 1; });
  }
  const int N = num_nodes();
  g_.resize(N, 3);
  for (int j = 0; j < N; ++j) g_.row(j) = V.row(node_vertex_[j]);

  // Influences: every node's reach within 2 × spacing, the nearest max_influences per vertex.
  const double radius = 2.0 * spacing;
  std::vector<std::vector<std::pair<double, int>>> reach(n);
  for (int j = 0; j < N; ++j)
    bounded_dijkstra(V, topology.one_ring, node_vertex_[j], radius, dist, touched,
                     [&](int u, double d) { reach[u].push_back({d, j}); });
  base_.setZero(n, 3);
  for (int i = 0; i < n; ++i) {
    auto& r = reach[i];
    std::sort(r.begin(), r.end());
    if (static_cast<int>(r.size()) > max_influences) r.resize(max_influences);
    double total = 0.0;
    for (const auto& [d, j] : r) total += (1.0 - d / radius) * (1.0 - d / radius);
    for (const auto& [d, j] : r) {
      double w = (1.0 - d / radius) * (1.0 - d / radius) / total;
      if (!(total > 0)) w = 1.0 / static_cast<double>(r.size());
      nodes_.push_back(j);
      weights_.push_back(w);
      Eigen::Vector4d a;
      a.head<3>() = w * (V.row(i) - g_.row(j)).transpose();
      a[3] = w;
      coeff_.push_back(a);
      base_.row(i) += w * g_.row(j);
    }
    if (r.empty()) base_.row(i) = V.row(i);  // in no triangle: stays where it is
    offsets_.push_back(static_cast<int>(nodes_.size()));
  }

  std::vector<std::array<int, 2>> edges;
  for (int i = 0; i < n; ++i)
    for (int a = begin(i); a < end(i); ++a)
      for (int b = a + 1; b < end(i); ++b)
        edges.push_back({std::min(nodes_[a], nodes_[b]), std::max(nodes_[a], nodes_[b])});
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  edges_ = std::move(edges);
}

Positions DeformationGraph::deform(const std::vector<NodeMap>& X) const {
  const int n = num_vertices();
  Positions out(n, 3);
  for (int i = 0; i < n; ++i) {
    Vec3 p = base(i);
    for (int k = begin(i); k < end(i); ++k) p += X[nodes_[k]] * coeff_[k];
    out.row(i) = p.transpose();
  }
  return out;
}

std::vector<NodeMap> DeformationGraph::identity() const {
  NodeMap id = NodeMap::Zero();
  id.leftCols<3>().setIdentity();
  return std::vector<NodeMap>(num_nodes(), id);
}

}  // namespace sm
