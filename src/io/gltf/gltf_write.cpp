#include "io/gltf/gltf_write.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

#include "io/atomic_file.hpp"
#include "io/gltf/gltf_glb.hpp"
#include "io/gltf/gltf_scene.hpp"
#include "io/gltf/gltf_write_source.hpp"
#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

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
                       const GltfTangents& source_tangents, Positions& normals,
                       GltfTangents& tangents) {
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

// The primitive of a chunk's mesh: the shared parts and the base frame's attributes.
json base_primitive(GlbBuilder& glb, const GltfSourcePrimitive& sp, const Positions& base,
                    const Positions& normals, const GltfTangents& tangents) {
  json prim = sp.shared;
  prim["attributes"]["POSITION"] = glb.add_floats(float_rows(base, sp.range, 3), TINYGLTF_TYPE_VEC3,
                                                  TINYGLTF_TARGET_ARRAY_BUFFER, true);
  if (sp.normals) {
    prim["attributes"]["NORMAL"] = glb.add_floats(
        float_rows(normals, sp.range, 3), TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  }
  if (sp.tangents) {
    prim["attributes"]["TANGENT"] = glb.add_floats(
        float_rows(tangents, sp.range, 4), TINYGLTF_TYPE_VEC4, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  }
  prim["targets"] = json::array();
  return prim;
}

// One frame's morph target of a primitive: its offsets D (normals DN, tangents DT) from the base.
json morph_target(GlbBuilder& glb, const GltfSourcePrimitive& sp, const Positions& D,
                  const Positions& DN, const Positions& DT) {
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
  return target;
}

// Frames: each mesh's base is its first frame; every frame is a morph target relative to it.
std::vector<Chunk> add_frames(GlbBuilder& glb, const fs::path& out_glb, const GltfSequence& source,
                              const GltfFrameSource& corrected_frame, const GltfSourceParts& parts,
                              int per_mesh) {
  const int frames = source.num_frames();
  const bool any_normals = parts.any_normals;
  const Positions rest_normals = any_normals ? vertex_normals(source.rest) : Positions();
  TriMesh frame_mesh = source.rest;
  Positions base, base_normals, normals;
  GltfTangents base_tangents, tangents;
  std::vector<Chunk> chunks;
  for (int k = 0; k < frames; ++k) {
    const Positions W = corrected_frame(k);
    check_frame(out_glb, source, k, W);
    const Positions G = unweld_frame(source.weld_map, W, source.scene->geometry.base);
    if (any_normals) {
      frame_mesh.V = W;
      transport_normals(source.weld_map, rest_normals, vertex_normals(frame_mesh),
                        parts.source_normals, parts.source_tangents, normals, tangents);
    }
    if (k % per_mesh == 0) {
      chunks.push_back({k, std::min(per_mesh, frames - k), {}});
      base = G.cast<float>().cast<double>();
      base_normals = normals.cast<float>().cast<double>();
      base_tangents = tangents.cast<float>().cast<double>();
      for (const GltfSourcePrimitive& sp : parts.prims)
        chunks.back().primitives.push_back(
            base_primitive(glb, sp, base, base_normals, base_tangents));
    }
    const Positions D = G - base;
    const Positions DN = any_normals ? Positions(normals - base_normals) : Positions();
    const Positions DT =
        any_normals ? Positions((tangents - base_tangents).leftCols<3>()) : Positions();
    for (size_t p = 0; p < parts.prims.size(); ++p)
      chunks.back().primitives[p]["targets"].push_back(
          morph_target(glb, parts.prims[p], D, DN, DT));
  }
  return chunks;
}

// The animation's samplers and channels, and a node and a mesh per chunk.
struct Animation {
  json samplers = json::array(), channels = json::array(), meshes = json::array(),
       nodes = json::array();

  void add_sampler(int input, int output, int node, const char* path) {
    samplers.push_back({{"input", input}, {"output", output}, {"interpolation", "STEP"}});
    channels.push_back(
        {{"sampler", samplers.size() - 1}, {"target", {{"node", node}, {"path", path}}}});
  }
};

// Chunk c's mesh (its morph targets named by frame) and node (hidden but for the first).
void add_chunk_mesh(Animation& anim, const std::string& mesh_name, const Chunk& ch, size_t c) {
  const int last = ch.first + ch.count - 1;
  json target_names = json::array();
  for (int k = ch.first; k <= last; ++k) target_names.push_back("frame " + std::to_string(k));
  anim.meshes.push_back(
      {{"name", mesh_name + " frames " + std::to_string(ch.first) + "-" + std::to_string(last)},
       {"primitives", ch.primitives},
       {"weights", std::vector<double>(size_t(ch.count), 0.0)},
       {"extras", {{"targetNames", target_names}}}});
  json node = {{"name", "frames " + std::to_string(ch.first) + "-" + std::to_string(last)},
               {"mesh", c}};
  if (c > 0) node["scale"] = {0.0, 0.0, 0.0};
  anim.nodes.push_back(std::move(node));
}

// Per mesh, STEP weights that select target j at its frame's time; with several meshes, STEP
// scale keys show each one only during its frames.
Animation animate_chunks(GlbBuilder& glb, const GltfSequence& source,
                         const std::vector<Chunk>& chunks) {
  std::vector<float> times(source.times.begin(), source.times.end());
  const int times_view = glb.add_view(times.data(), times.size() * sizeof(float));
  const std::string mesh_name = source.mesh_name.empty() ? "mesh" : source.mesh_name;
  Animation anim;
  for (size_t c = 0; c < chunks.size(); ++c) {
    const Chunk& ch = chunks[c];
    const int last = ch.first + ch.count - 1;
    add_chunk_mesh(anim, mesh_name, ch, c);
    const int input =
        glb.add_accessor(times_view, size_t(ch.first) * sizeof(float),
                         TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, size_t(ch.count),
                         false, {double(times[size_t(ch.first)])}, {double(times[size_t(last)])});
    std::vector<float> one_hot(size_t(ch.count) * size_t(ch.count), 0.0f);
    for (int j = 0; j < ch.count; ++j) one_hot[size_t(j) * size_t(ch.count) + size_t(j)] = 1.0f;
    anim.add_sampler(input, glb.add_floats(one_hot, TINYGLTF_TYPE_SCALAR, 0, false), int(c),
                     "weights");
    if (chunks.size() == 1) continue;
    std::vector<float> key_times, scales;
    const auto key = [&](int frame, float s) {
      key_times.push_back(times[size_t(frame)]);
      scales.insert(scales.end(), {s, s, s});
    };
    if (c > 0) key(0, 0.0f);
    key(ch.first, 1.0f);
    if (c + 1 < chunks.size()) key(ch.first + ch.count, 0.0f);
    anim.add_sampler(glb.add_floats(key_times, TINYGLTF_TYPE_SCALAR, 0, true),
                     glb.add_floats(scales, TINYGLTF_TYPE_VEC3, 0, false), int(c), "scale");
  }
  return anim;
}

json output_asset(const GltfSequence& source) {
  json asset = {{"version", "2.0"}, {"generator", "seqmassage"}};
  const json source_asset = source.scene->file.json.value("asset", json::object());
  if (source_asset.contains("copyright")) asset["copyright"] = source_asset["copyright"];
  asset["extras"] = {{"seqmassage",
                      {{"source", source.file.filename().string()},
                       {"mesh", source.mesh},
                       {"animation", source.animation},
                       {"frames", source.num_frames()}}}};
  return asset;
}

// The source's extensionsUsed / extensionsRequired that the output's copied parts still use.
void copy_extension_lists(json& doc, const GltfFile& file) {
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
}

// The document: the asset, scene, chunk nodes and meshes, the animation, the copied materials.
void fill_document(json& doc, const GltfSequence& source, Animation anim, size_t num_chunks,
                   json images) {
  const GltfFile& file = source.scene->file;
  json scene_nodes = json::array();
  for (size_t c = 0; c < num_chunks; ++c) scene_nodes.push_back(c);
  doc["asset"] = output_asset(source);
  doc["scene"] = 0;
  doc["scenes"] = json::array({{{"nodes", scene_nodes}}});
  doc["nodes"] = std::move(anim.nodes);
  doc["meshes"] = std::move(anim.meshes);
  doc["animations"] =
      json::array({{{"name", source.animation_name.empty() ? "sequence" : source.animation_name},
                    {"samplers", std::move(anim.samplers)},
                    {"channels", std::move(anim.channels)}}});
  for (const char* key : {"materials", "textures", "samplers"}) {
    if (file.json.contains(key)) doc[key] = file.json.at(key);
  }
  if (!images.empty()) doc["images"] = std::move(images);
  copy_extension_lists(doc, file);
}

}  // namespace

void check_gltf_sequence_source(const GltfSequence& source, const GltfWriteOptions& options) {
  GlbBuilder glb;
  copy_gltf_source(glb, source, options);
}

GltfWriteReport write_gltf_sequence(const fs::path& out_glb, const GltfSequence& source,
                                    const GltfFrameSource& corrected_frame,
                                    const GltfWriteOptions& options) {
  const int frames = source.num_frames();
  const int per_mesh = std::max(1, options.frames_per_mesh);
  GlbBuilder glb;
  GltfSourceParts parts = copy_gltf_source(glb, source, options);
  const size_t per_frame =
      size_t(source.scene->geometry.num_vertices()) * 4 * (parts.any_normals ? 9 : 3);
  glb.reserve(glb.binary_size() + per_frame * size_t(frames + frames / per_mesh + 1) +
              size_t(frames) * size_t(per_mesh) * 4 + size_t(frames) * 16);
  const std::vector<Chunk> chunks =
      add_frames(glb, out_glb, source, corrected_frame, parts, per_mesh);
  fill_document(glb.document(), source, animate_chunks(glb, source, chunks), chunks.size(),
                std::move(parts.images));
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
