#pragma once
/// The synthetic drifted sequences of the demo, the tests and the correspondence benchmark: a tube
/// bending over time (its triangles stretch and shrink) or a flat sheet rolled onto a cylinder
/// (isometric: no triangle changes shape), whose vertices slide tangentially by a smooth
/// time-varying field, generated deterministically, with the clean (undrifted) frames as ground
/// truth.
#include <filesystem>
#include <string>

#include "io/obj.hpp"
#include "mesh/mesh.hpp"
#include "core/options_table.hpp"

namespace sm {

enum class SyntheticShape {
  BendingTube,  ///< "bending_tube": stretches on the inside and outside of the bend
  RolledSheet,  ///< "rolled_sheet": isometric, every triangle keeps its shape
};
inline constexpr EnumName<SyntheticShape> kSyntheticShapeNames[] = {
    {"bending_tube", SyntheticShape::BendingTube}, {"rolled_sheet", SyntheticShape::RolledSheet}};

/// "input.synthetic": the generated drifted sequence (frame 0 straight and undrifted).
struct SyntheticOptions {
  SyntheticShape shape = SyntheticShape::BendingTube;
  int frames = 24;
  int segments = 32;  ///< vertices around the tube
  int rings = 48;     ///< segments along the tube
  double radius = 0.5;
  double length = 4.0;
  double bend = 90.0;  ///< bend angle of the last frame, degrees
  double drift = 0.6;  ///< slide amplitude, in edge lengths
  int seed = 1;        ///< seed of the drift field
  int drift_waves = 6;          ///< number of waves in the drift field
  double drift_cycles = 4.0;    ///< most cycles of a wave along the shape (the least is 1.5)
};

template <>
inline const Fields<SyntheticOptions>& fields_of<SyntheticOptions>() {
  using O = SyntheticOptions;
  static const Fields<O> fields = {
      field<&O::shape>("shape", choice(kSyntheticShapeNames),
                       "the generated shape: `\"bending_tube\"` (a tube bending, its triangles "
                       "stretch) or `\"rolled_sheet\"` (a flat sheet of width 2π·radius rolled "
                       "onto a cylinder: isometric, no triangle changes shape)"),
      field<&O::frames>("frames", closed(2, 100000), "number of frames"),
      field<&O::segments>("segments", closed(3, 100000),
                          "vertices around the tube (across the sheet)"),
      field<&O::rings>("rings", closed(1, 100000), "segments along the tube (the sheet)"),
      field<&O::radius>("radius", above(0),
                        "tube radius (the sheet's width is 2π times it, so a roll of 360° closes "
                        "it)"),
      field<&O::length>("length", above(0),
                        "tube length; the bend (in radians) times the radius must stay below it, "
                        "or the tube would fold onto itself"),
      field<&O::bend>("bend", closed(0, 300),
                      "bend angle of the last frame, degrees (for the sheet: the angle its width "
                      "wraps around the cylinder)"),
      field<&O::drift>("drift", closed(0, 2), "slide amplitude, in edge lengths"),
      field<&O::seed>("seed", at_least(0), "seed of the drift field"),
      field<&O::drift_waves>("drift_waves", closed(1, 64),
                             "waves in the drift field, each with its own frequencies, "
                             "direction, phase and speed"),
      field<&O::drift_cycles>("drift_cycles", closed(1.5, 64),
                              "the most cycles of a drift wave along the shape (each wave draws "
                              "its own between 1.5 and this; across, 2 to 4)"),
  };
  return fields;
}

/// Throws ConfigError (naming the key, "input.synthetic.bend: ...") for a value outside its
/// table's range or a tube that would fold onto itself (bend · radius >= length; not checked for
/// the sheet, whose roll never closes below 360°).
void check_synthetic_options(const SyntheticOptions& options);

/// What every frame shares: the tube's triangles (mesh/primitives make_cylinder layout: vertex
/// j·segments + i sits at angle 2πi/segments on ring j) and its texture coordinates, (segments+1)
/// × (rings+1) of them so that the seam gets its own column (u = 1); for the sheet, make_grid's
/// layout with segments vertices across and one texture coordinate per vertex.
struct SyntheticSequence {
  SyntheticOptions config;
  Triangles F;
  TexCoords uv;
  Triangles F_uv;  ///< per triangle corner, the row of `uv`
  TriMesh rest;    ///< the straight tube (frame 0)
};

/// The two versions of frame t: `clean` has every vertex where its (angle, length) parameters put
/// it on the bent tube (its (across, along) parameters on the rolled sheet); `drifted` moves the
/// parameters by the drift field (drift_waves smooth waves, vanishing at both ends of the tube
/// and on the sheet's boundary, amplitude growing from 0 at frame 0 to config.drift edge lengths
/// at the last frame, phases moving with time), so its vertices stay exactly on the smooth
/// surface but slide along it. The bend angle grows smoothly from 0 to config.bend.
struct SyntheticFrame {
  Positions clean;
  Positions drifted;
};

/// The shared connectivity. Throws ConfigError for invalid options (check_synthetic_options).
SyntheticSequence make_synthetic_sequence(const SyntheticOptions& config);

/// Frame t in [0, config.frames). Same config and t, same bytes.
SyntheticFrame synthetic_frame(const SyntheticSequence& sequence, int t);

/// "frame_0007.obj": the file name of frame t, zero-padded to at least 4 digits.
std::string synthetic_frame_name(const SyntheticSequence& sequence, int t);

/// OBJ text of a frame: a comment, "g tube" (or "g sheet"), v, vt and "f v/vt" statements; numbers in their
/// shortest exact form.
std::string format_synthetic_obj(const SyntheticSequence& sequence, const Positions& V,
                                 const std::string& comment);

/// Writes every frame: drifted ones to `drifted_dir`, clean ones to `clean_dir` (atomically, with
/// the same file names). Returns the number of frames written.
int write_synthetic_sequence(const SyntheticSequence& sequence,
                             const std::filesystem::path& drifted_dir,
                             const std::filesystem::path& clean_dir);

}  // namespace sm
