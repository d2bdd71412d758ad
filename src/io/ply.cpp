#include "io/ply.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "io/atomic_file.hpp"
#include "io/text_scan.hpp"
#include "core/coordinate_limit.hpp"
#include "core/errors.hpp"

namespace sm {

namespace {

std::string format_g(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

enum class PlyType : uint8_t {
  kInt8,
  kUInt8,
  kInt16,
  kUInt16,
  kInt32,
  kUInt32,
  kFloat32,
  kFloat64
};

bool parse_type(std::string_view s, PlyType& type) {
  static const struct {
    const char* name;
    const char* alias;
    PlyType type;
  } kTypes[] = {{"char", "int8", PlyType::kInt8},        {"uchar", "uint8", PlyType::kUInt8},
                {"short", "int16", PlyType::kInt16},     {"ushort", "uint16", PlyType::kUInt16},
                {"int", "int32", PlyType::kInt32},       {"uint", "uint32", PlyType::kUInt32},
                {"float", "float32", PlyType::kFloat32}, {"double", "float64", PlyType::kFloat64}};
  for (const auto& t : kTypes) {
    if (s == t.name || s == t.alias) {
      type = t.type;
      return true;
    }
  }
  return false;
}

size_t type_size(PlyType t) {
  static const size_t kSizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
  return kSizes[static_cast<int>(t)];
}

bool is_float(PlyType t) {
  return t == PlyType::kFloat32 || t == PlyType::kFloat64;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  ///< scalar type, or the item type of a list
  bool list = false;
  PlyType count_type = PlyType::kUInt8;
};

struct PlyElement {
  std::string name;
  int64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  bool binary = false;
  std::vector<PlyElement> elements;
  size_t body = 0;    ///< offset of the first byte after end_header
  int body_line = 0;  ///< number of the first line after end_header
};

PlyHeader parse_header(std::string_view data, const std::string& name) {
  PlyHeader header;
  size_t pos = 0;
  int line_no = 0;
  std::string_view line;
  auto next_line = [&]() {
    if (pos >= data.size()) return false;
    const size_t nl = data.find('\n', pos);
    const size_t end = nl == std::string_view::npos ? data.size() : nl;
    line = data.substr(pos, end - pos);
    pos = end == data.size() ? end : end + 1;
    ++line_no;
    return true;
  };
  auto fail = [&](const std::string& message) {
    throw InputError(name + ":" + std::to_string(line_no) + ": " + message);
  };
  size_t at = 0;
  if (!next_line() || next_token(line, at) != "ply" || !next_token(line, at).empty()) {
    throw InputError(name + ": not a PLY file (the first line is not 'ply')");
  }
  bool format = false;
  for (;;) {
    if (!next_line()) throw InputError(name + ": the PLY header has no end_header line");
    at = 0;
    const std::string_view keyword = next_token(line, at);
    if (keyword == "end_header") break;
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      const std::string_view f = next_token(line, at);
      if (f == "binary_big_endian") fail("format binary_big_endian is not supported");
      if (f != "ascii" && f != "binary_little_endian") {
        fail("unknown format '" + std::string(f) + "' (expected ascii or binary_little_endian)");
      }
      header.binary = f == "binary_little_endian";
      format = true;
    } else if (keyword == "element") {
      PlyElement e;
      e.name = std::string(next_token(line, at));
      const std::string_view count = next_token(line, at);
      if (e.name.empty() || !parse_int(count, e.count) || e.count < 0 || e.count > 0x7fffffff) {
        fail("expected 'element <name> <count>' with a count from 0 to 2^31-1");
      }
      header.elements.push_back(std::move(e));
    } else if (keyword == "property") {
      if (header.elements.empty()) fail("property before the first element");
      PlyProperty p;
      std::string_view type = next_token(line, at);
      if (type == "list") {
        p.list = true;
        const std::string_view count_type = next_token(line, at);
        if (!parse_type(count_type, p.count_type) || is_float(p.count_type)) {
          fail("list count type '" + std::string(count_type) + "' is not an integer type");
        }
        type = next_token(line, at);
      }
      if (!parse_type(type, p.type)) fail("unknown property type '" + std::string(type) + "'");
      p.name = std::string(next_token(line, at));
      if (p.name.empty()) fail("property without a name");
      header.elements.back().properties.push_back(std::move(p));
    } else {
      fail("unknown header keyword '" + std::string(keyword) + "'");
    }
  }
  if (!format) throw InputError(name + ": the PLY header has no format line");
  header.body = pos;
  header.body_line = line_no + 1;
  return header;
}

// Reads the values of the body in order, as text tokens or little-endian binary.
class PlyBody {
 public:
  PlyBody(std::string_view data, const PlyHeader& header, const std::string& name)
      : data_(data),
        pos_(header.body),
        line_(header.body_line),
        binary_(header.binary),
        name_(name) {}

  // `element`, `item` and `property` name the value in messages.
  // `list_count`: the value is the length of list `property`.
  double read(PlyType type, const PlyElement& element, int64_t item, const PlyProperty& property,
              bool list_count = false) {
    return binary_ ? read_binary(type, element, item, property, list_count)
                   : read_text(type, element, item, property, list_count);
  }

  [[noreturn]] void fail(const PlyElement& element, int64_t item, const std::string& message) {
    const std::string where = binary_ ? name_ : name_ + ":" + std::to_string(line_);
    throw InputError(where + ": " + element.name + " " + std::to_string(item) + ": " + message);
  }

 private:
  static std::string label(const PlyProperty& property, bool list_count) {
    return list_count ? property.name + " count" : property.name;
  }

  double read_binary(PlyType type, const PlyElement& element, int64_t item,
                     const PlyProperty& property, bool list_count) {
    const size_t size = type_size(type);
    if (data_.size() - pos_ < size) {
      fail(element, item,
           label(property, list_count) + ": the data ends early (binary, byte " +
               std::to_string(pos_) + ")");
    }
    uint64_t bits = 0;
    for (size_t b = 0; b < size; ++b) {
      bits |= uint64_t(static_cast<uint8_t>(data_[pos_ + b])) << (8 * b);
    }
    pos_ += size;
    switch (type) {
      case PlyType::kInt8:
        return static_cast<int8_t>(bits);
      case PlyType::kUInt8:
        return static_cast<uint8_t>(bits);
      case PlyType::kInt16:
        return static_cast<int16_t>(bits);
      case PlyType::kUInt16:
        return static_cast<uint16_t>(bits);
      case PlyType::kInt32:
        return static_cast<int32_t>(bits);
      case PlyType::kUInt32:
        return static_cast<uint32_t>(bits);
      case PlyType::kFloat32: {
        const auto b32 = static_cast<uint32_t>(bits);
        float f;
        std::memcpy(&f, &b32, sizeof f);
        return f;
      }
      case PlyType::kFloat64: {
        double d;
        std::memcpy(&d, &bits, sizeof d);
        return d;
      }
    }
    return 0.0;
  }

  double read_text(PlyType type, const PlyElement& element, int64_t item,
                   const PlyProperty& property, bool list_count) {
    int line = line_;  // line_ stays on the last token's line when the data ends
    while (pos_ < data_.size() && (is_blank(data_[pos_]) || data_[pos_] == '\n')) {
      if (data_[pos_++] == '\n') ++line;
    }
    if (pos_ < data_.size()) line_ = line;
    size_t end = pos_;
    while (end < data_.size() && !is_blank(data_[end]) && data_[end] != '\n') ++end;
    const std::string_view token = data_.substr(pos_, end - pos_);
    if (token.empty()) fail(element, item, label(property, list_count) + ": the data ends early");
    pos_ = end;
    if (is_float(type)) {
      double value = 0;
      if (!parse_double(token, value)) {
        fail(element, item,
             label(property, list_count) + " '" + std::string(token) + "' is not a number");
      }
      return value;
    }
    int64_t value = 0;
    if (!parse_int(token, value)) {
      fail(element, item,
           label(property, list_count) + " '" + std::string(token) + "' is not an integer");
    }
    return static_cast<double>(value);
  }

  std::string_view data_;
  size_t pos_;
  int line_;
  bool binary_;
  const std::string& name_;
};

uint8_t to_channel(double value, PlyType type) {
  const double scaled = is_float(type) ? std::round(value * 255.0) : value;
  return static_cast<uint8_t>(std::clamp(std::isfinite(scaled) ? scaled : 0.0, 0.0, 255.0));
}

int find_property(const PlyElement& e, std::string_view name, bool list) {
  for (size_t k = 0; k < e.properties.size(); ++k) {
    if (e.properties[k].name == name && e.properties[k].list == list) return static_cast<int>(k);
  }
  return -1;
}

// Where the mesh's data sits among a PLY header's elements and properties (indices into an
// element's properties; -1: absent).
struct PlyLayout {
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;
  int xyz[3] = {-1, -1, -1};
  int indices = -1;  ///< the face's list of vertex indices
  int vrgb[3] = {-1, -1, -1}, frgb[3] = {-1, -1, -1};
  bool vertex_colors = false, face_colors = false;  ///< asked for and present
  int extra = -1;                                   ///< the extra vertex property
};

PlyLayout find_layout(const PlyHeader& header, const std::string& name, bool colors,
                      const PlyVertexProperty* extra) {
  PlyLayout l;
  for (const PlyElement& e : header.elements) {
    if (e.name == "vertex" && !l.vertex) l.vertex = &e;
    if (e.name == "face" && !l.face) l.face = &e;
  }
  if (!l.vertex || l.vertex->count == 0)
    throw InputError(name + ": no vertices (no 'vertex' element, or its count is 0)");
  if (!l.face || l.face->count == 0)
    throw InputError(name + ": no faces (no 'face' element, or its count is 0)");
  for (int c = 0; c < 3; ++c) {
    l.xyz[c] = find_property(*l.vertex, std::string(1, "xyz"[c]), false);
    if (l.xyz[c] < 0)
      throw InputError(name + ": the vertex element has no scalar property " + "xyz"[c]);
  }
  l.indices = find_property(*l.face, "vertex_indices", true);
  if (l.indices < 0) l.indices = find_property(*l.face, "vertex_index", true);
  if (l.indices < 0)
    throw InputError(name + ": the face element has no list property vertex_indices");
  for (int c = 0; c < 3; ++c) {
    const char* channel[] = {"red", "green", "blue"};
    l.vrgb[c] = find_property(*l.vertex, channel[c], false);
    l.frgb[c] = find_property(*l.face, channel[c], false);
  }
  l.vertex_colors = colors && l.vrgb[0] >= 0 && l.vrgb[1] >= 0 && l.vrgb[2] >= 0;
  l.face_colors = colors && l.frgb[0] >= 0 && l.frgb[1] >= 0 && l.frgb[2] >= 0;
  l.extra = extra ? find_property(*l.vertex, extra->name, false) : -1;
  if (extra && l.extra < 0)
    throw InputError(name + ": the vertex element has no scalar property '" + extra->name + "'");
  return l;
}

// Decodes the body's items in order into positions and triangles (and the colours and the extra
// vertex property, when asked for).
class PlyMeshReader {
 public:
  PlyMeshReader(std::string_view data, const PlyHeader& header, const std::string& name,
                const PlyLayout& layout, PlyColors* colors, PlyVertexProperty* extra)
      : body_(data, header, name),
        l_(layout),
        nv_(layout.vertex->count),
        colors_(colors),
        extra_(extra) {
    // The counts come from the file: allocate by what the data can hold, not by what they claim.
    positions_.reserve(3 * std::min<size_t>(static_cast<size_t>(nv_), data.size() / 3));
  }

  void read_item(const PlyElement& e, int64_t item) {
    std::array<uint8_t, 3> rgb{};
    double xyz[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
      const PlyProperty& p = e.properties[k];
      if (p.list) {
        read_list(e, item, k);
      } else if (&e == l_.vertex) {
        read_vertex_scalar(e, item, k, rgb, xyz);
      } else {
        const double value = body_.read(p.type, e, item, p);
        for (int c = 0; c < 3 && &e == l_.face && l_.face_colors; ++c)
          if (k == l_.frgb[c]) rgb[c] = to_channel(value, p.type);
      }
    }
    if (&e == l_.vertex) positions_.insert(positions_.end(), xyz, xyz + 3);
    if (&e == l_.vertex && l_.vertex_colors) colors_->vertex.push_back(rgb);
    if (&e != l_.face) return;
    for (size_t k = 1; k + 1 < poly_.size(); ++k) {  // a fan of triangles
      tris_.insert(tris_.end(), {poly_[0], poly_[k], poly_[k + 1]});
      if (l_.face_colors) colors_->face.push_back(rgb);
    }
  }

  TriMesh mesh() const {
    TriMesh mesh;
    mesh.V = Eigen::Map<const Positions>(positions_.data(), static_cast<Eigen::Index>(nv_), 3);
    mesh.F =
        Eigen::Map<const Triangles>(tris_.data(), static_cast<Eigen::Index>(tris_.size() / 3), 3);
    return mesh;
  }

 private:
  void read_vertex_scalar(const PlyElement& e, int64_t item, int k, std::array<uint8_t, 3>& rgb,
                          double xyz[3]) {
    const PlyProperty& p = e.properties[k];
    const double value = body_.read(p.type, e, item, p);
    for (int c = 0; c < 3; ++c) {
      if (k == l_.xyz[c]) {
        if (!std::isfinite(value)) body_.fail(e, item, p.name + " is not finite");
        if (std::abs(value) > kMaxCoordinate) {
          body_.fail(e, item,
                     p.name + " " + format_g(value) +
                         " is too large (more than 1e18 in magnitude: the geometry would "
                         "overflow)");
        }
        xyz[c] = value;
      }
      if (l_.vertex_colors && k == l_.vrgb[c]) rgb[c] = to_channel(value, p.type);
    }
    if (k == l_.extra) extra_->values.push_back(value);
  }

  // A list property; the face's vertex indices go to poly_, other lists are skipped.
  void read_list(const PlyElement& e, int64_t item, int k) {
    const PlyProperty& p = e.properties[k];
    const double n = body_.read(p.count_type, e, item, p, true);
    if (n < 0) body_.fail(e, item, p.name + ": negative list length");
    const bool corners = &e == l_.face && k == l_.indices;
    if (corners) poly_.clear();
    for (int64_t j = 0; j < static_cast<int64_t>(n); ++j) {
      const double value = body_.read(p.type, e, item, p);
      if (!corners) continue;
      if (!(value >= 0 && value < static_cast<double>(nv_)) || value != std::floor(value)) {
        std::string text;
        append_double(text, value);
        body_.fail(e, item,
                   "corner " + std::to_string(j + 1) + ": vertex index " + text +
                       (value != std::floor(value)
                            ? " is not an integer"
                            : " is out of range (the file has " + std::to_string(nv_) +
                                  " vertices, numbered from 0)"));
      }
      poly_.push_back(static_cast<int>(value));
    }
    if (corners && n < 3) {
      body_.fail(
          e, item,
          "a face needs at least 3 corners, found " + std::to_string(static_cast<int64_t>(n)));
    }
  }

  PlyBody body_;
  const PlyLayout& l_;
  const int64_t nv_;
  PlyColors* colors_;
  PlyVertexProperty* extra_;
  std::vector<double> positions_;
  std::vector<int> tris_, poly_;
};

}  // namespace

TriMesh parse_ply(std::string_view data, const std::string& name, PlyColors* colors,
                  PlyVertexProperty* extra) {
  const PlyHeader header = parse_header(data, name);
  const PlyLayout layout = find_layout(header, name, colors != nullptr, extra);
  if (colors) *colors = PlyColors{};
  if (extra) extra->values.clear();
  PlyMeshReader reader(data, header, name, layout, colors, extra);
  int done = 0;
  for (const PlyElement& e : header.elements) {
    if (e.properties.empty()) continue;  // items without properties hold no data, however many
    for (int64_t item = 0; item < e.count; ++item) reader.read_item(e, item);
    if (&e == layout.vertex || &e == layout.face) ++done;
    if (done == 2) break;  // later elements are not needed
  }
  return reader.mesh();
}

TriMesh read_ply(const std::filesystem::path& path, PlyColors* colors) {
  const std::string data = read_file(path);
  return parse_ply(data, path.string(), colors);
}

}  // namespace sm
