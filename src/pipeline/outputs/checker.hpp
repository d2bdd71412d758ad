#pragma once
/// The checker output (the paper's Figure 6): texture coordinates fixed on the template and a
/// checkerboard texture, so that a frame whose vertices slid over the surface shows the squares
/// swimming and a corrected frame shows them in place.
#include <optional>
#include <string>

#include "io/obj.hpp"
#include "io/png.hpp"
#include "core/frame_selection.hpp"
#include "mesh/mesh.hpp"
#include "pipeline/sequence/output_options.hpp"

namespace sm {

/// Texture coordinates of a mesh's triangle corners.
struct CornerUv {
  TexCoords uv;        ///< k×2 (u, v), OBJ convention (v up the image)
  Triangles faces;     ///< m×3: the uv row of each corner of each triangle
  std::string source;  ///< "input" (the template's own) or "charts"
};

/// The texture coordinates of `obj`'s corners for the triangles of its fan triangulation (face
/// after face, (c0, ck, ck+1)), or nothing when a corner has no `vt` or the triangles differ from
/// F (m×3).
std::optional<CornerUv> input_uv(const ObjFile& obj, const Triangles& F);

/// Charts by the dominant axis of each triangle's normal on `templ`: ±x, ±y, ±z (a degenerate
/// triangle counts as +z). A triangle of chart +x is projected to (y, z), −x to (z, y), +y to
/// (z, x), −y to (x, z), +z to (x, y), −z to (y, x), so no chart is mirrored, and the bounding
/// box's minimum corner maps to (0, 0). One uv row per (vertex, chart) pair: vertices are split at
/// chart borders. UV units: 1 = `period` model units (the texture repeats beyond [0, 1]).
CornerUv chart_uv(const TriMesh& templ, double period);

/// The template's texture coordinates for `options`: input_uv of `obj` (the template frame as
/// read, if any) with CheckerUvSource::Auto when it has them, else chart_uv with a period of
/// cells × cell_size × (mean edge length of templ).
CornerUv template_uv(const TriMesh& templ, const ObjFile* obj, const CheckerOutputOptions& options);

/// The checkerboard: cells × cells squares, light (235, 235, 235) and dark (45, 50, 70), the
/// square at the image's top left light; max(8, 256 / cells) pixels per square side, RGB.
Image8 checker_texture(int cells);

}  // namespace sm
