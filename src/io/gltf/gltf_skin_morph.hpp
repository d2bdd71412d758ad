#pragma once
/// A glTF mesh as one vertex set (its triangle primitives concatenated) with its morph targets and
/// skin, and its world-space vertex positions at any time (glTF 2.0 §3.7.2.2 and §3.7.3).
#include <Eigen/Core>
#include <vector>

#include "io/gltf/gltf_file.hpp"
#include "io/gltf/gltf_rig.hpp"
#include "mesh/mesh.hpp"

namespace sm {

/// Where a primitive's vertices lie in the concatenated vertex set.
struct GltfPrimitiveRange {
  int first_vertex = 0;
  int vertex_count = 0;
};

struct GltfMeshGeometry {
  int mesh = -1;
  std::vector<GltfPrimitiveRange> primitives;  ///< one per primitive of the mesh, in order
  Positions base;                              ///< POSITION of every glTF vertex (n×3)
  std::vector<Positions> target_deltas;        ///< per morph target, n×3 POSITION displacements
  Triangles triangles;  ///< all primitives' triangles (lists, strips and fans), glTF vertex ids

  int skin = -1;                              ///< skins[] index, -1 when not skinned
  std::vector<int> joint_nodes;               ///< skin.joints
  std::vector<Eigen::Matrix4d> inverse_bind;  ///< per joint (identity when not given)
  int influences = 0;           ///< joint/weight pairs per vertex: 4 per JOINTS_n/WEIGHTS_n set
  std::vector<int> joints;      ///< n × influences, indices into joint_nodes
  std::vector<double> weights;  ///< n × influences

  int num_vertices() const { return int(base.rows()); }
};

/// Reads meshes[mesh]; skins[skin] when skin >= 0. Throws InputError naming the element for a
/// primitive that is not made of triangles (points, lines), a missing POSITION, attribute counts
/// that disagree, indices out of range, primitives with different morph target counts, a skinned
/// primitive without JOINTS_0/WEIGHTS_0, joint indices or joint nodes out of range, or inverse
/// bind matrices of the wrong count.
GltfMeshGeometry load_gltf_mesh_geometry(const GltfFile& file, int mesh, int skin);

/// World-space positions (n×3) of the mesh instantiated by `node` at time `t`: morphed by the
/// node's weights, then skinned by the joints' world transforms (the node's own transform is
/// ignored for a skinned mesh, as the specification requires) or else moved by the node's world
/// transform.
Positions gltf_mesh_positions(const GltfMeshGeometry& geometry, const GltfRig& rig, int node,
                              double t);

}  // namespace sm
