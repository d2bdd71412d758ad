#include "io/off.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/text_scan.hpp"
#include "core/coordinate_limit.hpp"
#include "core/errors.hpp"

namespace sm {
namespace {

class OffParser {
 public:
  OffParser(std::string_view text, const std::string& name) : text_(text), name_(name) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);  // UTF-8 byte order mark
  }

  TriMesh parse() {
    int nv = 0, nf = 0;
    read_header(nv, nf);
    const std::vector<double> positions = read_vertices(nv);
    std::vector<int> tris;
    tris.reserve(3 * std::min<size_t>(static_cast<size_t>(nf), text_.size() / 8));
    std::vector<int> poly;
    for (int f = 0; f < nf; ++f) {
      read_face(f, nf, nv, poly);
      for (size_t k = 1; k + 1 < poly.size(); ++k) {
        tris.insert(tris.end(), {poly[0], poly[k], poly[k + 1]});
      }
    }
    TriMesh mesh;
    mesh.V = Eigen::Map<const Positions>(positions.data(), nv, 3);
    mesh.F =
        Eigen::Map<const Triangles>(tris.data(), static_cast<Eigen::Index>(tris.size() / 3), 3);
    return mesh;
  }

 private:
  // The keyword line and the vertex and face counts (on the keyword's line or the next).
  void read_header(int& nv, int& nf) {
    std::string_view line = next_line();
    if (!next_line_found_) throw InputError(name_ + ": empty file, expected the OFF header");
    size_t at = 0;
    const std::string_view keyword = next_token(line, at);
    check_keyword(keyword);
    const std::string_view rest = line.substr(at);
    size_t rest_at = 0;
    if (next_token(rest, rest_at) == "BINARY") fail(line_, "binary OFF is not supported");
    line = rest;
    at = 0;
    if (next_token(line, at).empty()) {  // the counts are on a line of their own
      line = next_line();
      if (!next_line_found_) throw InputError(name_ + ": the file ends before the counts line");
    }
    at = 0;
    nv = count(line, at, "vertex count");
    nf = count(line, at, "face count");
    if (nv == 0) fail(line_, "no vertices (the vertex count is 0)");
    if (nf == 0) fail(line_, "no faces (the face count is 0)");
  }

  std::vector<double> read_vertices(int nv) {
    // The counts come from the file: allocate by what the text can hold, not by what they claim.
    std::vector<double> positions;
    positions.reserve(3 * std::min<size_t>(static_cast<size_t>(nv), text_.size() / 6));
    for (int i = 0; i < nv; ++i) {
      const std::string_view line = expect_line("vertices", nv, i);
      size_t at = 0;
      for (int c = 0; c < 3; ++c) {
        const auto where = [&] {
          return "vertex " + std::to_string(i) + ": coordinate " + "xyz"[c];
        };
        const std::string_view token = next_token(line, at);
        if (token.empty()) fail(line_, where() + " is missing");
        double value = 0;
        if (!parse_double(token, value)) {
          fail(line_, where() + " '" + std::string(token) + "' is not a number");
        }
        if (!std::isfinite(value)) {
          fail(line_, where() + " '" + std::string(token) + "' is not finite");
        }
        if (std::abs(value) > kMaxCoordinate) {
          fail(line_, where() + " '" + std::string(token) +
                          "' is too large (more than 1e18 in magnitude: the geometry would "
                          "overflow)");
        }
        positions.push_back(value);
      }
    }
    return positions;
  }

  // Face f's corners into `poly`.
  void read_face(int f, int nf, int nv, std::vector<int>& poly) {
    const std::string_view line = expect_line("faces", nf, f);
    size_t at = 0;
    const auto face = [f] { return "face " + std::to_string(f); };
    const std::string_view n_token = next_token(line, at);
    int64_t n = 0;
    if (!parse_int(n_token, n)) {
      fail(line_, face() + ": corner count '" + std::string(n_token) + "' is not an integer");
    }
    if (n < 3) {
      fail(line_, face() + ": a face needs at least 3 corners, found " + std::to_string(n));
    }
    poly.clear();
    for (int64_t k = 0; k < n; ++k) {
      const auto where = [&] { return face() + ": corner " + std::to_string(k + 1); };
      const std::string_view token = next_token(line, at);
      if (token.empty()) {
        fail(line_, face() + ": expected " + std::to_string(n) + " vertex indices, found " +
                        std::to_string(k));
      }
      int64_t index = 0;
      if (!parse_int(token, index)) {
        fail(line_, where() + ": vertex index '" + std::string(token) + "' is not an integer");
      }
      if (index < 0 || index >= nv) {
        fail(line_, where() + ": vertex index " + std::to_string(index) +
                        " is out of range (the file has " + std::to_string(nv) +
                        " vertices, numbered from 0)");
      }
      poly.push_back(static_cast<int>(index));
    }
  }

  [[noreturn]] void fail(int line, const std::string& message) const {
    throw InputError(name_ + ":" + std::to_string(line) + ": " + message);
  }

  // [ST][C][N]OFF; texture coordinates, colours and normals are skipped with the rest of a line.
  void check_keyword(std::string_view keyword) const {
    std::string_view rest = keyword;
    for (const std::string_view p : {"ST", "C", "N"}) {
      if (rest.substr(0, p.size()) == p) rest.remove_prefix(p.size());
    }
    if (rest == "OFF") return;
    if (rest == "4OFF" || rest == "nOFF" || rest == "4nOFF") {
      fail(line_, "'" + std::string(keyword) + "': only 3-dimensional OFF is supported");
    }
    fail(line_, "expected the header keyword OFF, found '" + std::string(keyword) + "'");
  }

  int count(std::string_view line, size_t& at, const char* what) const {
    const std::string_view token = next_token(line, at);
    int64_t value = 0;
    if (token.empty()) fail(line_, std::string(what) + " is missing");
    if (!parse_int(token, value) || value < 0 || value > 0x7fffffff) {
      fail(line_,
           std::string(what) + " '" + std::string(token) + "' is not a non-negative integer");
    }
    return static_cast<int>(value);
  }

  // The next line with data, without its comment; sets next_line_found_ and line_.
  std::string_view next_line() {
    while (pos_ < text_.size()) {
      const void* nl = std::memchr(text_.data() + pos_, '\n', text_.size() - pos_);
      const size_t end =
          nl ? static_cast<size_t>(static_cast<const char*>(nl) - text_.data()) : text_.size();
      std::string_view line = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      line_ = ++physical_;
      line = line.substr(0, line.find('#'));
      size_t at = 0;
      if (!next_token(line, at).empty()) {
        next_line_found_ = true;
        return line;
      }
    }
    next_line_found_ = false;
    return {};
  }

  std::string_view expect_line(const char* what, int expected, int found) {
    const std::string_view line = next_line();
    if (!next_line_found_) {
      throw InputError(name_ + ": expected " + std::to_string(expected) + " " + what +
                       ", the file ends after " + std::to_string(found));
    }
    return line;
  }

  std::string_view text_;
  const std::string& name_;
  size_t pos_ = 0;
  int physical_ = 0;
  int line_ = 0;
  bool next_line_found_ = false;
};

}  // namespace

TriMesh parse_off(std::string_view text, const std::string& name) {
  return OffParser(text, name).parse();
}

TriMesh read_off(const std::filesystem::path& path) {
  const std::string text = read_file(path);
  return parse_off(text, path.string());
}

std::string format_off(const TriMesh& mesh) {
  validate_mesh(mesh, "cannot write OFF");
  std::string out = "OFF\n";
  out.reserve(static_cast<size_t>(mesh.num_vertices()) * 40 +
              static_cast<size_t>(mesh.num_triangles()) * 24);
  append_int(out, mesh.num_vertices());
  out += ' ';
  append_int(out, mesh.num_triangles());
  out += " 0\n";
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    for (int c = 0; c < 3; ++c) {
      if (c > 0) out += ' ';
      append_double(out, mesh.V(i, c));
    }
    out += '\n';
  }
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    out += '3';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      append_int(out, mesh.F(t, k));
    }
    out += '\n';
  }
  return out;
}

void write_off(const std::filesystem::path& path, const TriMesh& mesh) {
  write_file_atomic(path, format_off(mesh));
}

}  // namespace sm
