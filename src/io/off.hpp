#pragma once
/// OFF mesh files (Geomview Object File Format, ASCII): read with polygons fan-triangulated, write.
#include <filesystem>
#include <string>
#include <string_view>

#include "mesh/mesh.hpp"

namespace sm {

/// Parses OFF text; `name` prefixes messages. The header keyword may carry the ST, C and N
/// prefixes (COFF, NOFF, ...): texture coordinates, colours and normals after x y z are ignored,
/// like anything after a face's vertex indices. '#' comments and blank lines are skipped; the
/// counts may follow the keyword on its line. Polygons are fan-triangulated from their first
/// vertex. Throws InputError "name:line: ..." naming the vertex or face and the field, and
/// "name: ..." for a missing header, binary or 4-dimensional OFF, or a file ending early.
TriMesh parse_off(std::string_view text, const std::string& name);

/// Reads and parses a file (IoError if it cannot be read; messages name the path).
TriMesh read_off(const std::filesystem::path& path);

/// "OFF", the counts "n m 0", one "x y z" line per vertex (shortest text that reads back as
/// exactly the same doubles), one "3 a b c" line per triangle. Throws InputError for a mesh with
/// an out-of-range index or a non-finite coordinate.
std::string format_off(const TriMesh& mesh);

/// format_off written atomically to `path`.
void write_off(const std::filesystem::path& path, const TriMesh& mesh);

}  // namespace sm
