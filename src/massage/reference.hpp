#pragma once
/// The reference geometry N of the distance energy (paper §2.2): a triangle mesh with its
/// acceleration structure, connectivity and the samples w_j that are projected onto M.
#include <memory>

#include "geometry/bvh.hpp"
#include "geometry/triangle_planes.hpp"
#include "core/enum_names.hpp"
#include "mesh/mesh.hpp"
#include "mesh/topology.hpp"

namespace sm {

/// Which points of a surface act as samples of the distance energy (eq. 4).
enum class SampleKind {
  Vertices,  ///< the vertices (the paper's default)
  Edges,     ///< the vertices and the midpoint of every edge
  Faces,     ///< the vertices, edge midpoints and the centroid of every triangle
};
inline constexpr EnumName<SampleKind> kSampleKindNames[] = {
    {"vertices", SampleKind::Vertices}, {"edges", SampleKind::Edges}, {"faces", SampleKind::Faces}};

/// N, prepared once and then shared read-only by any number of concurrent Massager::run calls.
class Reference {
 public:
  /// Validates `mesh` (finite coordinates, indices in range: InputError naming `name`), builds its
  /// topology (or shares `topology` when the caller already has it for this connectivity), its
  /// BVH (or, when `tree` is a BVH over the same triangles, e.g. Massager::template_bvh(), a copy
  /// of it refitted to these positions, which costs O(m) instead of O(m log m)), the projection
  /// frames of its triangles and its samples.
  Reference(TriMesh mesh, SampleKind samples, const char* name = "reference",
            std::shared_ptr<const Topology> topology = nullptr, const TriangleBvh* tree = nullptr);

  const TriMesh& mesh() const { return mesh_; }
  const Topology& topology() const { return *topology_; }
  const TriangleBvh& bvh() const { return bvh_; }
  const TrianglePlanes& planes() const { return planes_; }
  /// The samples w_j (s×3): N's vertices that lie in a triangle first, in order, then the extra
  /// ones (vertices in no triangle are not on the surface).
  const Positions& samples() const { return samples_; }
  SampleKind sample_kind() const { return sample_kind_; }
  double bounding_box_diagonal() const { return diagonal_; }

 private:
  TriMesh mesh_;
  std::shared_ptr<const Topology> topology_;
  TriangleBvh bvh_;
  TrianglePlanes planes_;
  Positions samples_;
  SampleKind sample_kind_ = SampleKind::Vertices;
  double diagonal_ = 0.0;
};

/// Sample points of `mesh` of the given kind (its vertices that lie in a triangle first, then edge
/// midpoints, then face centroids), each edge once.
Positions surface_samples(const TriMesh& mesh, const Topology& topo, SampleKind kind);

}  // namespace sm
