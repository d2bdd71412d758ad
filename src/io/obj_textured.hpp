#pragma once
/// OBJ files with texture coordinates and a material (OBJ + MTL + image), which every viewer
/// shows textured: the checker output of the sequence job.
#include <filesystem>
#include <string>
#include <string_view>

#include "io/obj.hpp"

namespace sm {

/// An OBJ: `comment` (one `#` line per line), `mtllib <mtllib>`, one `v` per row of V (n×3), one
/// `vt` per row of uv (k×2), `usemtl <material>`, then `f a/ta b/tb c/tc` for each triangle of F
/// (m×3, into V) with uv_faces (m×3, into uv), 1-based. Numbers are the shortest text that reads
/// back exactly. No normals: viewers compute them. Byte-deterministic. Throws InputError for
/// sizes that disagree, an index out of range or a non-finite number.
std::string format_textured_obj(const Positions& V, const Triangles& F, const TexCoords& uv,
                                const Triangles& uv_faces, std::string_view mtllib,
                                std::string_view material, std::string_view comment = {});

/// An MTL file with one material `material`: white, unlit by specular highlights, its diffuse
/// colour the image `texture` (a file name beside the MTL).
std::string format_texture_mtl(std::string_view material, std::string_view texture);

}  // namespace sm
