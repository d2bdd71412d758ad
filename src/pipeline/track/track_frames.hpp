#pragma once
/// The track job's frames: the raw frames of a folder (OBJ, PLY, OFF, each with its own
/// connectivity), read one at a time, and the template's layout, which every output frame keeps
/// (an OBJ template's texture coordinates, normals, groups and materials).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "io/obj.hpp"
#include "mesh/mesh.hpp"
#include "pipeline/sequence/frame_source.hpp"

namespace sm {

/// The `.obj`, `.ply` and `.off` files of `dir` (extension case-insensitive, hidden files
/// skipped) in natural order. Throws IoError when the folder is missing or cannot be listed,
/// InputError when it is not a folder, holds no frame, or holds an entry with a frame's
/// extension that is not a regular file.
std::vector<std::filesystem::path> list_raw_frames(const std::filesystem::path& dir);

/// Raw frame `index` read from `file` (polygons fanned). Throws IoError when it cannot be read,
/// InputError for malformed content, a non-finite coordinate or no triangle; every message names
/// the frame's index and file.
TriMesh read_raw_frame(const std::filesystem::path& file, int index);

/// The template as the outputs write it: its OBJ statements (an OBJ's own; a PLY or OFF as a
/// plain OBJ of its vertices and triangles) and, for a template frame, the file's bytes.
struct TemplateLayout {
  std::shared_ptr<const ObjFile> obj;
  std::string bytes;  ///< the OBJ file as read, else empty
};

/// Reads the template from `file`, named `who` in messages.
TemplateLayout read_template_layout(const std::filesystem::path& file, const std::string& who);

/// The frames as the per-frame outputs see them: the raw frames' names (output files are named
/// after them), and for every frame the template's layout with its own positions (the outputs
/// read the template's texture coordinates and rest.obj from it). The tracked positions reach
/// the outputs through FrameOutcome, not through decode.
class TrackLayoutSource : public FrameSource {
 public:
  TrackLayoutSource(std::filesystem::path dir, std::vector<std::filesystem::path> files,
                    TemplateLayout layout);

  int size() const override;
  std::string name(int i) const override;
  std::string describe() const override;
  nlohmann::json report() const override;
  std::vector<std::filesystem::path> files(const std::vector<int>& frames) const override;
  bool needs_check() const override { return false; }
  TriMesh template_frame(int i) const override;
  SourceFrame decode(int i, std::string bytes) const override;

 private:
  std::filesystem::path dir_;
  std::vector<std::filesystem::path> files_;
  TemplateLayout layout_;
};

}  // namespace sm
