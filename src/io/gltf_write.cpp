#include "io/gltf_write.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

#include "io/atomic_file.hpp"
#include "io/gltf_accessor.hpp"
#include "io/gltf_glb.hpp"
#include "io/gltf_scene.hpp"
#include "mesh/errors.hpp"

namespace sm {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using Tangents = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>;

/// Rows [first, first + count) of M as floats (the layout of a VEC3/VEC4 float accessor).
template <typename Matrix>
std::vector<float> float_rows(const Matrix& M, const GltfPrimitiveRange& r, int columns) {
  std::vector<float> out;
  out.reserve(size_t(r.vertex_count) * size_t(columns));
  for (int v = r.first_vertex; v < r.first_vertex + r.vertex_count; ++v) {
    for (int c = 0; c < columns; ++c) out.push_back(float(M(v, c)));
  }
  return out;
}

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

void collect_extensions(const json& j, std::set<std::string>& names) {
  if (j.is_object()) {
    const auto ext = j.find("extensions");
    if (ext != j.end() && ext->is_object()) {
      for (const auto& item : ext->items()) names.insert(item.key());
    }
    for (const auto& item : j.items()) collect_extensions(item.value(), names);
  } else if (j.is_array()) {
    for (const json& e : j) collect_extensions(e, names);
  }
}

/// Per glTF vertex, the rotation that takes the welded rest normal to the frame's normal, applied
/// to the source normals and tangents (xyz; w is the handedness and stays).
void transport_normals(const std::vector<int>& map, const Positions& rest_normals,
                       const Positions& frame_normals, const Positions& source_normals,
                       const Tangents& source_tangents, Positions& normals, Tangents& tangents) {
  std::vector<Eigen::Quaterniond> turn(size_t(rest_normals.rows()), Eigen::Quaterniond::Identity());
  for (Eigen::Index w = 0; w < rest_normals.rows(); ++w) {
    const Vec3 a = rest_normals.row(w).transpose(), b = frame_normals.row(w).transpose();
    if (a.squaredNorm() > 0 && b.squaredNorm() > 0) turn[size_t(w)].setFromTwoVectors(a, b);
  }
  normals = source_normals;
  tangents = source_tangents;
  for (size_t v = 0; v < map.size(); ++v) {
    if (map[v] < 0) continue;
    const Eigen::Quaterniond& q = turn[size_t(map[v])];
    const auto i = Eigen::Index(v);
    const Vec3 n = q * Vec3(source_normals.row(i).transpose());
    if (n.squaredNorm() > 0) normals.row(i) = n.normalized().transpose();
    const Vec3 t = q * Vec3(source_tangents.row(i).head<3>().transpose());
    if (t.squaredNorm() > 0) tangents.row(i).head<3>() = t.normalized().transpose();
  }
}

struct SourcePrimitive {
  const tinygltf::Primitive* prim = nullptr;
  GltfPrimitiveRange range;
  bool normals = false;
  bool tangents = false;
  json shared = json::object();  ///< output primitive without POSITION/NORMAL/TANGENT and targets
};

struct Chunk {
  int first = 0;
  int count = 0;
  std::vector<json> primitives;  ///< per source primitive, with base attributes and targets
};

void check_frame(const fs::path& out, const GltfSequence& source, int k, const Positions& W) {
  const auto fail = [&](const std::string& why) {
    throw InputError("writing '" + out.string() + "': corrected frame " + std::to_string(k) + " " +
                     why);
  };
  if (W.rows() != source.rest.num_vertices()) {
    fail("has " + std::to_string(W.rows()) + " vertices, the welded mesh has " +
         std::to_string(source.rest.num_vertices()));
  }
  if (!W.allFinite()) fail("has a coordinate that is not finite");
}

// What the GLB takes over from the source once: its primitives' attributes that do not move
// (texture coordinates, colours), indices and materials, its normals and tangents, its images.
// Everything about the source that writing can refuse is refused here (write_gltf_sequence and,
// before anything is written, check_gltf_sequence_source).
struct SourceParts {
  std::vector<SourcePrimitive> prims;
  Positions source_normals;
  Tangents source_tangents;
  bool any_normals = false;
  json images;
};

SourceParts copy_source(GlbBuilder& glb, const GltfSequence& source,
                        const GltfWriteOptions& options) {
  const GltfScene& scene = *source.scene;
  const GltfFile& file = scene.file;
  const GltfMeshGeometry& g = scene.geometry;
  const tinygltf::Mesh& mesh = file.model.meshes[size_t(source.mesh)];
  SourceParts parts;
  std::vector<SourcePrimitive>& prims = parts.prims;
  Positions& source_normals = parts.source_normals;
  Tangents& source_tangents = parts.source_tangents;
  bool& any_normals = parts.any_normals;
  prims.resize(mesh.primitives.size());
  source_normals = Positions::Zero(g.num_vertices(), 3);
  source_tangents = Tangents::Zero(g.num_vertices(), 4);
  for (size_t p = 0; p < prims.size(); ++p) {
    SourcePrimitive& sp = prims[p];
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

}  // namespace

void check_gltf_sequence_source(const GltfSequence& source, const GltfWriteOptions& options) {
  GlbBuilder glb;
  copy_source(glb, source, options);
}

GltfWriteReport write_gltf_sequence(const fs::path& out_glb, const GltfSequence& source,
                                    const GltfFrameSource& corrected_frame,
                                    const GltfWriteOptions& options) {
  const GltfScene& scene = *source.scene;
  const GltfFile& file = scene.file;
  const GltfMeshGeometry& g = scene.geometry;
  const int frames = source.num_frames();
  const int per_mesh = std::max(1, options.frames_per_mesh);
  GlbBuilder glb;

  SourceParts parts = copy_source(glb, source, options);
  const std::vector<SourcePrimitive>& prims = parts.prims;
  const Positions& source_normals = parts.source_normals;
  const Tangents& source_tangents = parts.source_tangents;
  const bool any_normals = parts.any_normals;
  json& images = parts.images;

  const size_t per_frame = size_t(g.num_vertices()) * 4 * (any_normals ? 9 : 3);
  glb.reserve(glb.binary_size() + per_frame * size_t(frames + frames / per_mesh + 1) +
              size_t(frames) * size_t(per_mesh) * 4 + size_t(frames) * 16);

  // Frames: each mesh's base is its first frame; every frame is a morph target relative to it.
  const Positions rest_normals = any_normals ? vertex_normals(source.rest) : Positions();
  TriMesh frame_mesh = source.rest;
  Positions base, base_normals, normals;
  Tangents base_tangents, tangents;
  std::vector<Chunk> chunks;
  for (int k = 0; k < frames; ++k) {
    const Positions W = corrected_frame(k);
    check_frame(out_glb, source, k, W);
    const Positions G = unweld_frame(source.weld_map, W, g.base);
    if (any_normals) {
      frame_mesh.V = W;
      transport_normals(source.weld_map, rest_normals, vertex_normals(frame_mesh), source_normals,
                        source_tangents, normals, tangents);
    }
    if (k % per_mesh == 0) {
      chunks.push_back({k, std::min(per_mesh, frames - k), {}});
      base = G.cast<float>().cast<double>();
      base_normals = normals.cast<float>().cast<double>();
      base_tangents = tangents.cast<float>().cast<double>();
      for (const SourcePrimitive& sp : prims) {
        json prim = sp.shared;
        prim["attributes"]["POSITION"] = glb.add_floats(
            float_rows(base, sp.range, 3), TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
        if (sp.normals) {
          prim["attributes"]["NORMAL"] =
              glb.add_floats(float_rows(base_normals, sp.range, 3), TINYGLTF_TYPE_VEC3,
                             TINYGLTF_TARGET_ARRAY_BUFFER, false);
        }
        if (sp.tangents) {
          prim["attributes"]["TANGENT"] =
              glb.add_floats(float_rows(base_tangents, sp.range, 4), TINYGLTF_TYPE_VEC4,
                             TINYGLTF_TARGET_ARRAY_BUFFER, false);
        }
        prim["targets"] = json::array();
        chunks.back().primitives.push_back(std::move(prim));
      }
    }
    const Positions D = G - base;
    const Positions DN = any_normals ? Positions(normals - base_normals) : Positions();
    const Positions DT =
        any_normals ? Positions((tangents - base_tangents).leftCols<3>()) : Positions();
    for (size_t p = 0; p < prims.size(); ++p) {
      const SourcePrimitive& sp = prims[p];
      json target = {{"POSITION", glb.add_floats(float_rows(D, sp.range, 3), TINYGLTF_TYPE_VEC3,
                                                 TINYGLTF_TARGET_ARRAY_BUFFER, true)}};
      if (sp.normals) {
        target["NORMAL"] = glb.add_floats(float_rows(DN, sp.range, 3), TINYGLTF_TYPE_VEC3,
                                          TINYGLTF_TARGET_ARRAY_BUFFER, false);
      }
      if (sp.tangents) {
        target["TANGENT"] = glb.add_floats(float_rows(DT, sp.range, 3), TINYGLTF_TYPE_VEC3,
                                           TINYGLTF_TARGET_ARRAY_BUFFER, false);
      }
      chunks.back().primitives[p]["targets"].push_back(std::move(target));
    }
  }

  // Animation: per mesh, STEP weights that select target j at its frame's time; with several
  // meshes, STEP scale keys show each one only during its frames.
  std::vector<float> times(source.times.begin(), source.times.end());
  const int times_view = glb.add_view(times.data(), times.size() * sizeof(float));
  json& doc = glb.document();
  json samplers = json::array(), channels = json::array(), meshes = json::array(),
       nodes = json::array();
  const std::string mesh_name = source.mesh_name.empty() ? "mesh" : source.mesh_name;
  const auto add_sampler = [&](int input, int output, int node, const char* path) {
    samplers.push_back({{"input", input}, {"output", output}, {"interpolation", "STEP"}});
    channels.push_back(
        {{"sampler", samplers.size() - 1}, {"target", {{"node", node}, {"path", path}}}});
  };
  for (size_t c = 0; c < chunks.size(); ++c) {
    const Chunk& ch = chunks[c];
    const int last = ch.first + ch.count - 1;
    json target_names = json::array();
    for (int k = ch.first; k <= last; ++k) target_names.push_back("frame " + std::to_string(k));
    meshes.push_back(
        {{"name", mesh_name + " frames " + std::to_string(ch.first) + "-" + std::to_string(last)},
         {"primitives", ch.primitives},
         {"weights", std::vector<double>(size_t(ch.count), 0.0)},
         {"extras", {{"targetNames", target_names}}}});
    json node = {{"name", "frames " + std::to_string(ch.first) + "-" + std::to_string(last)},
                 {"mesh", c}};
    if (c > 0) node["scale"] = {0.0, 0.0, 0.0};
    nodes.push_back(std::move(node));

    const int input =
        glb.add_accessor(times_view, size_t(ch.first) * sizeof(float),
                         TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, size_t(ch.count),
                         false, {double(times[size_t(ch.first)])}, {double(times[size_t(last)])});
    std::vector<float> one_hot(size_t(ch.count) * size_t(ch.count), 0.0f);
    for (int j = 0; j < ch.count; ++j) one_hot[size_t(j) * size_t(ch.count) + size_t(j)] = 1.0f;
    add_sampler(input, glb.add_floats(one_hot, TINYGLTF_TYPE_SCALAR, 0, false), int(c), "weights");
    if (chunks.size() > 1) {
      std::vector<float> key_times, scales;
      const auto key = [&](int frame, float s) {
        key_times.push_back(times[size_t(frame)]);
        scales.insert(scales.end(), {s, s, s});
      };
      if (c > 0) key(0, 0.0f);
      key(ch.first, 1.0f);
      if (c + 1 < chunks.size()) key(ch.first + ch.count, 0.0f);
      add_sampler(glb.add_floats(key_times, TINYGLTF_TYPE_SCALAR, 0, true),
                  glb.add_floats(scales, TINYGLTF_TYPE_VEC3, 0, false), int(c), "scale");
    }
  }
  json scene_nodes = json::array();
  for (size_t c = 0; c < chunks.size(); ++c) scene_nodes.push_back(c);

  json asset = {{"version", "2.0"}, {"generator", "seqmassage"}};
  const json source_asset = file.json.value("asset", json::object());
  if (source_asset.contains("copyright")) asset["copyright"] = source_asset["copyright"];
  asset["extras"] = {{"seqmassage",
                      {{"source", source.file.filename().string()},
                       {"mesh", source.mesh},
                       {"animation", source.animation},
                       {"frames", frames}}}};
  doc["asset"] = asset;
  doc["scene"] = 0;
  doc["scenes"] = json::array({{{"nodes", scene_nodes}}});
  doc["nodes"] = nodes;
  doc["meshes"] = meshes;
  doc["animations"] =
      json::array({{{"name", source.animation_name.empty() ? "sequence" : source.animation_name},
                    {"samplers", samplers},
                    {"channels", channels}}});
  for (const char* key : {"materials", "textures", "samplers"}) {
    if (file.json.contains(key)) doc[key] = file.json.at(key);
  }
  if (!images.empty()) doc["images"] = std::move(images);

  std::set<std::string> used;
  for (const char* key : {"materials", "textures", "samplers", "images"}) {
    if (doc.contains(key)) collect_extensions(doc[key], used);
  }
  const auto names_in = [&](const char* key) {
    std::vector<std::string> names;
    for (const json& name : file.json.value(key, json::array())) {
      if (name.is_string()) names.push_back(name.get<std::string>());
    }
    return names;
  };
  json used_list = json::array(), required_list = json::array();
  for (const std::string& name : names_in("extensionsUsed")) {
    // Copied texture coordinates and colours may be quantized.
    if (name == "KHR_mesh_quantization") used.insert(name);
    if (used.count(name) && gltf_extension_is_kept(name)) used_list.push_back(name);
  }
  for (const std::string& name : names_in("extensionsRequired")) {
    if (used.count(name) && gltf_extension_is_kept(name)) required_list.push_back(name);
  }
  if (!used_list.empty()) doc["extensionsUsed"] = used_list;
  if (!required_list.empty()) doc["extensionsRequired"] = required_list;

  const std::string bytes = glb.finish();
  write_file_atomic(out_glb, bytes);
  return {frames, int(chunks.size()), bytes.size()};
}

GltfWriteReport write_gltf_sequence(const fs::path& out_glb, const GltfSequence& source,
                                    const std::vector<Positions>& corrected_frames,
                                    const GltfWriteOptions& options) {
  if (int(corrected_frames.size()) != source.num_frames()) {
    throw InputError("writing '" + out_glb.string() +
                     "': " + std::to_string(corrected_frames.size()) +
                     " corrected frames for a sequence of " + std::to_string(source.num_frames()));
  }
  return write_gltf_sequence(
      out_glb, source, [&](int k) { return corrected_frames[size_t(k)]; }, options);
}

}  // namespace sm
