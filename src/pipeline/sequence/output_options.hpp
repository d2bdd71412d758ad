#pragma once
/// The options of the per-frame image outputs, "output.checker" (outputs/checker) and
/// "output.colored" (outputs/shear_ply), with their tables: here, below the outputs, because
/// the job's options (sequence_options) hold them.
#include "core/frame_selection.hpp"
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

/// How shear colours are attached to the PLY.
enum class ShearColorMode {
  /// "faces": every triangle gets three vertices of its own carrying its colour, and the same
  /// colour as a face property: flat colours in every viewer (Blender reads vertex colours only).
  Faces,
  /// "vertices": the mesh's own vertices (connectivity kept), each coloured by the mean of its
  /// triangles' values on the scale; face colours as well (MeshLab shows either).
  Vertices,
};
inline constexpr EnumName<ShearColorMode> kShearColorModeNames[] = {
    {"faces", ShearColorMode::Faces}, {"vertices", ShearColorMode::Vertices}};

/// "output.colored": colored/before/<frame>.ply and colored/after/<frame>.ply, binary PLY whose
/// colours map the shear distortion (eq. 8) of each triangle against the template to a blue-red
/// scale (see shear_color).
struct ColoredOutputOptions {
  bool enabled = false;
  FrameSelection frames;
  double max = 0.1;  ///< the shear shown red
  ShearColorMode colors = ShearColorMode::Faces;
};

template <>
inline const Fields<ColoredOutputOptions>& fields_of<ColoredOutputOptions>() {
  using O = ColoredOutputOptions;
  static const Fields<O> fields = {
      field<&O::frames>("frames", any_value(),
                        "frames written, by index in the full list of frames; listed frames the "
                        "run does not process get a warning"),
      field<&O::max>("max", left_open(0, 1e6),
                     "the shear shown red, the same for every frame, before and after"),
      field<&O::colors>("colors", choice(kShearColorModeNames),
                        "`\"faces\"`: three vertices of its own per triangle and a face colour "
                        "(flat in every viewer); `\"vertices\"`: the mesh's own vertices, each "
                        "with the mean colour of its triangles"),
  };
  return fields;
}

}  // namespace sm
