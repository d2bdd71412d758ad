#include "mesh/reorder.hpp"

#include <algorithm>
#include <numeric>
#include <utility>

namespace sm {
namespace {

// Vertex adjacency (CSR) from the triangles, each neighbour once, sorted.
void adjacency(const TriMesh& mesh, std::vector<int>& start, std::vector<int>& next) {
  const int n = mesh.num_vertices(), m = mesh.num_triangles();
  start.assign(static_cast<size_t>(n) + 1, 0);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) start[mesh.F(t, k) + 1] += 2;
  std::partial_sum(start.begin(), start.end(), start.begin());
  next.assign(start[n], 0);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(t, k);
      next[fill[a]++] = mesh.F(t, (k + 1) % 3);
      next[fill[a]++] = mesh.F(t, (k + 2) % 3);
    }
  std::vector<int> compact(start.size(), 0);
  int out = 0;
  for (int v = 0; v < n; ++v) {
    auto first = next.begin() + start[v], last = next.begin() + start[v + 1];
    std::sort(first, last);
    compact[v] = out;
    for (auto it = first; it != last; ++it)
      if (it == first || *it != *(it - 1)) next[out++] = *it;
  }
  compact[n] = out;
  next.resize(out);
  start.swap(compact);
}

}  // namespace

MeshOrder banded_order(const TriMesh& mesh) {
  const int n = mesh.num_vertices(), m = mesh.num_triangles();
  std::vector<int> start, next;
  adjacency(mesh, start, next);
  auto degree = [&](int v) { return start[v + 1] - start[v]; };
  std::vector<int> order;
  order.reserve(n);
  std::vector<int> level(n, -1);
  std::vector<char> placed(n, 0);
  // Breadth-first levels from `root` within its component (marks in `level`, reset after).
  std::vector<int> queue;
  auto bfs = [&](int root) {
    queue.assign(1, root);
    level[root] = 0;
    for (size_t q = 0; q < queue.size(); ++q)
      for (int p = start[queue[q]]; p < start[queue[q] + 1]; ++p)
        if (level[next[p]] < 0) {
          level[next[p]] = level[queue[q]] + 1;
          queue.push_back(next[p]);
        }
  };
  for (int seed = 0; seed < n; ++seed) {
    if (placed[seed]) continue;
    // A pseudo-peripheral root: the lowest-degree vertex of the last level, twice.
    int root = seed;
    for (int pass = 0; pass < 2; ++pass) {
      bfs(root);
      int best = queue.back();
      for (int v : queue)
        if (level[v] == level[queue.back()] &&
            (degree(v) < degree(best) || (degree(v) == degree(best) && v < best)))
          best = v;
      for (int v : queue) level[v] = -1;
      root = best;
    }
    // Cuthill–McKee: breadth first, unplaced neighbours by increasing degree, then index.
    const size_t first = order.size();
    order.push_back(root);
    placed[root] = 1;
    std::vector<int> fresh;
    for (size_t q = first; q < order.size(); ++q) {
      fresh.clear();
      for (int p = start[order[q]]; p < start[order[q] + 1]; ++p)
        if (!placed[next[p]]) {
          placed[next[p]] = 1;
          fresh.push_back(next[p]);
        }
      std::sort(fresh.begin(), fresh.end(), [&](int a, int b) {
        return degree(a) != degree(b) ? degree(a) < degree(b) : a < b;
      });
      order.insert(order.end(), fresh.begin(), fresh.end());
    }
    std::reverse(order.begin() + static_cast<long>(first), order.end());
  }
  MeshOrder o;
  o.vertex_order = std::move(order);
  o.vertex_rank.resize(n);
  for (int k = 0; k < n; ++k) o.vertex_rank[o.vertex_order[k]] = k;
  std::vector<int> first_slot(static_cast<size_t>(n) + 1, 0), lowest(m);
  for (int t = 0; t < m; ++t) {
    lowest[t] = std::min(
        {o.vertex_rank[mesh.F(t, 0)], o.vertex_rank[mesh.F(t, 1)], o.vertex_rank[mesh.F(t, 2)]});
    ++first_slot[lowest[t] + 1];
  }
  std::partial_sum(first_slot.begin(), first_slot.end(), first_slot.begin());
  o.triangle_order.resize(m);
  for (int t = 0; t < m; ++t) o.triangle_order[first_slot[lowest[t]]++] = t;
  return o;
}

Positions to_new_order(const MeshOrder& order, const Positions& X) {
  Positions out(X.rows(), 3);
  for (Eigen::Index k = 0; k < X.rows(); ++k) out.row(k) = X.row(order.vertex_order[k]);
  return out;
}

Positions to_old_order(const MeshOrder& order, const Positions& X) {
  Positions out(X.rows(), 3);
  for (Eigen::Index i = 0; i < X.rows(); ++i) out.row(i) = X.row(order.vertex_rank[i]);
  return out;
}

Triangles to_new_order(const MeshOrder& order, const Triangles& F) {
  Triangles out(F.rows(), 3);
  for (Eigen::Index k = 0; k < F.rows(); ++k)
    for (int c = 0; c < 3; ++c) out(k, c) = order.vertex_rank[F(order.triangle_order[k], c)];
  return out;
}

}  // namespace sm
