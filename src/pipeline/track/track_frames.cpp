#include "pipeline/track/track_frames.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

#include "io/frame_folder.hpp"
#include "io/off.hpp"
#include "io/ply.hpp"
#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr const char* kFrameExtensions[] = {".obj", ".ply", ".off"};

std::string frame_extension_lower(const fs::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// The file's bytes; IoError naming `who` and the file when it cannot be read.
std::string read_bytes(const fs::path& file, const std::string& who) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw IoError(who + ": cannot read '" + file.string() + "': " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw IoError(who + ": error reading '" + file.string() + "'");
  return text.str();
}

TriMesh parse_mesh(const std::string& bytes, const fs::path& file, const std::string& name) {
  const std::string ext = frame_extension_lower(file);
  if (ext == ".obj") return parse_obj(bytes, name).mesh;
  if (ext == ".ply") return parse_ply(bytes, name);
  if (ext == ".off") return parse_off(bytes, name);
  throw InputError(name + ": not a mesh file (.obj, .ply or .off)");
}

}  // namespace

std::vector<fs::path> list_raw_frames(const fs::path& dir) {
  std::error_code ec;
  const fs::file_status status = fs::status(dir, ec);
  if (!fs::exists(status))
    throw IoError("input.frames: the folder '" + dir.string() + "' does not exist");
  if (!fs::is_directory(status))
    throw InputError("input.frames: '" + dir.string() + "' is not a folder");
  std::vector<bool> present(std::size(kFrameExtensions), false);
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    const std::string ext = frame_extension_lower(it->path());
    for (size_t k = 0; k < std::size(kFrameExtensions); ++k)
      present[k] = present[k] || ext == kFrameExtensions[k];
  }
  if (ec) throw IoError("input.frames: cannot list '" + dir.string() + "': " + ec.message());
  std::vector<fs::path> files;
  for (size_t k = 0; k < std::size(kFrameExtensions); ++k) {
    if (!present[k]) continue;
    std::vector<fs::path> some = list_frames(dir, kFrameExtensions[k]);  // checks the entries
    files.insert(files.end(), some.begin(), some.end());
  }
  if (files.empty())
    throw InputError("input.frames: the folder '" + dir.string() +
                     "' holds no frame (no .obj, .ply or .off file)");
  std::stable_sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return natural_less(a.filename().string(), b.filename().string());
  });
  return files;
}

TriMesh read_raw_frame(const fs::path& file, int index) {
  const std::string who = "frame " + std::to_string(index) + " ('" + file.string() + "')";
  TriMesh mesh = parse_mesh(read_bytes(file, "frame " + std::to_string(index)), file, who);
  validate_mesh(mesh, who.c_str());
  if (mesh.num_triangles() == 0) throw InputError(who + ": no triangles");
  return mesh;
}

TemplateLayout read_template_layout(const fs::path& file, const std::string& who) {
  TemplateLayout layout;
  const std::string bytes = read_bytes(file, who);
  const std::string name = who + " ('" + file.string() + "')";
  if (frame_extension_lower(file) == ".obj") {
    layout.obj = std::make_shared<const ObjFile>(parse_obj(bytes, name));
    layout.bytes = bytes;
  } else {
    const TriMesh mesh = parse_mesh(bytes, file, name);
    validate_mesh(mesh, name.c_str());
    layout.obj = std::make_shared<const ObjFile>(parse_obj(format_obj(mesh), name));
  }
  validate_mesh(layout.obj->mesh, name.c_str());
  if (layout.obj->mesh.num_triangles() == 0) throw InputError(name + ": no triangles");
  return layout;
}

TrackLayoutSource::TrackLayoutSource(fs::path dir, std::vector<fs::path> files,
                                     TemplateLayout layout)
    : dir_(std::move(dir)), files_(std::move(files)), layout_(std::move(layout)) {}

int TrackLayoutSource::size() const { return int(files_.size()); }

std::string TrackLayoutSource::name(int i) const {
  // Output files are OBJ frames: a raw frame.ply writes frames/frame.obj.
  return fs::path(files_[size_t(i)].filename()).replace_extension(".obj").string();
}

std::string TrackLayoutSource::describe() const {
  return std::to_string(size()) + " raw frames (.obj, .ply, .off) in " + dir_.string();
}

json TrackLayoutSource::report() const {
  return {{"kind", "raw_frames"}, {"folder", dir_.string()}, {"frames", size()}};
}

std::vector<fs::path> TrackLayoutSource::files(const std::vector<int>& frames) const {
  std::vector<fs::path> out;
  for (int i : frames) out.push_back(files_[size_t(i)]);
  return out;
}

TriMesh TrackLayoutSource::template_frame(int) const { return layout_.obj->mesh; }

SourceFrame TrackLayoutSource::decode(int, std::string) const {
  SourceFrame frame;
  frame.mesh = layout_.obj->mesh;
  frame.obj = layout_.obj;
  frame.bytes = layout_.bytes;
  return frame;
}

}  // namespace sm
