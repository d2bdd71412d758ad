#include "massage/reference.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "core/errors.hpp"

namespace sm {

Positions surface_samples(const TriMesh& mesh, const Topology& topo, SampleKind kind) {
  const int n = mesh.num_vertices(), m = mesh.num_triangles();
  std::vector<Vec3> extra;
  if (kind == SampleKind::Edges || kind == SampleKind::Faces) {
    extra.reserve(topo.num_edges + (kind == SampleKind::Faces ? m : 0));
    // Each undirected edge once: the half-edge (a→b) with a < b, or a boundary half-edge.
    for (int t = 0; t < m; ++t)
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.F(t, k), b = mesh.F(t, (k + 1) % 3);
        if (a < b || topo.triangle_neighbours[t][k] < 0)
          extra.push_back(0.5 * (mesh.vertex(a) + mesh.vertex(b)));
      }
  }
  if (kind == SampleKind::Faces)
    for (int t = 0; t < m; ++t)
      extra.push_back((mesh.vertex(mesh.F(t, 0)) + mesh.vertex(mesh.F(t, 1)) +
                       mesh.vertex(mesh.F(t, 2))) / 3.0);
  // Vertices in no triangle are not on the surface: they are no samples of it.
  std::vector<int> on_surface;
  on_surface.reserve(n);
  for (int i = 0; i < n; ++i)
    if (topo.vertex_triangles.size(i) > 0) on_surface.push_back(i);
  const int k = static_cast<int>(on_surface.size());
  Positions s(k + static_cast<int>(extra.size()), 3);
  for (int j = 0; j < k; ++j) s.row(j) = mesh.V.row(on_surface[j]);
  for (size_t i = 0; i < extra.size(); ++i) s.row(k + static_cast<int>(i)) = extra[i].transpose();
  return s;
}

Reference::Reference(TriMesh mesh, SampleKind samples, const char* name,
                     std::shared_ptr<const Topology> topology, const TriangleBvh* tree)
    : mesh_(std::move(mesh)) {
  validate_mesh(mesh_, name);
  if (mesh_.num_triangles() == 0)
    throw InputError(std::string(name) + ": the reference mesh has no triangles");
  if (topology && (topology->num_vertices != mesh_.num_vertices() ||
                   topology->num_triangles != mesh_.num_triangles()))
    throw InputError(std::string(name) + ": connectivity does not match the shared topology");
  topology_ =
      topology ? std::move(topology) : std::make_shared<const Topology>(build_topology(mesh_));
  if (tree && !tree->empty() && tree->positions().rows() == mesh_.V.rows() &&
      tree->triangles().rows() == mesh_.F.rows() && tree->triangles() == mesh_.F) {
    bvh_ = *tree;
    bvh_.refit(mesh_.V);
  } else {
    bvh_ = TriangleBvh(mesh_);
  }
  planes_.update(mesh_.V, mesh_.F, topology_.get());
  samples_ = surface_samples(mesh_, *topology_, samples);
  sample_kind_ = samples;
  diagonal_ = sm::bounding_box_diagonal(mesh_.V);
}

}  // namespace sm
