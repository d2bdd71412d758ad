#pragma once
/// A glTF sequence's frames as OBJ files: the welded vertices as `v`, the source's texture
/// coordinates and normal seams kept, so that format_obj(layout, V) writes any frame.
#include <string>

#include "io/gltf/gltf_load.hpp"
#include "io/obj.hpp"

namespace sm {

/// The OBJ form of `sequence`'s welded mesh, positions at the rest pose: one `v` per welded vertex
/// (the optimizer's vertices, in their order), one `vt` per glTF vertex of a primitive with
/// TEXCOORD_0 (as (u, 1 − v): glTF's v axis points down the image, OBJ's up), one `vn` per distinct
/// (welded vertex, source NORMAL) pair of a primitive with NORMAL (so normal seams stay hard edges
/// and UV-only seams stay smooth when format_obj recomputes them), and one `f` per welded triangle
/// in `sequence.rest.F`'s order, under `g primitive_<p>`. `comment` opens the file (one `#` line
/// per line of text). The layout's mesh.F equals sequence.rest.F. Throws InputError naming the glTF
/// element for TEXCOORD_0 or NORMAL accessors that are malformed or of the wrong count.
ObjFile gltf_obj_layout(const GltfSequence& sequence, const std::string& comment);

}  // namespace sm
