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
#include "core/options_table.hpp"

namespace sm {

/// Where the checker's texture coordinates come from.
enum class CheckerUvSource {
  /// "auto": the template frame's own texture coordinates when every corner of it has one (OBJ
  /// `vt`, glTF TEXCOORD_0), else "charts".
  Auto,
  /// "charts": the template's triangles grouped by the dominant axis of their normal (±x, ±y,
  /// ±z), each group projected onto the plane of the other two axes.
  Charts,
};
inline constexpr EnumName<CheckerUvSource> kCheckerUvSourceNames[] = {
    {"auto", CheckerUvSource::Auto}, {"charts", CheckerUvSource::Charts}};

/// "output.checker": checker/before/<frame>.obj (the input frame) and checker/after/<frame>.obj
/// (the corrected frame), each folder with checker.mtl and checker.png; texture coordinates from
/// the template, identical for every frame, so a texture that swims on the input stays put.
struct CheckerOutputOptions {
  bool enabled = false;
  FrameSelection frames;
  CheckerUvSource uv = CheckerUvSource::Auto;
  int cells = 8;           ///< squares per side of the texture
  double cell_size = 4.0;  ///< with charts, a square's side in mean edge lengths of the template
};

template <>
inline const Fields<CheckerOutputOptions>& fields_of<CheckerOutputOptions>() {
  using O = CheckerOutputOptions;
  static const Fields<O> fields = {
      field<&O::frames>("frames", any_value(), "frames written"),
      field<&O::uv>("uv", choice(kCheckerUvSourceNames),
                    "`\"auto\"`: the template's own texture coordinates when every corner has "
                    "one, else charts; `\"charts\"`: always axis-aligned projection charts"),
      field<&O::cells>("cells", closed(1, 64), "squares per side of the texture"),
      field<&O::cell_size>("cell_size", left_open(0, 1e6),
                           "with charts: a square's side, in mean edge lengths of the template"),
  };
  return fields;
}

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
