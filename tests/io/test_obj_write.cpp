// Writing OBJ back with new positions: only v (and vn) lines change, positions round-trip
// exactly, polygons stay polygons, normals follow the new shape.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io/obj.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"
#include "support/error_of.hpp"
#include "support/temp_dir.hpp"

using namespace sm;

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  size_t pos = 0;
  while (pos < text.size()) {
    const size_t nl = text.find('\n', pos);
    const size_t end = nl == std::string::npos ? text.size() : nl + 1;
    lines.push_back(text.substr(pos, end - pos));
    pos = end;
  }
  return lines;
}

bool bit_equal(const Positions& a, const Positions& b) {
  return a.rows() == b.rows() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

const char* const kTextured =
    "# textured, with materials and groups\r\n"
    "mtllib scene.mtl\r\n"
    "o Sheet\r\n"
    "v 0 0 0\r\n"
    "v 1 0 0 1.0 # w\r\n"
    "v 2 0 0 0.5 0.25 1\r\n"
    "v 0 1 0\r\n"
    "v 1 1 0\r\n"
    "v 2 1 0\r\n"
    "vt 0 0\r\n"
    "vt 0.5 0\r\n"
    "vt 1 0\r\n"
    "vt 0 1\r\n"
    "vt 0.5 1\r\n"
    "vt 1 1\r\n"
    "g left\r\n"
    "usemtl red\r\n"
    "s 1\r\n"
    "f 1/1 2/2 5/5 4/4\r\n"
    "g right\r\n"
    "usemtl blue\r\n"
    "f -5/-5 -4/-4 -1/-1 -2/-2\r\n"
    "l 1 3\r\n";

}  // namespace

TEST_CASE("new positions change only the v lines; quads stay quads", "[obj][write]") {
  const ObjFile f = parse_obj(kTextured, "sheet.obj");
  REQUIRE(f.mesh.num_triangles() == 4);
  CHECK(f.triangle_face == std::vector<int>{0, 0, 1, 1});
  Positions V = f.mesh.V;
  V.col(2).array() += 0.125;
  V(3, 2) = f.mesh.V(3, 2);  // vertex 4 stays where it was
  const std::string out = format_obj(f, V);

  const auto in_lines = lines_of(kTextured), out_lines = lines_of(out);
  REQUIRE(in_lines.size() == out_lines.size());
  for (size_t k = 0; k < in_lines.size(); ++k) {
    INFO(in_lines[k]);
    const bool vertex = in_lines[k].rfind("v ", 0) == 0;
    const bool moved = vertex && in_lines[k] != "v 0 1 0\r\n";
    CHECK((out_lines[k] != in_lines[k]) == moved);
  }
  CHECK(out_lines[4] == "v 1 0 0.125 1.0 # w\r\n");  // w and comment kept, CRLF kept
  CHECK(out_lines[5] == "v 2 0 0.125 0.5 0.25 1\r\n");
  CHECK(out_lines[6] == "v 0 1 0\r\n");  // unchanged position: the line as read

  const ObjFile back = parse_obj(out, "back.obj");
  CHECK(bit_equal(back.mesh.V, V));
  CHECK(back.mesh.F == f.mesh.F);
  CHECK(back.texcoords == f.texcoords);
  CHECK(back.num_faces() == 2);  // written as the two quads that were read
}

TEST_CASE("a moved statement written on several lines becomes one line", "[obj][write]") {
  const ObjFile f = parse_obj(
      "v 0 0 \\\r\n0 1 # w\r\nv 1 0 0\r\nv 0 1 0\r\nvn 0 \\\r\n0 1 # up\r\nf 1//1 2//1 3//1\r\n",
      "joined.obj");
  CHECK(f.mesh.V(0, 2) == 0.0);
  Positions V = f.mesh.V;
  V(0, 0) = -1;
  CHECK(format_obj(f, V) ==
        "v -1 0 0 1 # w\r\nv 1 0 0\r\nv 0 1 0\r\nvn 0 0 1 # up\r\nf 1//1 2//1 3//1\r\n");
}

TEST_CASE("positions round-trip bit-exactly", "[obj][write]") {
  TriMesh m;
  m.V.resize(6, 3);
  // Up to 1e18 in magnitude: readers refuse larger coordinates (core/coordinate_limit.hpp).
  m.V << 0.1, -0.0, 1e-300, 5e-324, 1e18, -M_PI,                                     //
      1.0 / 3.0, 2.5e-7, -9.87654321e17, 123456789.123456789, -1e-5, 0.30000000000000004,  //
      0, 0, 0, 1, 1, 1;
  std::mt19937_64 rng(7);
  for (int i = 4; i < 6; ++i) {
    for (int c = 0; c < 3; ++c) {
      uint64_t bits;
      do {
        bits = rng();
        std::memcpy(&m.V(i, c), &bits, sizeof bits);
      } while (!(std::abs(m.V(i, c)) <= 1e18));  // finite, within the readers' limit
    }
  }
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 3, 4, 5;
  const std::string text = format_obj(m);
  const ObjFile f = parse_obj(text, "exact.obj");
  CHECK(bit_equal(f.mesh.V, m.V));
  CHECK(std::signbit(f.mesh.V(0, 1)));
  CHECK(f.mesh.F == m.F);
  CHECK(format_obj(f, f.mesh.V) == text);
  CHECK(text.substr(0, 25) == "v 0.1 -0 1e-300\nv 5e-324 ");
  // Through the file-preserving writer too: every position moved, read back exactly.
  Positions V = m.V;
  V.row(0).swap(V.row(1));
  CHECK(bit_equal(parse_obj(format_obj(f, V), "again.obj").mesh.V, V));
}

TEST_CASE("written files are a fixed point: rewriting them changes the same lines",
          "[obj][write]") {
  const ObjFile f = parse_obj(kTextured, "sheet.obj");
  Positions V2 = f.mesh.V, V3 = f.mesh.V;
  V2.col(1).array() *= 1.5;
  V3.col(0).array() -= 0.7;
  const std::string once = format_obj(f, V2);
  CHECK(format_obj(parse_obj(once, "once.obj"), V3) == format_obj(f, V3));
  CHECK(format_obj(parse_obj(once, "once.obj"), V2) == once);
}

TEST_CASE("normals are recomputed from the new positions through the corners", "[obj][write]") {
  SECTION("one vn per position: sm::vertex_normals of the new shape") {
    const TriMesh grid = make_grid(4, 3, 2.0, 1.5);
    std::string text;
    for (int i = 0; i < grid.num_vertices(); ++i) {
      text += "v " + std::to_string(grid.V(i, 0)) + " " + std::to_string(grid.V(i, 1)) + " 0\n";
    }
    for (int i = 0; i < grid.num_vertices(); ++i) text += "vn 0 0 1\n";
    for (int t = 0; t < grid.num_triangles(); ++t) {
      text += "f";
      for (int k = 0; k < 3; ++k) {
        const std::string idx = std::to_string(grid.F(t, k) + 1);
        text += " " + idx + "//" + idx;
      }
      text += "\n";
    }
    const ObjFile f = parse_obj(text, "grid.obj");
    TriMesh bent{f.mesh.V, f.mesh.F};
    for (int i = 0; i < bent.num_vertices(); ++i) {
      bent.V(i, 2) = 0.3 * bent.V(i, 0) * bent.V(i, 0) - 0.2 * bent.V(i, 1);
    }
    const ObjFile out = parse_obj(format_obj(f, bent.V), "bent.obj");
    CHECK(bit_equal(out.normals, vertex_normals(bent)));
  }
  SECTION("a vn shared by the corners of a flat face stays the face normal (hard edges)") {
    const char* const roof =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 2 0\nv 1 2 0\n"
        "vn 0 0 1\nvn 0 0 1\nvn 1 0 0\n"
        "f 1//1 2//1 3//1 4//1\nf 4//2 3//2 6//2 5//2\n";
    const ObjFile f = parse_obj(roof, "roof.obj");
    Positions V = f.mesh.V;
    V(4, 2) = V(5, 2) = 1.0;  // the second quad is folded up by 45 degrees
    const ObjFile out = parse_obj(format_obj(f, V), "roof2.obj");
    const double s = std::sqrt(0.5);
    CHECK(out.normals(0, 2) == 1.0);
    CHECK(out.normals(1, 1) == Approx(-s));
    CHECK(out.normals(1, 2) == Approx(s));
    CHECK(lines_of(format_obj(f, V))[8] == "vn 1 0 0\n");  // used by no face: kept
  }
  SECTION("unchanged positions keep the normals as read") {
    const char* const text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0.1 0.2 0.9\nf 1//1 2//1 3//1\n";
    const ObjFile f = parse_obj(text, "same.obj");
    CHECK(format_obj(f, f.mesh.V) == text);
  }
  SECTION("a vn whose triangles all have zero area is kept") {
    const char* const text =
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nvn 0 0 1\nvn 0.6 0.8 0 # authored\n"
        "f 1//1 2//1 3//1\nf 4//2 4//2 4//2\n";
    const ObjFile f = parse_obj(text, "zero.obj");
    Positions V = f.mesh.V;
    V(1, 1) = 0.5;
    V(3, 0) = 6;
    const auto out = lines_of(format_obj(f, V));
    CHECK(out[1] == "v 1 0.5 0\n");
    CHECK(out[3] == "v 6 5 5\n");
    CHECK(out[4] == "vn 0 0 1\n");  // recomputed: still +z
    CHECK(out[5] == "vn 0.6 0.8 0 # authored\n");
  }
}

TEST_CASE("plain OBJ of a triangle mesh", "[obj][write]") {
  TriMesh m;
  m.V.resize(3, 3);
  m.V << 0, 0, 0, 1.5, 0, 0, 0, 0.25, -2;
  m.F.resize(1, 3);
  m.F << 0, 1, 2;
  CHECK(format_obj(m) == "v 0 0 0\nv 1.5 0 0\nv 0 0.25 -2\nf 1 2 3\n");
  sm::test::TempDir dir;
  write_obj(dir / "plain.obj", m);
  const ObjFile f = read_obj(dir / "plain.obj");
  CHECK(f.mesh.V == m.V);
  CHECK(f.mesh.F == m.F);
  m.F(0, 2) = 3;
  CHECK(sm::test::error_of<InputError>([&] { format_obj(m); }) ==
        "cannot write OBJ: triangle 0 refers to vertex 3, but the mesh has 3 vertices");
}

TEST_CASE("a large generated OBJ parses in one linear pass", "[obj][large]") {
  // 548 x 548 = 300,304 vertices, 598,002 triangles, about 20 MB of text.
  const TriMesh grid = make_grid(547, 547, 1.0, 1.0);
  const std::string text = format_obj(grid);
  const ObjFile f = parse_obj(text, "large.obj");
  REQUIRE(f.mesh.num_vertices() == 300304);
  CHECK(f.mesh.num_triangles() == grid.num_triangles());
  CHECK(bit_equal(f.mesh.V, grid.V));
  CHECK(f.mesh.F == grid.F);
  CHECK(format_obj(f, f.mesh.V) == text);
}

TEST_CASE("captured frames and quad meshes of the shared data round-trip", "[obj][data]") {
  const std::filesystem::path data = SEQMASSAGE_SHARED_DATA_DIR;
  const auto crane = data / "sequences/vlasic_crane/frame_0000.obj";
  const auto quads = data / "static/fandisk/pmp_fandisk_quads.obj";
  if (!std::filesystem::exists(crane) || !std::filesystem::exists(quads)) {
    WARN("shared data not found under " << data.string() << ": test skipped");
    return;
  }
  const ObjFile frame = read_obj(crane);
  CHECK(frame.mesh.num_vertices() == 10002);
  CHECK(frame.mesh.num_triangles() == 20000);
  const ObjFile q = read_obj(quads);
  CHECK(q.num_faces() == 764);
  CHECK(q.mesh.num_triangles() == 2 * 764);
  for (const ObjFile* f : {&frame, &q}) {
    CHECK(format_obj(*f, f->mesh.V) == f->text);
    Positions V = f->mesh.V * 2.0;
    const ObjFile back = parse_obj(format_obj(*f, V), "scaled.obj");
    CHECK(bit_equal(back.mesh.V, V));
    CHECK(back.face_offsets == f->face_offsets);
  }
}
