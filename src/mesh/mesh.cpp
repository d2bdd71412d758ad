#include "mesh/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_set>
#include <vector>

#include "core/errors.hpp"

namespace sm {

double bounding_box_diagonal(const Positions& V) {
  if (V.rows() == 0) return 0.0;
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

double mean_edge_length(const TriMesh& mesh) {
  return mean_edge_length(mesh.V, unique_edges(mesh.F));
}

std::vector<std::array<int, 2>> unique_edges(const Triangles& F) {
  // Every interior edge appears in two triangles, a boundary edge in one: one key per half-edge,
  // (lower, higher) vertex, sorted and deduplicated (linearithmic and allocation-light).
  std::vector<uint64_t> keys;
  keys.reserve(static_cast<size_t>(F.rows()) * 3);
  for (int t = 0; t < F.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      uint32_t a = static_cast<uint32_t>(F(t, k)), b = static_cast<uint32_t>(F(t, (k + 1) % 3));
      if (a > b) std::swap(a, b);
      keys.push_back((uint64_t(a) << 32) | b);
    }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<std::array<int, 2>> edges(keys.size());
  for (size_t e = 0; e < keys.size(); ++e)
    edges[e] = {static_cast<int>(keys[e] >> 32), static_cast<int>(keys[e] & 0xffffffffu)};
  return edges;
}

double mean_edge_length(const Positions& V, const std::vector<std::array<int, 2>>& edges) {
  if (edges.empty()) return 0.0;
  double sum = 0.0;
  for (const auto& [a, b] : edges) sum += (V.row(a) - V.row(b)).norm();
  return sum / static_cast<double>(edges.size());
}

Eigen::VectorXd triangle_areas(const TriMesh& mesh) {
  Eigen::VectorXd a(mesh.num_triangles());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Vec3 p0 = mesh.vertex(mesh.F(t, 0));
    a[t] = 0.5 * (mesh.vertex(mesh.F(t, 1)) - p0).cross(mesh.vertex(mesh.F(t, 2)) - p0).norm();
  }
  return a;
}

Positions triangle_normals(const TriMesh& mesh) {
  Positions N(mesh.num_triangles(), 3);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Vec3 p0 = mesh.vertex(mesh.F(t, 0));
    Vec3 n = (mesh.vertex(mesh.F(t, 1)) - p0).cross(mesh.vertex(mesh.F(t, 2)) - p0);
    const double len = n.norm();
    if (len > 0.0) n /= len;
    N.row(t) = n.transpose();
  }
  return N;
}

Positions vertex_normals(const TriMesh& mesh) {
  Positions N = Positions::Zero(mesh.num_vertices(), 3);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Vec3 p0 = mesh.vertex(mesh.F(t, 0));
    const Vec3 n = (mesh.vertex(mesh.F(t, 1)) - p0).cross(mesh.vertex(mesh.F(t, 2)) - p0);
    for (int k = 0; k < 3; ++k) N.row(mesh.F(t, k)) += n.transpose();
  }
  for (int i = 0; i < N.rows(); ++i) {
    const double len = N.row(i).norm();
    if (len > 0.0) N.row(i) /= len;
  }
  return N;
}

void validate_mesh(const TriMesh& mesh, const char* what) {
  const int n = mesh.num_vertices();
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(mesh.V(i, c))) {
        std::ostringstream msg;
        msg << what << ": vertex " << i << " has a non-finite coordinate "
            << "xyz"[c] << " = " << mesh.V(i, c);
        throw InputError(msg.str());
      }
    }
  }
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.F(t, k);
      if (v < 0 || v >= n) {
        std::ostringstream msg;
        msg << what << ": triangle " << t << " refers to vertex " << v << ", but the mesh has "
            << n << " vertices";
        throw InputError(msg.str());
      }
    }
  }
}

}  // namespace sm
