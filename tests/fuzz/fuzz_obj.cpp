// Fuzz target: the OBJ reader and writer (io/obj.hpp).
#include <cmath>
#include <string>
#include <string_view>

#include "fuzz_targets.hpp"
#include "io/obj.hpp"
#include "core/errors.hpp"

namespace sm::fuzz {
namespace {

// What parse_obj promises of a file it accepts.
void check_file(const ObjFile& f) {
  const int n = f.mesh.num_vertices();
  expect(n > 0 && f.num_faces() > 0, "accepted a file without vertices or faces");
  expect(f.mesh.V.allFinite(), "accepted a non-finite coordinate");
  expect(f.texcoords.allFinite() && f.normals.allFinite(), "accepted a non-finite vt or vn");
  expect(static_cast<size_t>(n) == f.vertex_offsets.size(), "v statements and positions differ");
  expect(static_cast<size_t>(f.normals.rows()) == f.normal_offsets.size(),
         "vn statements and normals differ");
  expect(f.triangle_face.size() == static_cast<size_t>(f.mesh.num_triangles()),
         "triangle_face has the wrong size");
  expect(f.face_offsets.back() == static_cast<int>(f.corners.size()), "face_offsets end early");
  for (int face = 0; face < f.num_faces(); ++face)
    expect(f.face_offsets[face + 1] - f.face_offsets[face] >= 3, "a face with < 3 corners");
  for (const ObjCorner& c : f.corners) {
    expect(c.v >= 0 && c.v < n, "corner vertex index out of range");
    expect(c.vt >= -1 && c.vt < f.texcoords.rows(), "corner vt index out of range");
    expect(c.vn >= -1 && c.vn < f.normals.rows(), "corner vn index out of range");
  }
  for (int t = 0; t < f.mesh.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k)
      expect(f.mesh.F(t, k) >= 0 && f.mesh.F(t, k) < n, "triangle index out of range");
}

}  // namespace

void fuzz_obj(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  ObjFile file;
  try {
    file = parse_obj(text, "fuzz.obj");
  } catch (const InputError&) {
    return;  // rejected with a message: the documented outcome
  }
  check_file(file);

  // Unchanged positions: the writer reproduces the file byte for byte.
  expect(format_obj(file, file.mesh.V) == text, "format_obj with unchanged positions differs");

  // Moved positions: written with the shortest exact text, read back bit for bit, same faces.
  Positions moved = file.mesh.V;
  for (Eigen::Index i = 0; i < moved.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double x = moved(i, c) * 0.75 + 0.5;
      moved(i, c) = std::isfinite(x) ? x : moved(i, c);
    }
  const std::string written = format_obj(file, moved);
  ObjFile again;
  try {
    again = parse_obj(written, "fuzz-written.obj");
  } catch (const InputError& e) {
    throw FuzzFinding(std::string("the written OBJ does not read back: ") + e.what());
  }
  check_file(again);
  expect(again.mesh.V == moved, "moved positions do not read back exactly");
  expect(again.mesh.F == file.mesh.F, "faces change when positions are written");
  expect(again.corners.size() == file.corners.size(), "corners change when positions are written");
  expect(again.texcoords.rows() == file.texcoords.rows() &&
             again.normals.rows() == file.normals.rows(),
         "vt or vn count changes when positions are written");
}

}  // namespace sm::fuzz
