// OFF and PLY: reading the variants tools write, exact round trips, colours, messages.
#include <catch2/catch.hpp>

#include <cstring>
#include <string>

#include "io/off.hpp"
#include "io/ply.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"
#include "support/error_of.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
using sm::test::error_of;

namespace {

bool bit_equal(const Positions& a, const Positions& b) {
  return a.rows() == b.rows() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

TriMesh odd_mesh() {
  TriMesh m = make_icosphere(1, 1.0);
  m.V(0, 0) = 0.1 + 0.2;
  m.V(1, 1) = -0.0;
  m.V(2, 2) = 5e-324;
  return m;
}

std::string off_error(const std::string& text) {
  return error_of<InputError>([&] { parse_off(text, "bad.off"); });
}

std::string ply_error(const std::string& data) {
  return error_of<InputError>([&] { parse_ply(data, "bad.ply"); });
}

template <class T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // the test machine is little-endian, like the format
  out.append(bytes, sizeof(T));
}

const char* const kAsciiPly =
    "ply\r\n"
    "format ascii 1.0\r\n"
    "comment made by hand\r\n"
    "obj_info two quads\r\n"
    "element vertex 6\r\n"
    "property float x\r\n"
    "property float y\r\n"
    "property float nx\r\n"
    "property float z\r\n"
    "property uchar red\r\n"
    "property uchar green\r\n"
    "property uchar blue\r\n"
    "element face 2\r\n"
    "property list uchar int vertex_index\r\n"
    "property float quality\r\n"
    "element edge 1\r\n"
    "property int vertex1\r\n"
    "property int vertex2\r\n"
    "end_header\r\n"
    "0 0 9 0 255 0 0\r\n"
    "1 0 9 0 0 255 0\r\n"
    "1 1 9 0 0 0 255\r\n"
    "0 1 9 0 1 2 3\r\n"
    "0 2 9 0.5 4 5 6\r\n"
    "1 2 9 0.5 7 8 9\r\n"
    "4 0 1 2 3 0.5\r\n"
    "4 3 2 5 4 1\r\n"
    "0 1\r\n";

}  // namespace

TEST_CASE("OFF variants: comments, COFF colours, counts on the header line, polygons", "[off]") {
  const std::string text =
      "# a comment before the header\n"
      "COFF\n"
      "\n"
      "4 2 0  # counts\n"
      "0 0 0 255 0 0 255\n"
      "1 0 0 0 255 0 255\n"
      "1 1 0 0 0 255 255\n"
      "0 1 0.5 9 9 9 255\n"
      "4 0 1 2 3 128 128 128\n"
      "3 0 2 1\n";
  const TriMesh m = parse_off(text, "colour.off");
  REQUIRE(m.num_vertices() == 4);
  CHECK(m.V(3, 2) == 0.5);
  REQUIRE(m.num_triangles() == 3);
  CHECK(m.F.row(0) == Eigen::RowVector3i(0, 1, 2));
  CHECK(m.F.row(1) == Eigen::RowVector3i(0, 2, 3));
  CHECK(m.F.row(2) == Eigen::RowVector3i(0, 2, 1));

  const TriMesh same =
      parse_off("OFF 4 1 0\r\n0 0 0\r\n1 0 0\r\n1 1 0\r\n0 1 0\r\n4 0 1 2 3\r\n", "crlf.off");
  CHECK(same.num_triangles() == 2);
  CHECK(
      parse_off("\xEF\xBB\xBFNOFF\n3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n", "n.off")
          .num_triangles() == 1);
}

TEST_CASE("OFF round trip is exact", "[off]") {
  const TriMesh m = odd_mesh();
  const std::string text = format_off(m);
  CHECK(text.rfind("OFF\n42 80 0\n", 0) == 0);
  const TriMesh back = parse_off(text, "ico.off");
  CHECK(bit_equal(back.V, m.V));
  CHECK(back.F == m.F);
  sm::test::TempDir dir;
  write_off(dir / "ico.off", m);
  CHECK(bit_equal(read_off(dir / "ico.off").V, m.V));
}

TEST_CASE("malformed OFF: messages name the line, element and field", "[off][errors]") {
  const std::string head = "OFF\n3 1 0\n0 0 0\n1 0 0\n";
  CHECK(off_error("") == "bad.off: empty file, expected the OFF header");
  CHECK(off_error("PLY\n") == "bad.off:1: expected the header keyword OFF, found 'PLY'");
  CHECK(off_error("4OFF\n") == "bad.off:1: '4OFF': only 3-dimensional OFF is supported");
  CHECK(off_error("OFF BINARY\n") == "bad.off:1: binary OFF is not supported");
  CHECK(off_error("OFF\n") == "bad.off: the file ends before the counts line");
  CHECK(off_error("OFF\n3 x\n") == "bad.off:2: face count 'x' is not a non-negative integer");
  CHECK(off_error("OFF\n0 1 0\n") == "bad.off:2: no vertices (the vertex count is 0)");
  CHECK(off_error("OFF\n3 0 0\n") == "bad.off:2: no faces (the face count is 0)");
  CHECK(off_error(head + "0 1 y\n3 0 1 2\n") ==
        "bad.off:5: vertex 2: coordinate z 'y' is not a number");
  CHECK(off_error(head + "0 1\n3 0 1 2\n") == "bad.off:5: vertex 2: coordinate z is missing");
  CHECK(off_error(head + "0 nan 0\n3 0 1 2\n") ==
        "bad.off:5: vertex 2: coordinate y 'nan' is not finite");
  CHECK(off_error(head) == "bad.off: expected 3 vertices, the file ends after 2");
  CHECK(off_error(head + "0 1 0\n3 0 1 3\n") ==
        "bad.off:6: face 0: corner 3: vertex index 3 is out of range (the file has 3 vertices, "
        "numbered from 0)");
  CHECK(off_error(head + "0 1 0\n3 0 -1 2\n") ==
        "bad.off:6: face 0: corner 2: vertex index -1 is out of range (the file has 3 vertices, "
        "numbered from 0)");
  CHECK(off_error(head + "0 1 0\n2 0 1\n") ==
        "bad.off:6: face 0: a face needs at least 3 corners, found 2");
  CHECK(off_error(head + "0 1 0\n4 0 1 2\n") ==
        "bad.off:6: face 0: expected 4 vertex indices, found 3");
  CHECK(off_error(head + "0 1 0\n3 0 1 a\n") ==
        "bad.off:6: face 0: corner 3: vertex index 'a' is not an integer");
  CHECK(off_error(head + "0 1 0\n") == "bad.off: expected 1 faces, the file ends after 0");
  // Counts are not trusted for allocation: a huge claim fails as a short file.
  CHECK(off_error("OFF\n2000000000 2000000000 0\n0 0 0\n") ==
        "bad.off: expected 2000000000 vertices, the file ends after 1");
}

TEST_CASE("ASCII PLY with extra properties, elements and colours", "[ply]") {
  PlyColors colors;
  const TriMesh m = parse_ply(kAsciiPly, "quads.ply", &colors);
  REQUIRE(m.num_vertices() == 6);
  CHECK(m.V.row(4) == Eigen::RowVector3d(0, 2, 0.5));
  REQUIRE(m.num_triangles() == 4);
  CHECK(m.F.row(1) == Eigen::RowVector3i(0, 2, 3));
  CHECK(m.F.row(3) == Eigen::RowVector3i(3, 5, 4));
  REQUIRE(colors.vertex.size() == 6);
  CHECK(colors.vertex[3] == std::array<uint8_t, 3>{1, 2, 3});
  CHECK(colors.face.empty());
  CHECK(bit_equal(parse_ply(kAsciiPly, "quads.ply").V, m.V));  // colours are optional
}

TEST_CASE("PLY elements without properties are skipped whatever their count", "[ply][errors]") {
  // Found by fuzzing: 2^31-1 items of nothing used to be iterated one by one (a hang).
  for (const char* format : {"ascii", "binary_little_endian"}) {
    std::string data = std::string("ply\nformat ") + format +
                       " 1.0\nelement nothing 2147483647\nelement vertex 3\nproperty float x\n"
                       "property float y\nproperty float z\nelement face 1\n"
                       "property list uchar int vertex_indices\nend_header\n";
    if (std::strcmp(format, "ascii") == 0) {
      data += "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    } else {
      for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(data, v);
      put(data, uint8_t{3});
      for (int32_t i : {0, 1, 2}) put(data, i);
    }
    INFO(format);
    const TriMesh m = parse_ply(data, "empty-element.ply");
    CHECK(m.num_vertices() == 3);
    CHECK(m.F.row(0) == Eigen::RowVector3i(0, 1, 2));
  }
}

TEST_CASE("binary little-endian PLY with float positions and uchar/int lists", "[ply]") {
  std::string data =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nproperty double confidence\n"
      "element face 1\nproperty list uchar uint vertex_indices\n"
      "property float red\nproperty float green\nproperty float blue\nend_header\n";
  const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.25f}, {0, 1, 0}};
  for (const auto& p : xyz) {
    for (float c : p) put(data, c);
    put(data, 0.5);
  }
  put<uint8_t>(data, 4);
  for (uint32_t i : {0u, 1u, 2u, 3u}) put(data, i);
  for (float c : {1.0f, 0.5f, 0.0f}) put(data, c);
  PlyColors colors;
  const TriMesh m = parse_ply(data, "float.ply", &colors);
  REQUIRE(m.num_vertices() == 4);
  CHECK(m.V(2, 2) == 0.25);
  CHECK(m.num_triangles() == 2);
  CHECK(colors.vertex.empty());
  REQUIRE(colors.face.size() == 2);  // one per triangle of the quad
  CHECK(colors.face[1] == std::array<uint8_t, 3>{255, 128, 0});

  // Cut inside the fourth index: vertices, the list count and three indices remain.
  const size_t fourth = data.find("end_header\n") + 11 + 4 * 20 + 1 + 3 * 4;
  CHECK(ply_error(data.substr(0, data.size() - 14)) ==
        "bad.ply: face 0: vertex_indices: the data ends early (binary, byte " +
            std::to_string(fourth) + ")");
  std::string wrong = data;
  wrong[wrong.size() - 3 * 4 - 4 * 4] = 9;  // the first index, before 4 indices and 3 colours
  CHECK(ply_error(wrong) ==
        "bad.ply: face 0: corner 1: vertex index 9 is out of range (the file has 4 vertices, "
        "numbered from 0)");
}

TEST_CASE("PLY round trips: ASCII and binary, with and without colours", "[ply]") {
  const TriMesh m = odd_mesh();
  PlyColors colors;
  for (int i = 0; i < m.num_vertices(); ++i) {
    colors.vertex.push_back({uint8_t(i), uint8_t(255 - i), uint8_t(i * 3)});
  }
  for (int t = 0; t < m.num_triangles(); ++t) {
    colors.face.push_back({uint8_t(t), 7, uint8_t(200 + t / 2)});
  }
  PlyColors only_faces;
  only_faces.face = colors.face;
  for (const bool binary : {false, true}) {
    const PlyColors* const variants[] = {nullptr, &colors, &only_faces};
    for (const PlyColors* c : variants) {
      const std::string data = format_ply(m, c, binary);
      PlyColors back_colors;
      const TriMesh back = parse_ply(data, "rt.ply", &back_colors);
      CHECK(bit_equal(back.V, m.V));
      CHECK(back.F == m.F);
      CHECK(back_colors.vertex == (c ? c->vertex : PlyColors{}.vertex));
      CHECK(back_colors.face == (c ? c->face : PlyColors{}.face));
      CHECK(format_ply(back, &back_colors, binary) == format_ply(m, c, binary));
    }
  }
  const std::string ascii = format_ply(m, &colors);
  CHECK(ascii.rfind(
            "ply\nformat ascii 1.0\ncomment written by seqmassage\nelement vertex 42\n"
            "property double x\nproperty double y\nproperty double z\nproperty uchar red\n"
            "property uchar green\nproperty uchar blue\nelement face 80\n"
            "property list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\n"
            "property uchar blue\nend_header\n0.30000000000000004 ",
            0) == 0);
  sm::test::TempDir dir;
  write_ply(dir / "c.ply", m, &colors, true);
  PlyColors read_colors;
  CHECK(bit_equal(read_ply(dir / "c.ply", &read_colors).V, m.V));
  CHECK(read_colors.face == colors.face);

  PlyColors wrong;
  wrong.vertex.resize(3);
  CHECK(error_of<InputError>([&] { format_ply(m, &wrong); }) ==
        "cannot write PLY: 3 vertex colours for 42 vertices");
}

TEST_CASE("malformed PLY: messages name the header line or element, item and property",
          "[ply][errors]") {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  CHECK(ply_error("") == "bad.ply: not a PLY file (the first line is not 'ply')");
  CHECK(ply_error("OFF\n") == "bad.ply: not a PLY file (the first line is not 'ply')");
  CHECK(ply_error("ply\nformat binary_big_endian 1.0\nend_header\n") ==
        "bad.ply:2: format binary_big_endian is not supported");
  CHECK(ply_error("ply\nformat ascii 1.0\nelement vertex\nend_header\n") ==
        "bad.ply:3: expected 'element <name> <count>' with a count from 0 to 2^31-1");
  CHECK(ply_error("ply\nformat ascii 1.0\nproperty float x\nend_header\n") ==
        "bad.ply:3: property before the first element");
  CHECK(ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\nend_header\n") ==
        "bad.ply:4: unknown property type 'real'");
  CHECK(ply_error("ply\nformat ascii 1.0\nelement f 1\nproperty list float int i\n") ==
        "bad.ply:4: list count type 'float' is not an integer type");
  CHECK(ply_error("ply\nformat ascii 1.0\nelement vertex 1\n") ==
        "bad.ply: the PLY header has no end_header line");
  CHECK(ply_error("ply\nelement vertex 1\nend_header\n") ==
        "bad.ply: the PLY header has no format line");
  CHECK(ply_error("ply\nformat ascii 1.0\nelement vertex 0\nelement face 0\nend_header\n") ==
        "bad.ply: no vertices (no 'vertex' element, or its count is 0)");
  CHECK(ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n") ==
        "bad.ply: no faces (no 'face' element, or its count is 0)");
  CHECK(ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nelement face 1\n"
                  "property list uchar int vertex_indices\nend_header\n") ==
        "bad.ply: the vertex element has no scalar property y");
  CHECK(ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                  "property float z\nelement face 1\nproperty list uchar int corners\n"
                  "end_header\n") ==
        "bad.ply: the face element has no list property vertex_indices");
  CHECK(ply_error(header + "0 0 0\n1 0 0\n0 one 0\n3 0 1 2\n") ==
        "bad.ply:12: vertex 2: y 'one' is not a number");
  CHECK(ply_error(header + "0 0 0\n1 0 0\n0 1 inf\n3 0 1 2\n") ==
        "bad.ply:12: vertex 2: z is not finite");
  CHECK(ply_error(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n") ==
        "bad.ply:13: face 0: vertex_indices '2.5' is not an integer");
  CHECK(ply_error(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n") ==
        "bad.ply:13: face 0: corner 3: vertex index 3 is out of range (the file has 3 vertices, "
        "numbered from 0)");
  CHECK(ply_error(header + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n") ==
        "bad.ply:13: face 0: a face needs at least 3 corners, found 2");
  CHECK(ply_error(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n") ==
        "bad.ply:13: face 0: vertex_indices: the data ends early");
  const std::string huge =
      "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty double x\n"
      "property double y\nproperty double z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  CHECK(ply_error(huge) == "bad.ply: vertex 0: x: the data ends early (binary, byte " +
                               std::to_string(huge.size()) + ")");
  CHECK(ply_error(header + "0 0 0\n1 0 0\n0 1 0\n3 0 x 2\n") ==
        "bad.ply:13: face 0: vertex_indices 'x' is not an integer");
  CHECK(ply_error(header + "0 0 0\n1 0 0\n0 1 0\nx 0 1 2\n") ==
        "bad.ply:13: face 0: vertex_indices count 'x' is not an integer");
}
