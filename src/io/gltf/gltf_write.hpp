#pragma once
/// Writing a corrected sequence as a GLB that common viewers play: the source mesh's primitives
/// with their materials, textures and texture coordinates, one morph target per frame, and a STEP
/// animation of the morph weights that shows frame k from times[k] on.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <vector>

#include "io/gltf/gltf_load.hpp"
#include "io/gltf/gltf_write_options.hpp"

namespace sm {

struct GltfWriteReport {
  int frames = 0;
  int meshes = 0;    ///< nodes/meshes the frames were split over
  size_t bytes = 0;  ///< size of the GLB written
};

/// Returns the corrected positions of frame k on the welded vertices (rest.num_vertices() × 3).
using GltfFrameSource = std::function<Positions(int frame)>;

/// Throws the InputError that write_gltf_sequence would throw for `source` itself (an image of
/// unknown format, a missing material, unreadable NORMAL or TANGENT accessors), so that planning
/// refuses it before any output is written. Memory: a copy of the attributes and images it takes.
void check_gltf_sequence_source(const GltfSequence& source, const GltfWriteOptions& options = {});

/// Writes `out_glb` atomically. `corrected_frame` is called once per frame, in order 0, 1, ...,
/// so frames can be produced or read back one at a time; corrected positions are written to every
/// split copy of a welded vertex. Memory: the GLB's binary data (about 4·(3 + 3 + 3)·n bytes per
/// frame for n glTF vertices with normals and tangents, plus 4·k² bytes of weights per mesh of k
/// frames) is held twice at the end, when the file is assembled. Throws InputError naming the
/// frame when a frame has the wrong row count or non-finite values (nothing is written), IoError
/// when the file cannot be written or would exceed the GLB limit of 4 GiB.
GltfWriteReport write_gltf_sequence(const std::filesystem::path& out_glb,
                                    const GltfSequence& source,
                                    const GltfFrameSource& corrected_frame,
                                    const GltfWriteOptions& options = {});

/// Same, from frames held in memory (one per source frame).
GltfWriteReport write_gltf_sequence(const std::filesystem::path& out_glb,
                                    const GltfSequence& source,
                                    const std::vector<Positions>& corrected_frames,
                                    const GltfWriteOptions& options = {});

}  // namespace sm
