#pragma once
/// Reading a glTF 2.0 asset (.gltf with its resources, or .glb) into a tinygltf model, with the
/// container checks tinygltf leaves out; every error names the file and the glTF element.
#include <tiny_gltf.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/gltf/gltf_resource.hpp"  // throw_gltf_error

namespace sm {

/// A loaded glTF asset. Images are not decoded: `model.images[i].image` holds the bytes of the
/// image file (PNG, JPEG, ...) exactly as stored in the asset, whether it was embedded in a buffer
/// view, a data URI or an external file.
struct GltfFile {
  std::filesystem::path path;
  tinygltf::Model model;
  nlohmann::json json;  ///< the asset's JSON document as written (materials are copied from here)
  /// The external files read, resolved inside the model's folder: buffers, then images, in order.
  std::vector<std::filesystem::path> resources;
};

/// Deepest nesting of arrays and objects accepted in a glTF's JSON (a real asset nests about 10
/// levels; `extras` may nest more): checked before parsing, so that no parser recurses unbounded.
inline constexpr int kGltfMaxJsonDepth = 128;

/// Loads `path` (GLB or glTF JSON, told apart by the GLB magic). Throws IoError when a file cannot
/// be read and InputError for a truncated or malformed GLB, invalid JSON, JSON nested deeper than
/// kGltfMaxJsonDepth, a buffer or image URI that is missing, absolute, outside the model's folder
/// or not a regular file (io/gltf/gltf_resource.hpp), a buffer view outside its buffer, or a required
/// extension this reader does not implement (anything but KHR_mesh_quantization,
/// KHR_texture_transform, KHR_texture_basisu, EXT_texture_webp and KHR_materials_*).
GltfFile load_gltf_file(const std::filesystem::path& path);

/// The same checks and errors for the asset's bytes, read already; `path` names it in messages
/// and its folder is where external resources are looked up.
GltfFile parse_gltf_file(const std::filesystem::path& path, const std::string& bytes);

/// Whether extension `name` survives into a file written from this asset: the texture, material
/// and quantization extensions (the writer copies materials, textures and attributes verbatim).
bool gltf_extension_is_kept(const std::string& name);

}  // namespace sm
