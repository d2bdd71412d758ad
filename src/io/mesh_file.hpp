#pragma once
/// Mesh files of any supported format (OBJ, OFF, PLY), chosen by the file name's extension.
#include <filesystem>

#include "mesh/mesh.hpp"

namespace sm {

/// Reads the triangle mesh of an .obj, .off or .ply file (extension case-insensitive); polygons are
/// fan-triangulated. Throws InputError for another extension or malformed content, IoError if the
/// file cannot be read.
TriMesh read_mesh(const std::filesystem::path& path);

/// Writes `mesh` atomically as a plain OBJ (v and f lines), an OFF, or a binary little-endian PLY,
/// by the extension of `path` (case-insensitive). Throws InputError for another extension or an
/// invalid mesh, IoError if the file cannot be written.
void write_mesh(const std::filesystem::path& path, const TriMesh& mesh);

}  // namespace sm
