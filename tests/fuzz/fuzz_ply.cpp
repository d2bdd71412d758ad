// Fuzz target: the PLY reader and writer (io/ply.hpp).
#include <string>
#include <string_view>

#include "fuzz_targets.hpp"
#include "io/ply.hpp"
#include "core/errors.hpp"

namespace sm::fuzz {

void fuzz_ply(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  TriMesh mesh;
  PlyColors colors;
  try {
    mesh = parse_ply(bytes, "fuzz.ply", &colors);
  } catch (const InputError&) {
    return;
  }
  expect(mesh.num_vertices() > 0 && mesh.num_triangles() > 0, "accepted an empty mesh");
  try {
    validate_mesh(mesh, "fuzz.ply");
  } catch (const InputError& e) {
    throw FuzzFinding(std::string("accepted an invalid mesh: ") + e.what());
  }
  expect(colors.vertex.empty() || colors.vertex.size() == size_t(mesh.num_vertices()),
         "vertex colours and vertices differ in number");
  expect(colors.face.empty() || colors.face.size() == size_t(mesh.num_triangles()),
         "face colours and triangles differ in number");
  for (const bool binary : {false, true}) {
    TriMesh again;
    PlyColors colors_again;
    try {
      again = parse_ply(format_ply(mesh, &colors, binary), "fuzz-written.ply", &colors_again);
    } catch (const InputError& e) {
      throw FuzzFinding(std::string("the written PLY does not read back: ") + e.what());
    }
    expect(again.V == mesh.V && again.F == mesh.F, "the written PLY reads back differently");
    expect(colors_again.vertex == colors.vertex && colors_again.face == colors.face,
           "the written PLY's colours read back differently");
  }
}

}  // namespace sm::fuzz
