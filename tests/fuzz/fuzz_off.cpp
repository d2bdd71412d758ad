// Fuzz target: the OFF reader and writer (io/off.hpp).
#include <string>
#include <string_view>

#include "fuzz_targets.hpp"
#include "io/off.hpp"
#include "core/errors.hpp"

namespace sm::fuzz {

void fuzz_off(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  TriMesh mesh;
  try {
    mesh = parse_off(text, "fuzz.off");
  } catch (const InputError&) {
    return;
  }
  expect(mesh.num_vertices() > 0 && mesh.num_triangles() > 0, "accepted an empty mesh");
  try {
    validate_mesh(mesh, "fuzz.off");
  } catch (const InputError& e) {
    throw FuzzFinding(std::string("accepted an invalid mesh: ") + e.what());
  }
  TriMesh again;
  try {
    again = parse_off(format_off(mesh), "fuzz-written.off");
  } catch (const InputError& e) {
    throw FuzzFinding(std::string("the written OFF does not read back: ") + e.what());
  }
  expect(again.V == mesh.V && again.F == mesh.F, "the written OFF reads back differently");
}

}  // namespace sm::fuzz
