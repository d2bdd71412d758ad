#pragma once
/// The options of the GLB writer (gltf_write.hpp) and their config keys ("output.gltf"); a low
/// header, which the writer's parts (gltf_write_source.hpp) include.
#include <optional>

#include "core/options_table.hpp"

namespace sm {

struct GltfWriteOptions {
  /// Morph targets per mesh. A longer sequence is split into consecutive meshes of this many
  /// frames, each on its own node, shown in turn by STEP scale keys (0 hides a node). 256 keeps
  /// every mesh within the morph target limits of WebGL2 viewers (three.js, Babylon.js, Filament).
  int frames_per_mesh = 256;
  /// Write NORMAL (and TANGENT) morph deltas that turn the source's normals with the corrected
  /// surface (omitted for primitives without NORMAL; false drops normals and tangents so viewers
  /// compute flat normals, halving the file).
  bool normals = true;
  /// Frames per second of frames without times (the track job's raw frames): frame k shows
  /// from k / fps seconds on; unset: kDefaultFps. A glTF input keeps its own times (and refuses
  /// the key).
  std::optional<double> fps;
  static constexpr double kDefaultFps = 24.0;
};

template <>
inline const Fields<GltfWriteOptions>& fields_of<GltfWriteOptions>() {
  using O = GltfWriteOptions;
  static const Fields<O> fields = {
      field<&O::frames_per_mesh>("frames_per_mesh", closed(1, 100000),
                                 "morph targets per mesh of `sequence.glb`; longer sequences are "
                                 "split over meshes shown in turn"),
      field<&O::normals>("normals", any_value(),
                         "NORMAL/TANGENT morph deltas that turn the source's normals with the "
                         "corrected surface; `false` writes positions only (viewers compute "
                         "flat normals)"),
      field<&O::fps>("fps", left_open(0, 1e6),
                     "frame times of the track job's `sequence.glb`: frame k from k / fps "
                     "seconds on; `null`: 24 (a glTF input keeps its own times)"),
  };
  return fields;
}

}  // namespace sm
