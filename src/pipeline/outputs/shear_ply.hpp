#pragma once
/// Shear distortion (eq. 8) shown as colours on a mesh, the paper's Figure 4: a PLY per frame
/// whose triangles run from blue (undistorted) to red (distorted at or beyond a fixed maximum),
/// for MeshLab and Blender.
#include <array>
#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "core/frame_selection.hpp"
#include "mesh/mesh.hpp"
#include "pipeline/sequence/output_options.hpp"

namespace sm {

/// The colour of t in [0, 1] on the blue-red scale: blue (0, 0, 255) at 0, cyan (0, 255, 255)
/// at 0.25, green (0, 255, 0) at 0.5, yellow (255, 255, 0) at 0.75 and red (255, 0, 0) at 1,
/// linear in between; each channel is round(255 · value). t outside [0, 1] is clamped, NaN is 1.
std::array<uint8_t, 3> scale_color(double t);

/// Where a shear value falls on the scale: clamp(shear / max, 0, 1), and 1 for a non-finite
/// value (a degenerate triangle). `max` > 0.
double shear_scale_position(double shear, double max);

/// scale_color(shear_scale_position(shear, max)).
std::array<uint8_t, 3> shear_color(double shear, double max);

/// A binary little-endian PLY (see format_ply) of the triangles F (m×3) on positions V (n×3),
/// coloured by `shear` (m values) with `max` as red:
///  - ShearColorMode::Faces: 3m vertices, triangle t's corners being vertices 3t, 3t+1, 3t+2, all
///    three with the triangle's colour, which is also the face's colour;
///  - ShearColorMode::Vertices: the n vertices of V, each with the colour of the mean scale
///    position of the triangles around it (blue for a vertex in no triangle), faces with their
///    own colours.
/// Throws InputError for sizes that disagree.
std::string format_shear_ply(const Positions& V, const Triangles& F, const Eigen::VectorXd& shear,
                             double max, ShearColorMode mode);

}  // namespace sm
