#pragma once
/// What a GLB written from a glTF sequence takes over from its source once: the primitives'
/// attributes that do not move, indices, materials, normals, tangents and images.
#include <nlohmann/json.hpp>
#include <vector>

#include "io/gltf/gltf_glb.hpp"
#include "io/gltf/gltf_scene.hpp"
#include "io/gltf/gltf_load.hpp"
#include "io/gltf/gltf_write_options.hpp"

namespace sm {

using GltfTangents = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>;

/// A source primitive and where its vertices sit among the sequence's glTF vertices.
struct GltfSourcePrimitive {
  const tinygltf::Primitive* prim = nullptr;
  GltfPrimitiveRange range;
  bool normals = false;
  bool tangents = false;
  /// The output primitive without POSITION, NORMAL, TANGENT and targets.
  nlohmann::json shared = nlohmann::json::object();
};

/// What the GLB takes over from the source once: its primitives' attributes that do not move
/// (texture coordinates, colours), indices and materials, its normals and tangents, its images.
/// Everything about the source that writing can refuse is refused here (write_gltf_sequence and,
/// before anything is written, check_gltf_sequence_source).
struct GltfSourceParts {
  std::vector<GltfSourcePrimitive> prims;
  Positions source_normals;
  GltfTangents source_tangents;
  bool any_normals = false;
  nlohmann::json images;
};

/// Copies what the output keeps of `source` into `glb`; throws InputError for what it cannot.
GltfSourceParts copy_gltf_source(GlbBuilder& glb, const GltfSequence& source,
                                 const GltfWriteOptions& options);

}  // namespace sm
