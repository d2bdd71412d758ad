#include "io/obj.hpp"

#include <climits>
#include <cmath>
#include <cstring>
#include <utility>

#include "io/atomic_file.hpp"
#include "io/obj_lines.hpp"
#include "io/text_scan.hpp"
#include "core/coordinate_limit.hpp"
#include "core/errors.hpp"

namespace sm {
namespace {

const char* const kIndexName[3] = {"vertex", "texture coordinate", "normal"};
const char* const kCountName[3] = {"vertices", "texture coordinates", "normals"};

// An index beyond the statements read so far, checked against the totals at the end of the file.
struct ForwardIndex {
  int line;
  int corner;
  int field;  // 0 v, 1 vt, 2 vn
  int64_t index;
  std::string token;
};

class ObjParser {
 public:
  ObjParser(std::string text, const std::string& name) {
    file_.name = name;
    file_.text = std::move(text);
  }

  ObjFile parse() {
    const std::string_view text = file_.text;
    if (const std::string why = non_text_encoding(text); !why.empty()) {
      throw InputError(file_.name + ": not a text OBJ file: " + why +
                       "; OBJ is ASCII or UTF-8 text");
    }
    size_t pos = 0;
    if (text.substr(0, 3) == "\xEF\xBB\xBF") {  // UTF-8 byte order mark
      add_run(ObjRun::Kind::kText, 0, 3);
      pos = 3;
    }
    std::string joined;
    while (pos < text.size()) {
      const ObjLine line = scan_obj_line(text, pos);
      line_ = line_next_;
      line_next_ += line.physical_lines;
      const std::string_view content = obj_line_content(text, line, joined);
      size_t at = 0;
      const std::string_view keyword = next_token(content, at);
      const std::string_view data = content.substr(0, content.find('#'));
      if (keyword == "v") {
        add_run(ObjRun::Kind::kVertices, file_.vertex_offsets.size(),
                file_.vertex_offsets.size() + 1);
        file_.vertex_offsets.push_back(line.begin);
        parse_vertex(data, at);
      } else if (keyword == "vn") {
        add_run(ObjRun::Kind::kNormals, file_.normal_offsets.size(),
                file_.normal_offsets.size() + 1);
        file_.normal_offsets.push_back(line.begin);
        parse_numbers(data, at, "vn", 3, "xyz", 3, normals_);
      } else {
        add_run(ObjRun::Kind::kText, line.begin, line.end);
        if (keyword == "vt") {
          parse_numbers(data, at, "vt", 1, "uvw", 2, texcoords_);
        } else if (keyword == "f") {
          parse_face(data, at);
        }
      }
      pos = line.end;
    }
    return finish();
  }

 private:
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(file_.name + ":" + std::to_string(line_) + ": " + message);
  }

  void add_run(ObjRun::Kind kind, size_t begin, size_t end) {
    if (!file_.runs.empty() && file_.runs.back().kind == kind && file_.runs.back().end == begin) {
      file_.runs.back().end = end;
    } else {
      file_.runs.push_back({kind, begin, end});
    }
  }

  // `field()` names the value in messages; it is only called for one.
  template <class Field>
  double number(std::string_view token, const char* statement, Field field) const {
    double value = 0;
    const bool numeric = parse_double(token, value);
    if (!numeric || !std::isfinite(value)) {
      fail(std::string(statement) + ": " + field() + " '" + std::string(token) +
           (numeric ? "' is not finite" : "' is not a number"));
    }
    return value;
  }

  void parse_vertex(std::string_view data, size_t at) {
    for (int c = 0; c < 3; ++c) {
      const std::string_view token = next_token(data, at);
      if (token.empty()) {
        fail("v: expected 3 coordinates (x y z), found " + std::to_string(c));
      }
      const double x = number(token, "v", [c] { return std::string("coordinate ") + "xyz"[c]; });
      if (std::abs(x) > kMaxCoordinate) {
        fail(std::string("v: coordinate ") + "xyz"[c] + " '" + std::string(token) +
             "' is too large (more than 1e18 in magnitude: the geometry would overflow)");
      }
      positions_.push_back(x);
    }
    // w or vertex colours: validated here, written back from the text.
    for (int k = 1;; ++k) {
      const std::string_view token = next_token(data, at);
      if (token.empty()) break;
      number(token, "v", [k] { return "extra value " + std::to_string(k) + " (w or colour)"; });
    }
  }

  // `min` to strlen(`names`) values, named by the letters of `names`; the first `stored` values
  // are appended to `out`, missing ones as 0.
  void parse_numbers(std::string_view data, size_t at, const char* statement, int min,
                     const char* names, int stored, std::vector<double>& out) {
    const int max = static_cast<int>(std::strlen(names));
    std::string_view tokens[3];
    int count = 0;
    for (std::string_view token = next_token(data, at); !token.empty();
         token = next_token(data, at)) {
      if (count < max) tokens[count] = token;
      ++count;
    }
    if (count < min || count > max) {
      fail(std::string(statement) + ": expected " + std::to_string(min) +
           (min == max ? "" : " to " + std::to_string(max)) + " values (" + spaced(names) +
           "), found " + std::to_string(count));
    }
    for (int k = 0; k < stored; ++k) {
      const auto field = [&] { return std::string("coordinate ") + names[k]; };
      out.push_back(k < count ? number(tokens[k], statement, field) : 0.0);
    }
    for (int k = stored; k < count; ++k) {
      number(tokens[k], statement, [&] { return std::string("coordinate ") + names[k]; });
    }
  }

  static std::string spaced(const char* names) {
    std::string s;
    for (const char* p = names; *p; ++p) {
      if (!s.empty()) s += ' ';
      s += *p;
    }
    return s;
  }

  void parse_face(std::string_view data, size_t at) {
    const int first = static_cast<int>(file_.corners.size());
    const int face = file_.num_faces();
    std::string_view first_token;
    int first_form = 0;
    for (int k = 1;; ++k) {
      const std::string_view token = next_token(data, at);
      if (token.empty()) break;
      int form = 0;
      const ObjCorner corner = parse_corner(token, k, form);
      if (k == 1) {
        first_token = token;
        first_form = form;
      } else if (form != first_form) {
        fail("f: corner " + std::to_string(k) + " '" + std::string(token) + "' has the form " +
             form_name(form) + " but corner 1 '" + std::string(first_token) + "' has the form " +
             form_name(first_form));
      }
      file_.corners.push_back(corner);
    }
    const int n = static_cast<int>(file_.corners.size()) - first;
    if (n < 3) fail("f: a face needs at least 3 corners, found " + std::to_string(n));
    for (int k = 1; k + 1 < n; ++k) {
      triangles_.push_back(file_.corners[first].v);
      triangles_.push_back(file_.corners[first + k].v);
      triangles_.push_back(file_.corners[first + k + 1].v);
      file_.triangle_face.push_back(face);
    }
    file_.face_offsets.push_back(first + n);
  }

  static const char* form_name(int form) {
    static const char* const names[4] = {"v", "v/vt", "v//vn", "v/vt/vn"};
    return names[form];
  }

  // Splits "v", "v/vt", "v//vn" or "v/vt/vn"; `form` gets bit 0 for vt and bit 1 for vn.
  ObjCorner parse_corner(std::string_view token, int k, int& form) {
    std::string_view parts[3];
    int count = 0;
    bool too_many = false;
    for (size_t start = 0;;) {
      const size_t slash = token.find('/', start);
      parts[count++] = token.substr(start, slash - start);  // npos: up to the end
      if (slash == std::string_view::npos) break;
      if (count == 3) {
        too_many = true;
        break;
      }
      start = slash + 1;
    }
    if (too_many || parts[0].empty() || (count == 2 && parts[1].empty()) ||
        (count == 3 && parts[2].empty())) {
      fail(corner_name(k, token) + ": expected v, v/vt, v//vn or v/vt/vn");
    }
    form = (count >= 2 && !parts[1].empty() ? 1 : 0) | (count == 3 ? 2 : 0);
    ObjCorner c;
    c.v = resolve(parts[0], 0, k, token);
    if (form & 1) c.vt = resolve(parts[1], 1, k, token);
    if (form & 2) c.vn = resolve(parts[2], 2, k, token);
    return c;
  }

  static std::string corner_name(int k, std::string_view token) {
    return "f: corner " + std::to_string(k) + " '" + std::string(token) + "'";
  }

  int count_of(int field) const {
    const size_t n = field == 0   ? positions_.size() / 3
                     : field == 1 ? texcoords_.size() / 2
                                  : normals_.size() / 3;
    return static_cast<int>(n);
  }

  int resolve(std::string_view part, int field, int k, std::string_view token) {
    const auto where = [&] { return corner_name(k, token); };
    int64_t index = 0;
    if (!parse_int(part, index)) {
      fail(where() + ": " + kIndexName[field] + " index '" + std::string(part) +
           "' is not an integer");
    }
    const int64_t defined = count_of(field);
    if (index == 0) {
      fail(where() + ": " + kIndexName[field] + " index 0 is invalid (OBJ indices start at 1)");
    }
    if (index < 0) {
      if (-index > defined) {
        fail(where() + ": relative " + kIndexName[field] + " index " + std::to_string(index) +
             " is out of range (" + std::to_string(defined) + " " + kCountName[field] +
             " defined before this line)");
      }
      return static_cast<int>(defined + index);
    }
    if (index > defined) {
      if (index > INT_MAX) {
        fail(where() + ": " + kIndexName[field] + " index " + std::to_string(index) +
             " is out of range");
      }
      forward_.push_back({line_, k, field, index, std::string(token)});
    }
    return static_cast<int>(index - 1);
  }

  ObjFile finish() {
    for (const ForwardIndex& f : forward_) {
      if (f.index > count_of(f.field)) {
        line_ = f.line;
        fail("f: corner " + std::to_string(f.corner) + " '" + f.token +
             "': " + kIndexName[f.field] + " index " + std::to_string(f.index) +
             " is out of range (the file has " + std::to_string(count_of(f.field)) + " " +
             kCountName[f.field] + ")");
      }
    }
    if (positions_.empty()) throw InputError(file_.name + ": no vertices (no 'v' statement)");
    if (file_.num_faces() == 0) throw InputError(file_.name + ": no faces (no 'f' statement)");
    file_.mesh.V = Eigen::Map<const Positions>(positions_.data(), count_of(0), 3);
    file_.mesh.F = Eigen::Map<const Triangles>(triangles_.data(),
                                               static_cast<Eigen::Index>(triangles_.size() / 3), 3);
    file_.texcoords = Eigen::Map<const TexCoords>(texcoords_.data(), count_of(1), 2);
    file_.normals = Eigen::Map<const Positions>(normals_.data(), count_of(2), 3);
    return std::move(file_);
  }

  ObjFile file_;
  int line_ = 0;       // first physical line of the statement being parsed
  int line_next_ = 1;  // first physical line of the next statement
  std::vector<double> positions_, texcoords_, normals_;
  std::vector<int> triangles_;
  std::vector<ForwardIndex> forward_;
};

}  // namespace

ObjFile parse_obj(std::string_view text, const std::string& name) {
  return ObjParser(std::string(text), name).parse();
}

ObjFile read_obj(const std::filesystem::path& path) {
  return ObjParser(read_file(path), path.string()).parse();
}

}  // namespace sm
