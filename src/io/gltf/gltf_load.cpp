#include "io/gltf/gltf_load.hpp"

#include <cmath>

#include "io/gltf/gltf_scene.hpp"
#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;

namespace {

/// Most frames a glTF sequence may have, sampled by fps or one per keyframe time: planning holds
/// about 1.3 KB per frame, so this bounds it near 130 MB (about 28 minutes at 60 fps).
constexpr int kGltfMaxFrames = 100000;

/// Index of the element chosen by `index`, else called `key` in `names`: an exact name first,
/// else a decimal index.
int resolve(const fs::path& file, const char* array, const char* what, const std::string& key,
            std::optional<int> index, const std::vector<std::string>& names) {
  if (index) {
    if (*index >= 0 && size_t(*index) < names.size()) return *index;
  } else {
    for (size_t i = 0; i < names.size(); ++i) {
      if (names[i] == key) return int(i);
    }
    if (!key.empty() && key.find_first_not_of("0123456789") == std::string::npos &&
        key.size() < 10) {
      const int i = std::stoi(key);
      if (size_t(i) < names.size()) return i;
    }
  }
  std::string listing;
  for (size_t i = 0; i < names.size(); ++i) {
    listing +=
        (i ? ", " : "") + std::to_string(i) + (names[i].empty() ? "" : " '" + names[i] + "'");
  }
  const std::string wanted =
      index ? std::string("numbered ") + std::to_string(*index) : "named or numbered '" + key + "'";
  throw_gltf_error(file, array,
                   std::string("no ") + what + " " + wanted + " (the file has " +
                       (names.empty() ? std::string("none") : listing) + ")");
}

bool has_morph_targets(const tinygltf::Mesh& mesh) {
  return !mesh.primitives.empty() && !mesh.primitives[0].targets.empty();
}

/// The node that instantiates `mesh`: the first one with a skin, else the first one.
int node_of_mesh(const tinygltf::Model& m, int mesh) {
  int found = -1;
  for (size_t n = 0; n < m.nodes.size(); ++n) {
    if (m.nodes[n].mesh != mesh) continue;
    if (m.nodes[n].skin >= 0) return int(n);
    if (found < 0) found = int(n);
  }
  return found;
}

int default_mesh(const GltfFile& file) {
  const tinygltf::Model& m = file.model;
  for (const tinygltf::Node& node : m.nodes) {
    if (node.mesh >= 0 && node.skin >= 0) return node.mesh;
  }
  for (const tinygltf::Node& node : m.nodes) {
    if (node.mesh >= 0 && has_morph_targets(m.meshes[size_t(node.mesh)])) return node.mesh;
  }
  for (const tinygltf::Node& node : m.nodes) {
    if (node.mesh >= 0) return node.mesh;
  }
  throw_gltf_error(file.path, "nodes", "no node instantiates a mesh");
}

std::vector<double> frame_times(const GltfInputOptions& options, const GltfRig& rig) {
  const std::vector<double>& keys = rig.keyframe_times;
  if (!options.fps) return keys;
  check_ranges(options, "input");  // fps in its table's range
  const double fps = *options.fps;
  const double span = keys.back() - keys.front();
  if (span * fps + 1 > kGltfMaxFrames) {
    throw ConfigError("input.fps: " + std::to_string(fps) + " frames per second over " +
                      std::to_string(span) + " s exceed " + std::to_string(kGltfMaxFrames) +
                      " frames");
  }
  const int count = int(std::floor(span * fps + 1e-9)) + 1;
  std::vector<double> times(static_cast<size_t>(count));
  for (int k = 0; k < count; ++k) times[size_t(k)] = keys.front() + k / fps;
  return times;
}

// The rig checks the nodes too, but choosing the mesh reads them first (tinygltf does not check
// these indices; found by fuzzing).
void check_node_references(const GltfFile& file) {
  const tinygltf::Model& m = file.model;
  for (size_t n = 0; n < m.nodes.size(); ++n) {
    const tinygltf::Node& node = m.nodes[n];
    if (node.mesh >= int(m.meshes.size())) {
      throw_gltf_error(file.path, "nodes[" + std::to_string(n) + "]",
                       "mesh " + std::to_string(node.mesh) + " does not exist");
    }
    if (node.skin >= int(m.skins.size())) {
      throw_gltf_error(file.path, "nodes[" + std::to_string(n) + "]",
                       "skin " + std::to_string(node.skin) + " does not exist");
    }
  }
}

// The welded rest mesh of s.mesh's geometry and the map from glTF vertices to it.
void weld_rest_mesh(const GltfFile& file, const GltfMeshGeometry& geometry, GltfSequence& s) {
  GltfWeld weld = weld_by_position(geometry.base, geometry.triangles);
  if (weld.mesh.num_triangles() == 0) {
    throw_gltf_error(file.path, "meshes[" + std::to_string(s.mesh) + "]",
                     "has no triangle of non-zero extent");
  }
  s.rest = std::move(weld.mesh);
  s.weld_map = std::move(weld.map);
  s.gltf_vertices = geometry.num_vertices();
  s.welded_vertices = weld.merged;
  s.unreferenced_vertices = weld.unreferenced;
  s.dropped_triangles = weld.dropped_triangles;
}

}  // namespace

GltfSequence load_gltf_sequence(const GltfInputOptions& options) {
  return gltf_sequence_of(load_gltf_file(options.file), options);
}

GltfSequence gltf_sequence_of(GltfFile loaded, const GltfInputOptions& options) {
  auto scene = std::make_shared<GltfScene>();
  scene->file = std::move(loaded);
  const GltfFile& file = scene->file;
  const tinygltf::Model& m = file.model;
  check_node_references(file);

  GltfSequence s;
  s.file = file.path;
  std::vector<std::string> names;
  for (const tinygltf::Mesh& mesh : m.meshes) names.push_back(mesh.name);
  s.mesh = options.mesh.empty() && !options.mesh_index
               ? default_mesh(file)
               : resolve(file.path, "meshes", "mesh", options.mesh, options.mesh_index, names);
  s.mesh_name = m.meshes[size_t(s.mesh)].name;
  s.node = node_of_mesh(m, s.mesh);
  if (s.node < 0) {
    throw_gltf_error(file.path, "meshes[" + std::to_string(s.mesh) + "]",
                     "no node instantiates it");
  }
  if (m.animations.empty()) {
    throw_gltf_error(file.path, "animations",
                     "the file has no animation, so it is not a sequence (a static model has "
                     "nothing to correct)");
  }
  names.clear();
  for (const tinygltf::Animation& a : m.animations) names.push_back(a.name);
  s.animation = options.animation.empty() && !options.animation_index
                    ? 0
                    : resolve(file.path, "animations", "animation", options.animation,
                              options.animation_index, names);
  s.animation_name = m.animations[size_t(s.animation)].name;

  scene->rig = load_gltf_rig(file, s.animation);
  if (scene->rig.keyframe_times.empty()) {
    throw_gltf_error(file.path, "animations[" + std::to_string(s.animation) + "]",
                     "has no channel with a target node");
  }
  scene->node = s.node;
  scene->geometry = load_gltf_mesh_geometry(file, s.mesh, m.nodes[size_t(s.node)].skin);

  weld_rest_mesh(file, scene->geometry, s);

  if (!options.fps && scene->rig.keyframe_times.size() > size_t(kGltfMaxFrames)) {
    throw_gltf_error(file.path, "animations[" + std::to_string(s.animation) + "]",
                     std::to_string(scene->rig.keyframe_times.size()) +
                         " distinct keyframe times exceed " + std::to_string(kGltfMaxFrames) +
                         " frames (set input.fps to sample fewer)");
  }
  s.times = frame_times(options, scene->rig);
  for (size_t k = 1; k < s.times.size(); ++k) {
    if (!(float(s.times[k]) > float(s.times[k - 1]))) {
      throw ConfigError("input.fps: frame times " + std::to_string(s.times[k - 1]) + " and " +
                        std::to_string(s.times[k]) + " s are equal as float32 (fps too high)");
    }
  }
  s.scene = std::move(scene);
  return s;
}

Positions evaluate_gltf_vertices(const GltfSequence& sequence, double t) {
  const GltfScene& scene = *sequence.scene;
  return gltf_mesh_positions(scene.geometry, scene.rig, scene.node, t);
}

WeldedFrame evaluate_gltf_frame(const GltfSequence& sequence, int frame) {
  if (frame < 0 || frame >= sequence.num_frames()) {
    throw InputError("'" + sequence.file.string() + "': frame " + std::to_string(frame) +
                     " is out of range (the sequence has " + std::to_string(sequence.num_frames()) +
                     " frames)");
  }
  const Positions P = evaluate_gltf_vertices(sequence, sequence.times[size_t(frame)]);
  const double tolerance = 1e-5 * bounding_box_diagonal(P);
  return weld_frame(sequence.weld_map, sequence.rest.num_vertices(), P, tolerance);
}

}  // namespace sm
