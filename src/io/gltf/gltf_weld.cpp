#include "io/gltf/gltf_weld.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <unordered_map>

namespace sm {
namespace {

using Key = std::array<double, 3>;

struct KeyHash {
  size_t operator()(const Key& k) const {
    size_t h = 0;
    for (double x : k) h = h * 1000003u ^ std::hash<double>{}(x);
    return h;
  }
};

}  // namespace

GltfWeld weld_by_position(const Positions& V, const Triangles& F) {
  GltfWeld w;
  const Eigen::Index n = V.rows();
  std::vector<char> referenced(size_t(n), 0);
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    for (int c = 0; c < 3; ++c) referenced[size_t(F(t, c))] = 1;
  }
  w.map.assign(size_t(n), -1);
  std::unordered_map<Key, int, KeyHash> index;
  index.reserve(size_t(n));
  std::vector<Eigen::Index> first_copy;
  for (Eigen::Index v = 0; v < n; ++v) {
    if (!referenced[size_t(v)]) {
      ++w.unreferenced;
      continue;
    }
    // Adding +0.0 turns -0.0 into +0.0, so both hash and compare alike.
    const Key key{V(v, 0) + 0.0, V(v, 1) + 0.0, V(v, 2) + 0.0};
    const auto [it, inserted] = index.emplace(key, int(first_copy.size()));
    if (inserted) {
      first_copy.push_back(v);
    } else {
      ++w.merged;
    }
    w.map[size_t(v)] = it->second;
  }
  w.mesh.V.resize(Eigen::Index(first_copy.size()), 3);
  for (size_t i = 0; i < first_copy.size(); ++i)
    w.mesh.V.row(Eigen::Index(i)) = V.row(first_copy[i]);
  std::vector<int> corners;
  corners.reserve(size_t(F.size()));
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    const int a = w.map[size_t(F(t, 0))], b = w.map[size_t(F(t, 1))], c = w.map[size_t(F(t, 2))];
    if (a == b || b == c || c == a) {
      ++w.dropped_triangles;
      continue;
    }
    corners.insert(corners.end(), {a, b, c});
  }
  w.mesh.F = Eigen::Map<const Triangles>(corners.data(), Eigen::Index(corners.size() / 3), 3);
  return w;
}

WeldedFrame weld_frame(const std::vector<int>& map, int num_welded, const Positions& P,
                       double tolerance) {
  WeldedFrame out;
  out.V = Positions::Zero(num_welded, 3);
  std::vector<int> copies(size_t(num_welded), 0);
  for (size_t v = 0; v < map.size(); ++v) {
    if (map[v] < 0) continue;
    out.V.row(map[v]) += P.row(Eigen::Index(v));
    ++copies[size_t(map[v])];
  }
  for (int i = 0; i < num_welded; ++i) out.V.row(i) /= double(std::max(copies[size_t(i)], 1));
  std::vector<char> separated(size_t(num_welded), 0);
  for (size_t v = 0; v < map.size(); ++v) {
    if (map[v] < 0 || copies[size_t(map[v])] < 2) continue;
    const double d = (P.row(Eigen::Index(v)) - out.V.row(map[v])).norm();
    out.max_separation = std::max(out.max_separation, d);
    if (d > tolerance) separated[size_t(map[v])] = 1;
  }
  for (char s : separated) out.separated_vertices += s;
  return out;
}

Positions unweld_frame(const std::vector<int>& map, const Positions& welded,
                       const Positions& fallback) {
  Positions out(Eigen::Index(map.size()), 3);
  for (size_t v = 0; v < map.size(); ++v) {
    out.row(Eigen::Index(v)) = map[v] >= 0 ? welded.row(map[v]) : fallback.row(Eigen::Index(v));
  }
  return out;
}

}  // namespace sm
