#pragma once
/// A glTF sequence built from an OBJ mesh, so that the GLB writer (gltf_write.hpp) can write the
/// frames of an input that has no glTF asset (the track job's template): its geometry and texture
/// coordinates, normals from its surface, no materials.
#include <string>
#include <vector>

#include "io/gltf/gltf_load.hpp"
#include "io/obj.hpp"

namespace sm {

/// The sequence of `obj`'s mesh at `times` (seconds, strictly increasing as float32, at least
/// one): one glTF vertex per distinct (v, vt) corner pair of its faces, POSITION from `v`,
/// TEXCOORD_0 as (u, 1 − v) when the file has `vt` ((0, 0) for a corner without), NORMAL the
/// area-weighted normals of the mesh welded by position (so a seam of split `v`s stays smooth),
/// and an animation of constant node translation keyed at `times`. Its `rest_source` maps every
/// welded rest vertex to a `v` row of `obj`, so that frames given as positions of `obj`'s `v`
/// rows can be written. `name` names the asset in messages. Throws InputError when the mesh has
/// no triangle of non-zero extent.
GltfSequence gltf_sequence_from_obj(const ObjFile& obj, const std::vector<double>& times,
                                    const std::string& name);

}  // namespace sm
