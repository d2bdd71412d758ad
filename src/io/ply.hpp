#pragma once
/// PLY mesh files, ASCII and binary little-endian: read polygons (fan-triangulated), write
/// triangles with optional per-vertex and per-face RGB colours that MeshLab and Blender display.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/mesh.hpp"

namespace sm {

/// 8-bit RGB colours (PLY properties `uchar red, green, blue`). Each list is empty or has one
/// entry per vertex, respectively per triangle.
struct PlyColors {
  std::vector<std::array<uint8_t, 3>> vertex;
  std::vector<std::array<uint8_t, 3>> face;
};

/// One scalar vertex property read besides x, y, z (e.g. per-vertex weights): `name` in, one
/// value per vertex out.
struct PlyVertexProperty {
  std::string name;
  std::vector<double> values;
};

/// Parses PLY data (format ascii or binary_little_endian 1.0); `name` prefixes messages.
/// Reads element `vertex` (properties x, y, z of any scalar type; others are skipped) and element
/// `face` (list property `vertex_indices` or `vertex_index`, any integer types); other elements
/// and properties are skipped. Polygons are fan-triangulated from their first vertex. If `colors`
/// is given it receives the red, green and blue properties of vertices and faces (per triangle;
/// float colours in [0, 1] are scaled to 0..255), or empty lists where there are none. If `extra`
/// is given, its values receive the vertex property `extra->name` (InputError if there is none).
/// Throws InputError naming the header line, or the element, item and property ("name:line: ..."
/// for ASCII data): unsupported format, malformed header, missing x/y/z or face indices,
/// non-numeric or non-finite values, an index out of range, a face with fewer than 3 corners, data
/// ending early, no vertices or no faces.
TriMesh parse_ply(std::string_view data, const std::string& name, PlyColors* colors = nullptr,
                  PlyVertexProperty* extra = nullptr);

/// Reads and parses a file (IoError if it cannot be read; messages name the path).
TriMesh read_ply(const std::filesystem::path& path, PlyColors* colors = nullptr);

/// PLY of `mesh`: vertex x, y, z as double (shortest exact text in ASCII), faces as
/// `list uchar int vertex_indices` triangles, then red, green, blue uchar for the non-empty colour
/// lists of `colors`. Byte-deterministic. Throws InputError for an invalid mesh or colour lists
/// of the wrong length.
std::string format_ply(const TriMesh& mesh, const PlyColors* colors = nullptr, bool binary = false);

/// format_ply written atomically to `path`.
void write_ply(const std::filesystem::path& path, const TriMesh& mesh,
               const PlyColors* colors = nullptr, bool binary = false);

}  // namespace sm
