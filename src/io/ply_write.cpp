// Writing PLY files (declared in ply.hpp): triangles with optional RGB colours, ASCII or binary.
#include <cstring>
#include <string>

#include "io/atomic_file.hpp"
#include "io/ply.hpp"
#include "io/text_scan.hpp"
#include "core/errors.hpp"

namespace sm {
namespace {

void append_le(std::string& out, uint64_t bits, size_t bytes) {
  for (size_t b = 0; b < bytes; ++b) out += static_cast<char>((bits >> (8 * b)) & 0xff);
}

void append_rgb(std::string& out, const std::array<uint8_t, 3>& rgb, bool binary) {
  for (const uint8_t channel : rgb) {
    if (binary) {
      out += static_cast<char>(channel);
    } else {
      out += ' ';
      append_int(out, channel);
    }
  }
}

}  // namespace

std::string format_ply(const TriMesh& mesh, const PlyColors* colors, bool binary) {
  validate_mesh(mesh, "cannot write PLY");
  const size_t nv = static_cast<size_t>(mesh.num_vertices());
  const size_t nf = static_cast<size_t>(mesh.num_triangles());
  const bool vertex_colors = colors && !colors->vertex.empty();
  const bool face_colors = colors && !colors->face.empty();
  if (vertex_colors && colors->vertex.size() != nv) {
    throw InputError("cannot write PLY: " + std::to_string(colors->vertex.size()) +
                     " vertex colours for " + std::to_string(nv) + " vertices");
  }
  if (face_colors && colors->face.size() != nf) {
    throw InputError("cannot write PLY: " + std::to_string(colors->face.size()) +
                     " face colours for " + std::to_string(nf) + " triangles");
  }
  const char* const rgb_properties =
      "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  std::string out = "ply\nformat ";
  out += binary ? "binary_little_endian" : "ascii";
  out += " 1.0\ncomment written by seqmassage\nelement vertex ";
  append_int(out, static_cast<int64_t>(nv));
  out += "\nproperty double x\nproperty double y\nproperty double z\n";
  if (vertex_colors) out += rgb_properties;
  out += "element face ";
  append_int(out, static_cast<int64_t>(nf));
  out += "\nproperty list uchar int vertex_indices\n";
  if (face_colors) out += rgb_properties;
  out += "end_header\n";
  out.reserve(out.size() + nv * (binary ? 27 : 48) + nf * (binary ? 16 : 28));
  for (size_t i = 0; i < nv; ++i) {
    for (int c = 0; c < 3; ++c) {
      const double value = mesh.V(static_cast<Eigen::Index>(i), c);
      if (binary) {
        uint64_t bits;
        std::memcpy(&bits, &value, sizeof bits);
        append_le(out, bits, 8);
      } else {
        if (c > 0) out += ' ';
        append_double(out, value);
      }
    }
    if (vertex_colors) append_rgb(out, colors->vertex[i], binary);
    if (!binary) out += '\n';
  }
  for (size_t t = 0; t < nf; ++t) {
    out += binary ? '\3' : '3';
    for (int k = 0; k < 3; ++k) {
      const int index = mesh.F(static_cast<Eigen::Index>(t), k);
      if (binary) {
        append_le(out, static_cast<uint32_t>(index), 4);
      } else {
        out += ' ';
        append_int(out, index);
      }
    }
    if (face_colors) append_rgb(out, colors->face[t], binary);
    if (!binary) out += '\n';
  }
  return out;
}

void write_ply(const std::filesystem::path& path, const TriMesh& mesh, const PlyColors* colors,
               bool binary) {
  write_file_atomic(path, format_ply(mesh, colors, binary));
}

}  // namespace sm
