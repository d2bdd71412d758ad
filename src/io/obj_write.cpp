// Writing OBJ files (declared in obj.hpp): the file as read, with new vertex positions.
#include <cmath>
#include <cstring>
#include <string>

#include "io/atomic_file.hpp"
#include "io/obj.hpp"
#include "io/obj_lines.hpp"
#include "io/text_scan.hpp"
#include "core/errors.hpp"

namespace sm {
namespace {

void check_positions(const ObjFile& file, const Positions& V) {
  if (V.rows() != file.mesh.V.rows()) {
    throw InputError("cannot write OBJ '" + file.name + "': " + std::to_string(V.rows()) +
                     " positions given for " + std::to_string(file.mesh.V.rows()) + " vertices");
  }
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    if (!V.row(i).allFinite()) {
      throw InputError("cannot write OBJ '" + file.name + "': vertex " + std::to_string(i + 1) +
                       " has a non-finite coordinate");
    }
  }
}

bool same_row(const Positions& a, const Positions& b, Eigen::Index i) {
  return std::memcmp(a.row(i).data(), b.row(i).data(), 3 * sizeof(double)) == 0;
}

// Area-weighted normal of every vn over the triangles whose corners use it, with the arithmetic
// of sm::vertex_normals; `valid[j]` is false where no triangle with area uses vn j, or where the
// sum is not finite.
Positions corner_normals(const ObjFile& file, const Positions& V, std::vector<char>& valid) {
  Positions N = Positions::Zero(file.normals.rows(), 3);
  for (int f = 0; f < file.num_faces(); ++f) {
    const int c0 = file.face_offsets[f];
    for (int c1 = c0 + 1; c1 + 1 < file.face_offsets[f + 1]; ++c1) {
      const int c[3] = {c0, c1, c1 + 1};
      const Vec3 p0 = V.row(file.corners[c[0]].v).transpose();
      const Vec3 n = (Vec3(V.row(file.corners[c[1]].v).transpose()) - p0)
                         .cross(Vec3(V.row(file.corners[c[2]].v).transpose()) - p0);
      for (int k = 0; k < 3; ++k) {
        const int vn = file.corners[c[k]].vn;
        if (vn >= 0) N.row(vn) += n.transpose();
      }
    }
  }
  valid.assign(static_cast<size_t>(N.rows()), 0);
  for (Eigen::Index j = 0; j < N.rows(); ++j) {
    double len = N.row(j).norm();
    if (!std::isfinite(len) && N.row(j).allFinite()) {  // the norm overflowed, the sum did not
      N.row(j) /= N.row(j).cwiseAbs().maxCoeff();
      len = N.row(j).norm();
    }
    if (len > 0.0 && std::isfinite(len)) {  // not when the sum overflowed (coordinates ~1e150)
      N.row(j) /= len;
      valid[static_cast<size_t>(j)] = 1;
    }
  }
  return N;
}

// Writes statement `keyword` with coordinates `xyz`, then the tokens of the original statement
// after its first four (extra values), its comment and its line break.
void write_statement(std::string& out, std::string_view text, size_t offset, const char* keyword,
                     const double* xyz, std::string& buffer) {
  const ObjLine line = scan_obj_line(text, offset);
  const std::string_view content = obj_line_content(text, line, buffer);
  const size_t hash = content.find('#');
  const std::string_view data = content.substr(0, hash);
  out += keyword;
  for (int c = 0; c < 3; ++c) {
    out += ' ';
    append_double(out, xyz[c]);
  }
  size_t at = 0;
  for (int k = 0;; ++k) {
    const std::string_view token = next_token(data, at);
    if (token.empty()) break;
    if (k >= 4) {
      out += ' ';
      out += token;
    }
  }
  if (hash != std::string_view::npos) {
    out += ' ';
    out += content.substr(hash);
  }
  out.append(text.substr(line.content_end, line.end - line.content_end));
}

void copy_statement(std::string& out, std::string_view text, size_t offset) {
  const ObjLine line = scan_obj_line(text, offset);
  out.append(text.substr(line.begin, line.end - line.begin));
}

}  // namespace

std::string format_obj(const ObjFile& file, const Positions& V) {
  check_positions(file, V);
  bool moved = false;
  for (Eigen::Index i = 0; i < V.rows() && !moved; ++i) moved = !same_row(V, file.mesh.V, i);
  std::vector<char> valid;
  Positions normals;
  if (moved && file.has_normals()) normals = corner_normals(file, V, valid);

  const std::string_view text = file.text;
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  std::string buffer;
  for (const ObjRun& run : file.runs) {
    switch (run.kind) {
      case ObjRun::Kind::kText:
        out.append(text.substr(run.begin, run.end - run.begin));
        break;
      case ObjRun::Kind::kVertices:
        for (size_t i = run.begin; i < run.end; ++i) {
          const auto row = static_cast<Eigen::Index>(i);
          if (same_row(V, file.mesh.V, row)) {
            copy_statement(out, text, file.vertex_offsets[i]);
          } else {
            write_statement(out, text, file.vertex_offsets[i], "v", V.row(row).data(), buffer);
          }
        }
        break;
      case ObjRun::Kind::kNormals:
        for (size_t j = run.begin; j < run.end; ++j) {
          if (moved && valid[j]) {
            const auto row = static_cast<Eigen::Index>(j);
            write_statement(out, text, file.normal_offsets[j], "vn", normals.row(row).data(),
                            buffer);
          } else {
            copy_statement(out, text, file.normal_offsets[j]);
          }
        }
        break;
    }
  }
  return out;
}

void write_obj(const std::filesystem::path& path, const ObjFile& file, const Positions& V) {
  write_file_atomic(path, format_obj(file, V));
}

std::string format_obj(const TriMesh& mesh) {
  validate_mesh(mesh, "cannot write OBJ");
  std::string out;
  out.reserve(static_cast<size_t>(mesh.num_vertices()) * 40 +
              static_cast<size_t>(mesh.num_triangles()) * 24);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    out += 'v';
    for (int c = 0; c < 3; ++c) {
      out += ' ';
      append_double(out, mesh.V(i, c));
    }
    out += '\n';
  }
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    out += 'f';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      append_int(out, mesh.F(t, k) + 1);
    }
    out += '\n';
  }
  return out;
}

void write_obj(const std::filesystem::path& path, const TriMesh& mesh) {
  write_file_atomic(path, format_obj(mesh));
}

}  // namespace sm
