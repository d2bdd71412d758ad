#include "io/mesh_file.hpp"

#include <string>

#include "io/obj.hpp"
#include "io/off.hpp"
#include "io/ply.hpp"
#include "core/errors.hpp"

namespace sm {
namespace {

enum class MeshFormat { kObj, kOff, kPly };

MeshFormat format_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  if (ext == ".obj") return MeshFormat::kObj;
  if (ext == ".off") return MeshFormat::kOff;
  if (ext == ".ply") return MeshFormat::kPly;
  throw InputError("'" + path.string() + "': unknown mesh file extension '" +
                   path.extension().string() + "' (expected .obj, .off or .ply)");
}

}  // namespace

TriMesh read_mesh(const std::filesystem::path& path) {
  switch (format_of(path)) {
    case MeshFormat::kObj:
      return read_obj(path).mesh;
    case MeshFormat::kOff:
      return read_off(path);
    case MeshFormat::kPly:
      return read_ply(path);
  }
  return {};
}

void write_mesh(const std::filesystem::path& path, const TriMesh& mesh) {
  switch (format_of(path)) {
    case MeshFormat::kObj:
      write_obj(path, mesh);
      break;
    case MeshFormat::kOff:
      write_off(path, mesh);
      break;
    case MeshFormat::kPly:
      write_ply(path, mesh, nullptr, /*binary=*/true);
      break;
  }
}

}  // namespace sm
