#include "io/gltf/gltf_write_source.hpp"

#include <cstring>
#include <string>

#include "io/gltf/gltf_accessor.hpp"
#include "io/gltf/gltf_scene.hpp"
#include "core/errors.hpp"

namespace sm {
using nlohmann::json;

namespace {

/// Copies accessor `index` (dense, sparse applied) into the output. Vertex attributes whose
/// element size is not a multiple of 4 get a padded stride, as glTF requires.
int copy_accessor(GlbBuilder& glb, const GltfFile& file, int index, bool vertex_attribute) {
  const tinygltf::Accessor& a = file.model.accessors[size_t(index)];
  std::vector<unsigned char> bytes = gltf_accessor_bytes(file, index);
  const size_t element = gltf_element_size(a.componentType, a.type);
  int stride = 0;
  if (vertex_attribute && element % 4 != 0) {
    const size_t padded = (element + 3) / 4 * 4;
    std::vector<unsigned char> spaced(a.count * padded, 0);
    for (size_t e = 0; e < a.count; ++e) {
      std::memcpy(spaced.data() + e * padded, bytes.data() + e * element, element);
    }
    bytes.swap(spaced);
    stride = int(padded);
  }
  const int view = glb.add_view(
      bytes.data(), bytes.size(),
      vertex_attribute ? TINYGLTF_TARGET_ARRAY_BUFFER : TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER,
      stride);
  return glb.add_accessor(view, 0, a.componentType, a.type, a.count, a.normalized);
}

std::string sniff_mime_type(const std::vector<unsigned char>& b) {
  const auto starts = [&](const char* magic, size_t n, size_t at = 0) {
    return b.size() >= at + n && std::memcmp(b.data() + at, magic, n) == 0;
  };
  if (starts("\x89PNG", 4)) return "image/png";
  if (starts("\xFF\xD8\xFF", 3)) return "image/jpeg";
  if (starts("RIFF", 4) && starts("WEBP", 4, 8)) return "image/webp";
  if (starts("\xABKTX 20\xBB", 8)) return "image/ktx2";
  return "";
}

/// The source's images, embedded as buffer views with their original bytes.
json copy_images(GlbBuilder& glb, const GltfFile& file) {
  json out = json::array();
  const json source = file.json.value("images", json::array());
  for (size_t i = 0; i < file.model.images.size(); ++i) {
    const tinygltf::Image& image = file.model.images[i];
    json im = i < source.size() && source[i].is_object() ? source[i] : json::object();
    im.erase("uri");
    const std::string mime = image.mimeType.empty() ? sniff_mime_type(image.image) : image.mimeType;
    if (mime.empty()) {
      throw_gltf_error(file.path, "images[" + std::to_string(i) + "]",
                       "unknown image format (not PNG, JPEG, WebP or KTX2)");
    }
    im["mimeType"] = mime;
    im["bufferView"] = glb.add_view(image.image.data(), image.image.size());
    out.push_back(std::move(im));
  }
  return out;
}

}  // namespace

GltfSourceParts copy_gltf_source(GlbBuilder& glb, const GltfSequence& source,
                                 const GltfWriteOptions& options) {
  const GltfScene& scene = *source.scene;
  const GltfFile& file = scene.file;
  const GltfMeshGeometry& g = scene.geometry;
  const tinygltf::Mesh& mesh = file.model.meshes[size_t(source.mesh)];
  GltfSourceParts parts;
  std::vector<GltfSourcePrimitive>& prims = parts.prims;
  Positions& source_normals = parts.source_normals;
  GltfTangents& source_tangents = parts.source_tangents;
  bool& any_normals = parts.any_normals;
  prims.resize(mesh.primitives.size());
  source_normals = Positions::Zero(g.num_vertices(), 3);
  source_tangents = GltfTangents::Zero(g.num_vertices(), 4);
  for (size_t p = 0; p < prims.size(); ++p) {
    GltfSourcePrimitive& sp = prims[p];
    sp.prim = &mesh.primitives[p];
    sp.range = g.primitives[p];
    const std::string name =
        "meshes[" + std::to_string(source.mesh) + "].primitives[" + std::to_string(p) + "]";
    for (const auto& [attribute, accessor] : sp.prim->attributes) {
      if (attribute == "POSITION" || attribute == "NORMAL" || attribute == "TANGENT" ||
          attribute.rfind("JOINTS_", 0) == 0 || attribute.rfind("WEIGHTS_", 0) == 0) {
        continue;
      }
      sp.shared["attributes"][attribute] = copy_accessor(glb, file, accessor, true);
    }
    if (sp.prim->indices >= 0)
      sp.shared["indices"] = copy_accessor(glb, file, sp.prim->indices, false);
    if (sp.prim->mode >= 0 && sp.prim->mode != TINYGLTF_MODE_TRIANGLES)
      sp.shared["mode"] = sp.prim->mode;
    if (sp.prim->material >= 0) {
      if (size_t(sp.prim->material) >= file.model.materials.size()) {
        throw_gltf_error(file.path, name,
                         "material " + std::to_string(sp.prim->material) + " does not exist");
      }
      sp.shared["material"] = sp.prim->material;
    }
    const auto normal = sp.prim->attributes.find("NORMAL");
    sp.normals = options.normals && normal != sp.prim->attributes.end();
    if (!sp.normals) continue;
    any_normals = true;
    const GltfAccessorValues n =
        read_gltf_accessor(file, normal->second, gltf_rules::kNormal, name + ".attributes.NORMAL");
    const auto tangent = sp.prim->attributes.find("TANGENT");
    GltfAccessorValues t;
    if (tangent != sp.prim->attributes.end()) {
      t = read_gltf_accessor(file, tangent->second, gltf_rules::kTangent,
                             name + ".attributes.TANGENT");
      sp.tangents = true;
    }
    if (n.count != sp.range.vertex_count || (sp.tangents && t.count != sp.range.vertex_count)) {
      throw_gltf_error(file.path, name, "NORMAL/TANGENT counts differ from POSITION's");
    }
    for (int v = 0; v < sp.range.vertex_count; ++v) {
      for (int c = 0; c < 3; ++c) source_normals(sp.range.first_vertex + v, c) = n.at(v, c);
      for (int c = 0; c < 4 && sp.tangents; ++c)
        source_tangents(sp.range.first_vertex + v, c) = t.at(v, c);
    }
  }
  parts.images = copy_images(glb, file);
  return parts;
}

}  // namespace sm
