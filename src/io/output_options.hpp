#pragma once
/// The sequence job's optional visual outputs, keys of the config's "output" object: shear
/// distortion as coloured PLY meshes ("colored"), the frames with a checkerboard texture
/// ("checker"), and the optimizer's figures after every iteration ("iterations"). Each key takes
/// `true` (every default), `false` (off, the default) or an object of the keys below.
#include <algorithm>
#include <optional>
#include <vector>

namespace sm {

/// Frames chosen for an optional output, by their index in the full list of input frames (like
/// template.frame): "all", an array of indices, or a range "A:B[:STEP]" (B may be empty: to the
/// end). Only frames the run processes are written.
struct FrameSelection {
  enum class Kind { All, List, Range };
  Kind kind = Kind::All;
  std::vector<int> list;    ///< Kind::List: sorted, without repeats (may be empty: no frame)
  int start = 0;            ///< Kind::Range: first frame
  std::optional<int> stop;  ///< Kind::Range: one past the last frame; empty = to the end
  int step = 1;             ///< Kind::Range: >= 1

  static FrameSelection none() { return {Kind::List, {}, 0, std::nullopt, 1}; }
  bool contains(int frame) const;
};

/// How shear colours are attached to the PLY.
enum class ShearColorMode {
  /// "faces": every triangle gets three vertices of its own carrying its colour, and the same
  /// colour as a face property: flat colours in every viewer (Blender reads vertex colours only).
  Faces,
  /// "vertices": the mesh's own vertices (connectivity kept), each coloured by the mean of its
  /// triangles' values on the scale; face colours as well (MeshLab shows either).
  Vertices,
};

/// "output.colored": colored/before/<frame>.ply and colored/after/<frame>.ply, binary PLY whose
/// colours map the shear distortion (eq. 8) of each triangle against the template to a blue-red
/// scale (see shear_color).
struct ColoredOutputOptions {
  bool enabled = false;
  FrameSelection frames;                          ///< "frames": default "all"
  double max = 0.1;                               ///< "max": the shear shown red, > 0
  ShearColorMode colors = ShearColorMode::Faces;  ///< "colors": "faces" | "vertices"
};

/// Where the checker's texture coordinates come from.
enum class CheckerUvSource {
  /// "auto": the template frame's own texture coordinates when every corner of it has one (OBJ
  /// `vt`, glTF TEXCOORD_0), else "charts".
  Auto,
  /// "charts": the template's triangles grouped by the dominant axis of their normal (±x, ±y,
  /// ±z), each group projected onto the plane of the other two axes.
  Charts,
};

/// "output.checker": checker/before/<frame>.obj (the input frame) and checker/after/<frame>.obj
/// (the corrected frame), each folder with checker.mtl and checker.png; texture coordinates from
/// the template, identical for every frame, so a texture that swims on the input stays put.
struct CheckerOutputOptions {
  bool enabled = false;
  FrameSelection frames;                       ///< "frames": default "all"
  CheckerUvSource uv = CheckerUvSource::Auto;  ///< "uv": "auto" | "charts"
  int cells = 8;  ///< "cells": squares per side of the texture, [1, 64]
  /// "cell_size": with charts, a square's side in mean edge lengths of the template, > 0.
  double cell_size = 4.0;
};

/// "output.iterations": iterations.csv, one row per logged frame and iteration (0 = the input).
struct IterationLogOptions {
  bool enabled = false;
  FrameSelection frames;  ///< "frames": frames logged, default "all"
  /// "shear_frames": frames whose shear is measured after every iteration (logged even when not
  /// among "frames"), during the frame's run (one shear measure per iteration); the other
  /// logged frames get shear at iteration 0 and at the last iteration only.
  FrameSelection shear_frames = FrameSelection::none();
};

inline bool FrameSelection::contains(int frame) const {
  switch (kind) {
    case Kind::All:
      return true;
    case Kind::List:
      return std::binary_search(list.begin(), list.end(), frame);
    case Kind::Range:
      return frame >= start && (!stop || frame < *stop) && (frame - start) % step == 0;
  }
  return false;
}

}  // namespace sm
