#include "io/obj_textured.hpp"

#include <cmath>
#include <sstream>

#include "io/text_scan.hpp"
#include "core/errors.hpp"

namespace sm {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw InputError("cannot write textured OBJ: " + what);
}

template <class Rows>
void append_rows(std::string& out, const char* keyword, const Rows& rows, const char* what) {
  for (Eigen::Index i = 0; i < rows.rows(); ++i) {
    out += keyword;
    for (Eigen::Index c = 0; c < rows.cols(); ++c) {
      const double x = rows(i, c);
      if (!std::isfinite(x))
        fail(std::string(what) + " " + std::to_string(i + 1) + " has a non-finite coordinate");
      out += ' ';
      append_double(out, x + 0.0);  // -0 written as 0
    }
    out += '\n';
  }
}

void check_indices(const Triangles& faces, Eigen::Index count, const char* what) {
  for (Eigen::Index t = 0; t < faces.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      if (faces(t, k) < 0 || faces(t, k) >= count)
        fail("triangle " + std::to_string(t + 1) + " refers to " + what + " " +
             std::to_string(faces(t, k) + 1) + " of " + std::to_string(count));
}

}  // namespace

std::string format_textured_obj(const Positions& V, const Triangles& F, const TexCoords& uv,
                                const Triangles& uv_faces, std::string_view mtllib,
                                std::string_view material, std::string_view comment) {
  if (uv_faces.rows() != F.rows())
    fail(std::to_string(uv_faces.rows()) + " texture triangles for " + std::to_string(F.rows()) +
         " triangles");
  check_indices(F, V.rows(), "vertex");
  check_indices(uv_faces, uv.rows(), "texture coordinate");
  std::string out;
  out.reserve(size_t(V.rows()) * 40 + size_t(uv.rows()) * 30 + size_t(F.rows()) * 40 + 256);
  std::istringstream lines{std::string(comment)};
  for (std::string line; std::getline(lines, line);) out += "# " + line + "\n";
  out += "mtllib ";
  out += mtllib;
  out += '\n';
  append_rows(out, "v", V, "vertex");
  append_rows(out, "vt", uv, "texture coordinate");
  out += "usemtl ";
  out += material;
  out += '\n';
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    out += 'f';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      append_int(out, F(t, k) + 1);
      out += '/';
      append_int(out, uv_faces(t, k) + 1);
    }
    out += '\n';
  }
  return out;
}

std::string format_texture_mtl(std::string_view material, std::string_view texture) {
  std::string out = "# written by seqmassage\nnewmtl ";
  out += material;
  out += "\nKa 1 1 1\nKd 1 1 1\nKs 0 0 0\nd 1\nillum 1\nmap_Kd ";
  out += texture;
  out += '\n';
  return out;
}

}  // namespace sm
