#pragma once
/// Wavefront OBJ frames: read, then write back with new vertex positions and nothing else changed.
///
/// Statements: `v x y z [w | r g b ...]`, `vt u [v [w]]`, `vn x y z`, and `f` with corners in the
/// forms v, v/vt, v//vn or v/vt/vn (1-based, or negative = relative to the statements read so far;
/// positive indices may refer forward). Every other line (mtllib, usemtl, o, g, s, l, p, comments,
/// blank lines, unknown statements) is kept verbatim. LF or CRLF line breaks, a UTF-8 byte order
/// mark, '#' comments after data and `\` line continuations (not on comment lines) are accepted.
///
/// Polygons are fan-triangulated from their first corner: (c0, ck, ck+1). Fans depend on
/// connectivity only, never on positions, so every frame of a sequence triangulates the same way.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/mesh.hpp"

namespace sm {

/// k×2 texture coordinates (u, v); a `vt` without v gets v = 0, a w is kept only in the text.
using TexCoords = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;

/// One face corner: 0-based indices into the positions, texture coordinates and normals, -1 if
/// the corner has none.
struct ObjCorner {
  int v = -1;
  int vt = -1;
  int vn = -1;
};

/// A stretch of the file in its original order.
struct ObjRun {
  enum class Kind : uint8_t {
    kText,      ///< bytes [begin, end) of ObjFile::text, written unchanged
    kVertices,  ///< v statements [begin, end)
    kNormals,   ///< vn statements [begin, end)
  };
  Kind kind = Kind::kText;
  size_t begin = 0;
  size_t end = 0;
};

struct ObjFile {
  std::string name;                  ///< as given to the reader, for messages
  TriMesh mesh;                      ///< v positions; triangles of all faces, face after face
  std::vector<int> triangle_face;    ///< per triangle: the face it came from
  TexCoords texcoords;               ///< vt, in file order
  Positions normals;                 ///< vn as read, in file order
  std::vector<ObjCorner> corners;    ///< the corners of all faces, face after face
  std::vector<int> face_offsets{0};  ///< face f has corners [face_offsets[f], face_offsets[f+1])

  // What the writer needs to reproduce the file: its text, where each v and vn statement starts
  // in it, and the runs of text / v / vn statements in file order.
  std::string text;
  std::vector<size_t> vertex_offsets;
  std::vector<size_t> normal_offsets;
  std::vector<ObjRun> runs;

  int num_faces() const { return static_cast<int>(face_offsets.size()) - 1; }
  bool has_normals() const { return normals.rows() > 0; }
  bool has_texcoords() const { return texcoords.rows() > 0; }
};

/// Parses OBJ text; `name` prefixes messages. Throws InputError "name:line: statement: problem"
/// for a non-numeric or non-finite number, a missing coordinate, an index that is 0, not an
/// integer or out of range, a malformed corner, corners of different forms within one face or a
/// face with fewer than 3 corners, and "name: ..." for a file without vertices or faces. Linear
/// in the size of the text. Degenerate faces are accepted.
ObjFile parse_obj(std::string_view text, const std::string& name);

/// Reads and parses a file (IoError if it cannot be read; messages name the path).
ObjFile read_obj(const std::filesystem::path& path);

/// The text of `file` with vertex positions `V` (one row per v statement). Lines whose position
/// is bit-identical to the one read are copied unchanged; others are written "v x y z" with the
/// shortest text that reads back as exactly the same doubles, followed by the statement's extra
/// values (w or colours) and comment as read. If any position differs and the file has vn
/// statements, every vn a face refers to is recomputed: the area-weighted sum of the normals of
/// the triangles whose corners use it, normalized. When each position uses one vn this equals
/// sm::vertex_normals mapped through the corners; a vn shared by several positions (flat shading,
/// deduplicated normals) gets the area-weighted normal of all the triangles that use it, so hard
/// edges stay hard. A vn no face refers to, whose triangles all have zero area, or whose sum
/// overflows (coordinates near 1e150 and beyond), is kept as it was. Line breaks are kept as read. Byte-deterministic. Throws InputError if `V` has the wrong
/// number of rows or a non-finite coordinate.
std::string format_obj(const ObjFile& file, const Positions& V);

/// format_obj written atomically to `path`.
void write_obj(const std::filesystem::path& path, const ObjFile& file, const Positions& V);

/// A plain OBJ of `mesh`: "v x y z" lines (shortest exact text), then "f a b c" lines (1-based).
std::string format_obj(const TriMesh& mesh);

/// format_obj(mesh) written atomically to `path`.
void write_obj(const std::filesystem::path& path, const TriMesh& mesh);

}  // namespace sm
