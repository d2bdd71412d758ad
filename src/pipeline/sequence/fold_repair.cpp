#include "pipeline/sequence/fold_repair.hpp"

#include <algorithm>
#include <deque>

#include "core/errors.hpp"
#include "pipeline/sequence/fold_check.hpp"

namespace sm {

std::vector<int> ring_distance(const Topology& topology, const std::vector<unsigned char>& seeds,
                               int limit) {
  const int n = topology.num_vertices;
  std::vector<int> d(size_t(n), limit + 1);
  std::deque<int> queue;
  for (int v = 0; v < n; ++v)
    if (seeds[size_t(v)]) {
      d[size_t(v)] = 0;
      queue.push_back(v);
    }
  while (!queue.empty()) {
    const int v = queue.front();
    queue.pop_front();
    if (d[size_t(v)] >= limit) continue;
    for (int p = topology.one_ring.begin(v); p < topology.one_ring.end(v); ++p) {
      const int u = topology.one_ring.data[size_t(p)];
      if (d[size_t(u)] > d[size_t(v)] + 1) {
        d[size_t(u)] = d[size_t(v)] + 1;
        queue.push_back(u);
      }
    }
  }
  return d;
}

std::vector<double> repair_weights(const Topology& topology,
                                   const std::vector<unsigned char>& seeds, int rings,
                                   const std::vector<double>& base) {
  const std::vector<int> d = ring_distance(topology, seeds, rings);
  std::vector<double> w(d.size(), 1.0);
  for (size_t v = 0; v < d.size(); ++v) {
    if (d[v] <= rings) w[v] = static_cast<double>(d[v]) / (rings + 1);
    if (!base.empty()) w[v] = std::min(w[v], base[v]);
  }
  return w;
}

FoldRepair repair_folds(const TriMesh& templ, const MassageOptions& massage,
                        const Topology& topology, const Positions& input,
                        const Reference& reference, const std::vector<int>& folded, int rings,
                        int rounds) {
  const int n = templ.num_vertices();
  std::vector<unsigned char> seeds(size_t(n), 0);
  auto add_folds = [&](const std::vector<int>& triangles) {
    for (int t : triangles)
      for (int a = 0; a < 3; ++a) seeds[size_t(templ.F(t, a))] = 1;
  };
  add_folds(folded);
  FoldRepair repair;
  std::vector<int> left;
  for (int round = 1; round <= rounds; ++round) {
    if (round > 1) {  // one more ring kept at the input, and the new folds' vertices
      const std::vector<int> d = ring_distance(topology, seeds, 1);
      for (int v = 0; v < n; ++v) seeds[size_t(v)] = d[size_t(v)] <= 1;
      add_folds(left);
    }
    MassageOptions options = massage;
    options.vertex_weights = repair_weights(topology, seeds, rings, massage.vertex_weights);
    repair.pinned = static_cast<int>(
        std::count(options.vertex_weights.begin(), options.vertex_weights.end(), 0.0));
    repair.weighted = static_cast<int>(
        std::count_if(options.vertex_weights.begin(), options.vertex_weights.end(),
                      [](double w) { return w > 0.0 && w < 1.0; }));
    const Massager massager =
        with_option_path("massage", [&] { return Massager(templ, options); });
    MassageResult result = massager.run(input, reference);
    repair.rounds = round;
    if (!result.ok) {
      repair.failure = result.failure;
      return repair;
    }
    repair.V = std::move(result.V);
    repair.folded_left = count_folded_triangles(templ.F, topology, input, repair.V, &left).folded;
    if (repair.folded_left == 0) {
      repair.repaired = true;
      return repair;
    }
  }
  return repair;
}

}  // namespace sm
