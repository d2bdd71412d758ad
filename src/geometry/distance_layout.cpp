#include "geometry/distance_layout.hpp"

#include <algorithm>
#include <utility>

namespace sm {

DistanceLayout::DistanceLayout(const Triangles& F, int num_vertices)
    : F_(F), num_vertices_(num_vertices) {
  const int n = num_vertices, m = static_cast<int>(F.rows());
  owns_.assign(m, 0);
  vertex_owner_.assign(n, -1);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k)
      if (vertex_owner_[F(t, k)] < 0) {
        vertex_owner_[F(t, k)] = t;
        owns_[t] |= uint8_t(1u << k);
      }
  std::vector<int> start(n + 1, 0);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) ++start[std::min(F(t, k), F(t, (k + 1) % 3)) + 1];
  for (int v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<std::pair<int, int>> entries(3 * static_cast<size_t>(m));  // (higher vertex, 3t+k)
  std::vector<int> cursor(start.begin(), start.end() - 1);
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = F(t, k), b = F(t, (k + 1) % 3);
      entries[cursor[std::min(a, b)]++] = {std::max(a, b), 3 * t + k};
    }
  edges_.reserve(entries.size() / 2 + 1);
  for (int a = 0; a < n; ++a) {
    const auto first = entries.begin() + start[a], last = entries.begin() + start[a + 1];
    std::sort(first, last);
    for (auto e = first; e != last; ++e) {
      if (e != first && (e - 1)->first == e->first) continue;
      edges_.push_back({a, e->first});
      owns_[e->second / 3] |= uint8_t(8u << (e->second % 3));
    }
  }
}

double DistanceLayout::mean_edge_length(const Positions& V) const {
  return sm::mean_edge_length(V, edges_);
}

}  // namespace sm
