#include "pipeline/sequence/point_cache_source.hpp"

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "io/atomic_file.hpp"
#include "io/mesh_file.hpp"
#include "io/sha256.hpp"
#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

bool is_obj(const fs::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".obj";
}

// The OBJ statements every frame is written with: the mesh's own for an OBJ, else its vertices
// and triangles as a plain OBJ.
ObjFile mesh_layout(const fs::path& file, const std::string& bytes) {
  if (is_obj(file)) return parse_obj(bytes, file.string());
  return parse_obj(format_obj(read_mesh(file)), file.string());
}

std::string cache_number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

class PointCacheSource : public FrameSource {
 public:
  explicit PointCacheSource(const PointCacheInput& input)
      : input_(input), header_(read_point_cache_header(input.file, input.format)) {
    const std::string mesh_bytes = read_file(input.mesh);
    mesh_hash_ = sha256_hex(mesh_bytes);
    layout_ = std::make_shared<const ObjFile>(mesh_layout(input.mesh, mesh_bytes));
    const int n = layout_->mesh.num_vertices();
    if (n != header_.points)
      throw InputError("'" + input.file.string() + "' has " + std::to_string(header_.points) +
                       " points per frame, but its mesh '" + input.mesh.string() + "' has " +
                       std::to_string(n) + " vertices; the cache must be of that mesh");
  }

  const PointCacheHeader* point_cache() const override { return &header_; }

  int size() const override { return header_.frames; }
  std::string name(int i) const override { return numbered_frame_name(i, size()); }
  std::optional<double> time(int i) const override {
    if (header_.times.empty()) return std::nullopt;
    return header_.times[size_t(i)];
  }
  std::string describe() const override {
    std::string text = std::string(point_cache_format_label(input_.format)) + " cache " +
                       input_.file.string() + ", " + std::to_string(size()) + " frames of " +
                       std::to_string(header_.points) + " points";
    if (input_.format == PointCacheFormat::Pc2)
      text += " (start frame " + cache_number(header_.start) + ", sample rate " +
              cache_number(header_.sample_rate) + ")";
    else
      text += " (" + cache_number(header_.times.front()) + " to " +
              cache_number(header_.times.back()) + " s)";
    return text + ", on the triangles of " + input_.mesh.string() + " (" +
           std::to_string(layout_->mesh.num_triangles()) + ")";
  }
  json report() const override {
    json r = {{"kind", input_.format == PointCacheFormat::Pc2 ? "pc2" : "mdd"},
              {"file", input_.file.string()},
              {"mesh", input_.mesh.string()},
              {"frames", size()},
              {"vertices", header_.points},
              {"triangles", layout_->mesh.num_triangles()}};
    if (input_.format == PointCacheFormat::Pc2) {
      r["start_frame"] = header_.start;
      r["sample_rate"] = header_.sample_rate;
    } else {
      r["time_start"] = header_.times.front();
      r["time_end"] = header_.times.back();
    }
    return r;
  }
  std::vector<fs::path> files(const std::vector<int>&) const override {
    return {input_.file, input_.mesh};
  }
  std::string fetch(int i) const override {
    return read_point_cache_frame_bytes(input_.file, header_, i);
  }
  SourceFrame decode(int i, std::string bytes) const override {
    SourceFrame frame;
    frame.mesh.V = decode_point_cache_frame(bytes, header_, i, "'" + input_.file.string() + "'");
    frame.mesh.F = layout_->mesh.F;
    frame.obj = layout_;
    return frame;
  }
  // The frame's positions and the mesh (whose statements an OBJ output copies); an MDD frame's
  // time too (summary.csv and the MDD output carry it), so that --resume redoes a frame whose
  // time alone changed. A PC2's frames have no time of their own: their hash is unchanged.
  std::string input_hash(int i, const std::string& fetched) const override {
    std::string text = mesh_hash_ + " " + sha256_hex(fetched);
    if (!header_.times.empty()) {
      uint32_t bits;
      const float time = header_.times[size_t(i)];
      std::memcpy(&bits, &time, 4);
      char hex[16];
      std::snprintf(hex, sizeof hex, "%08x", unsigned(bits));
      text += " time ";
      text += hex;
    }
    return sha256_hex(text);
  }

 private:
  PointCacheInput input_;
  PointCacheHeader header_;
  std::shared_ptr<const ObjFile> layout_;
  std::string mesh_hash_;
};

}  // namespace

std::shared_ptr<const FrameSource> make_point_cache_source(const PointCacheInput& input) {
  return std::make_shared<PointCacheSource>(input);
}

}  // namespace sm
