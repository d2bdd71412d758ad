#pragma once
/// The synthetic drifted sequence of the demo and the tests: a tube bending over time whose
/// vertices slide tangentially by a smooth time-varying field, generated deterministically, with
/// the clean (undrifted) frames as ground truth.
#include <filesystem>
#include <string>

#include "io/config.hpp"
#include "io/obj.hpp"
#include "mesh/mesh.hpp"

namespace sm {

/// What every frame shares: the tube's triangles (mesh/primitives make_cylinder layout: vertex
/// j·segments + i sits at angle 2πi/segments on ring j) and its texture coordinates, (segments+1)
/// × (rings+1) of them so that the seam gets its own column (u = 1).
struct SyntheticSequence {
  SyntheticConfig config;
  Triangles F;
  TexCoords uv;
  Triangles F_uv;  ///< per triangle corner, the row of `uv`
  TriMesh rest;    ///< the straight tube (frame 0)
};

/// The two versions of frame t: `clean` has every vertex where its (angle, length) parameters put
/// it on the bent tube; `drifted` moves the parameters by the drift field (a few smooth waves,
/// vanishing at both ends of the tube, amplitude growing from 0 at frame 0 to config.drift edge
/// lengths at the last frame, phases moving with time), so its vertices stay exactly on the
/// smooth tube surface but slide along it. The bend angle grows smoothly from 0 to config.bend.
struct SyntheticFrame {
  Positions clean;
  Positions drifted;
};

/// The shared connectivity. Throws ConfigError for an invalid config (see parse_config).
SyntheticSequence make_synthetic_sequence(const SyntheticConfig& config);

/// Frame t in [0, config.frames). Same config and t, same bytes.
SyntheticFrame synthetic_frame(const SyntheticSequence& sequence, int t);

/// "frame_0007.obj": the file name of frame t, zero-padded to at least 4 digits.
std::string synthetic_frame_name(const SyntheticSequence& sequence, int t);

/// OBJ text of a frame: a comment, "g tube", v, vt and "f v/vt" statements; numbers in their
/// shortest exact form.
std::string format_synthetic_obj(const SyntheticSequence& sequence, const Positions& V,
                                 const std::string& comment);

/// Writes every frame: drifted ones to `drifted_dir`, clean ones to `clean_dir` (atomically, with
/// the same file names). Returns the number of frames written.
int write_synthetic_sequence(const SyntheticSequence& sequence,
                             const std::filesystem::path& drifted_dir,
                             const std::filesystem::path& clean_dir);

}  // namespace sm
