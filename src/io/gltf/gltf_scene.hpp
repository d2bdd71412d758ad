#pragma once
/// What a loaded glTF sequence keeps of its source to evaluate frames and write the output: the
/// asset, its node rig with the chosen animation, and the chosen mesh's geometry.
#include "io/gltf/gltf_file.hpp"
#include "io/gltf/gltf_rig.hpp"
#include "io/gltf/gltf_skin_morph.hpp"

namespace sm {

struct GltfScene {
  GltfFile file;
  GltfRig rig;
  GltfMeshGeometry geometry;
  int node = -1;  ///< the node that instantiates the mesh (and holds its skin and weights)
};

}  // namespace sm
