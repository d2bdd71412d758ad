#pragma once
/// Loading an animated glTF 2.0 mesh as a frame sequence: choice of mesh and animation, frame
/// times, welding of split vertices, and evaluation of any frame on the welded connectivity.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/gltf/gltf_weld.hpp"
#include "mesh/mesh.hpp"
#include "core/options_table.hpp"

namespace sm {

/// The "input" of a glTF job: {"gltf": file, "mesh": name or index, "animation": name or index,
/// "fps": rate}.
struct GltfInputOptions {
  std::filesystem::path file;
  /// meshes[] name, or index as text; empty = the mesh of the first node with a skin, else the
  /// first mesh with morph targets, else the first mesh that a node instantiates.
  std::string mesh;
  /// animations[] name, or index as text; empty = the first animation.
  std::string animation;
  /// Frames per second; absent = one frame per keyframe time of the animation.
  std::optional<double> fps;
  /// meshes[] / animations[] index given as a number (the config's integer form): an index only,
  /// never a name; replaces `mesh` / `animation` when set.
  std::optional<int> mesh_index = std::nullopt;
  std::optional<int> animation_index = std::nullopt;
};

/// The keys sit in the sequence job's "input", beside "range"; "gltf" comes first (it says the
/// input is a glTF animation).
template <>
inline const Fields<GltfInputOptions>& fields_of<GltfInputOptions>() {
  using O = GltfInputOptions;
  static const Fields<O> fields = {
      field<&O::file>("gltf", any_value(),
                      "a glTF 2.0 animation (skinned or morph-target, `.gltf` or `.glb`) "
                      "sampled to frames"),
      selector_field<&O::mesh, &O::mesh_index>(
          "mesh",
          "`meshes[]` of the glTF file; `null`: the mesh of the first node with a skin, else the "
          "first mesh with morph targets, else the first mesh a node instantiates; only with "
          "`input.gltf`"),
      selector_field<&O::animation, &O::animation_index>(
          "animation",
          "`animations[]` of the glTF file; `null`: the first animation (index 0); only with "
          "`input.gltf`"),
      field<&O::fps>("fps", left_open(0, 1e6),
                     "frames at `t0 + k/fps` (t0 the first keyframe time) up to the last keyframe "
                     "time; `null`: one frame per distinct keyframe time of the animation's "
                     "samplers; more than 100,000 frames, or frame times equal as float32, are a "
                     "config error; only with `input.gltf`"),
  };
  return fields;
}

struct GltfFile;   // io/gltf/gltf_file.hpp: a loaded asset
struct GltfScene;  // io/gltf/gltf_scene.hpp: the source asset, rig and mesh geometry

/// A glTF animation as a sequence of frames on one welded connectivity. Copying is cheap (the
/// source is shared) and evaluation is const and thread-safe, so frames can be evaluated in
/// parallel and streamed instead of held in memory.
struct GltfSequence {
  std::filesystem::path file;
  int mesh = -1;
  std::string mesh_name;
  int node = -1;  ///< the node that instantiates the mesh
  int animation = -1;
  std::string animation_name;

  /// Welded rest pose: the mesh's POSITION values (before morphing, skinning and node transforms)
  /// and the triangles of all its primitives. This is the connectivity for the optimizer; frames
  /// are in world space, so a sequence template is usually frame 0 rather than this pose.
  TriMesh rest;
  std::vector<double> times;      ///< seconds, strictly increasing (also as float32)
  std::vector<int> weld_map;      ///< glTF vertex (all primitives, in order) -> rest vertex, or -1
  int gltf_vertices = 0;          ///< vertices of all primitives together
  int welded_vertices = 0;        ///< split copies merged into another vertex
  int unreferenced_vertices = 0;  ///< glTF vertices in no triangle (weld_map -1)
  int dropped_triangles = 0;      ///< triangles that collapse when welded (left out of `rest`)

  std::shared_ptr<const GltfScene> scene;
  /// Built from an OBJ mesh (gltf_from_obj.hpp): rest vertex -> the row of the `source_rows`
  /// positions a frame is given as (the OBJ's `v` rows); empty for an asset loaded from a file,
  /// whose frames are on the rest vertices.
  std::vector<int> rest_source;
  int source_rows = 0;

  int num_frames() const { return int(times.size()); }
};

/// Loads the sequence. Throws IoError when a file cannot be read, ConfigError for fps <= 0 or an
/// fps that makes float32 times collide, and InputError naming the file and the glTF element for
/// malformed glTF, an unknown mesh or animation, a file without animation (a static model is not a
/// sequence), or a mesh without triangles.
GltfSequence load_gltf_sequence(const GltfInputOptions& options);

/// The same for an asset loaded already (`options.file` is not read: `loaded` is that file).
GltfSequence gltf_sequence_of(GltfFile loaded, const GltfInputOptions& options);

/// Positions of every glTF vertex (gltf_vertices × 3, world space) at time `t` in seconds.
Positions evaluate_gltf_vertices(const GltfSequence& sequence, double t);

/// Frame `frame` on the welded vertices. Welded copies are checked to coincide within 1e-5 of the
/// frame's bounding-box diagonal; those that do not (skin weights that differ between copies) are
/// counted in the result, and their mean position is used.
WeldedFrame evaluate_gltf_frame(const GltfSequence& sequence, int frame);

}  // namespace sm
