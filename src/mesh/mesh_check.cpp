#include "mesh/mesh_check.hpp"

#include <algorithm>
#include <array>
#include <sstream>
#include <tuple>

namespace sm {

std::string MeshReport::describe() const {
  std::ostringstream s;
  s << vertices << " vertices, " << triangles << " triangles, " << boundary_loops
    << (boundary_loops == 1 ? " boundary loop" : " boundary loops");
  auto item = [&](int count, const char* what) {
    if (count > 0) s << ", " << count << ' ' << what;
  };
  item(degenerate_triangles, "degenerate triangles");
  if (!degenerate_triangle_ids.empty()) {
    s << " (";
    for (size_t i = 0; i < degenerate_triangle_ids.size(); ++i)
      s << (i ? ", " : "") << degenerate_triangle_ids[i];
    if (static_cast<int>(degenerate_triangle_ids.size()) < degenerate_triangles) s << ", ...";
    s << ")";
  }
  item(duplicate_triangles, "duplicate triangles");
  item(duplicate_vertices, "duplicate vertices");
  item(isolated_vertices, "isolated vertices");
  item(nonmanifold_edges, "non-manifold edges");
  item(nonmanifold_vertices, "non-manifold vertices");
  return s.str();
}

MeshReport check_mesh(const TriMesh& mesh, const Topology& topo) {
  MeshReport r;
  r.vertices = mesh.num_vertices();
  r.triangles = mesh.num_triangles();
  r.isolated_vertices = topo.num_isolated_vertices;
  r.nonmanifold_edges = topo.num_nonmanifold_edges;
  r.nonmanifold_vertices = topo.num_nonmanifold_vertices;
  r.boundary_loops = static_cast<int>(topo.boundary_loops.size());
  r.euler_characteristic = topo.euler_characteristic();

  const double diag = bounding_box_diagonal(mesh.V);
  const double tiny = 1e-14 * diag * diag;
  std::vector<std::array<int, 4>> sorted;  // sorted vertex triple + triangle id
  sorted.reserve(mesh.num_triangles());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const int a = mesh.F(t, 0), b = mesh.F(t, 1), c = mesh.F(t, 2);
    const Vec3 p = mesh.vertex(a);
    const double twice_area = (mesh.vertex(b) - p).cross(mesh.vertex(c) - p).norm();
    if (a == b || b == c || a == c || !(twice_area > tiny)) {
      ++r.degenerate_triangles;
      if (r.degenerate_triangle_ids.size() < 20) r.degenerate_triangle_ids.push_back(t);
    }
    std::array<int, 4> key{a, b, c, t};
    std::sort(key.begin(), key.begin() + 3);
    sorted.push_back(key);
  }
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 1; i < sorted.size(); ++i)
    if (std::equal(sorted[i].begin(), sorted[i].begin() + 3, sorted[i - 1].begin()))
      ++r.duplicate_triangles;

  std::vector<std::tuple<double, double, double, int>> pos;
  pos.reserve(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) pos.emplace_back(mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2), i);
  std::sort(pos.begin(), pos.end());
  for (size_t i = 1; i < pos.size(); ++i)
    if (std::get<0>(pos[i]) == std::get<0>(pos[i - 1]) &&
        std::get<1>(pos[i]) == std::get<1>(pos[i - 1]) &&
        std::get<2>(pos[i]) == std::get<2>(pos[i - 1]))
      ++r.duplicate_vertices;
  return r;
}

MeshReport check_mesh(const TriMesh& mesh) { return check_mesh(mesh, build_topology(mesh)); }

}  // namespace sm
