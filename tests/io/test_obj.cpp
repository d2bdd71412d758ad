// Reading OBJ: every statement and corner form, line endings, continuations, and the messages of
// malformed files.
#include <catch2/catch.hpp>

#include <string>

#include "io/obj.hpp"
#include "core/errors.hpp"
#include "support/error_of.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
using sm::test::error_of;

namespace {

// A textured quad and a triangle with every kind of non-geometry line.
const char* const kFeatures =
    "# exported by a DCC tool\n"
    "mtllib scene.mtl\n"
    "o Cube\n"
    "v 0 0 0\n"
    "v 1 0 0 1.0\n"
    "v 1 1 0 0.5 0.25 1\n"
    "v 0 1 0\n"
    "v 0.5 0.5 1\n"
    "vt 0 0\n"
    "vt 1 0\n"
    "vt 1 1\n"
    "vt 0 1 0.5\n"
    "vt 0.25\n"
    "vn 0 0 1\n"
    "\n"
    "g side\n"
    "usemtl red\n"
    "s 1\n"
    "f 1/1/1 2/2/1 3/3/1 4/4/1\n"
    "l 1 2\n"
    "p 3\n"
    "vp 0.5\n"
    "s off\n"
    "f 1//1 2//1 5//1\n"
    "f -2/-1 -1/-2 -5/-3\n";

std::string obj_error(const std::string& text) {
  return error_of<InputError>([&] { parse_obj(text, "bad.obj"); });
}

}  // namespace

TEST_CASE("OBJ statements: positions, texture coordinates, normals, polygons", "[obj]") {
  const ObjFile f = parse_obj(kFeatures, "features.obj");
  REQUIRE(f.mesh.num_vertices() == 5);
  CHECK(f.mesh.V(1, 0) == 1.0);
  CHECK(f.mesh.V(4, 2) == 1.0);
  REQUIRE(f.texcoords.rows() == 5);
  CHECK(f.texcoords(3, 1) == 1.0);
  CHECK(f.texcoords(4, 0) == 0.25);
  CHECK(f.texcoords(4, 1) == 0.0);  // a vt with u only
  REQUIRE(f.normals.rows() == 1);
  CHECK(f.normals(0, 2) == 1.0);
  CHECK(f.has_normals());
  CHECK(f.has_texcoords());

  REQUIRE(f.num_faces() == 3);
  CHECK(f.face_offsets == std::vector<int>{0, 4, 7, 10});
  // The quad is fanned from its first corner, and every triangle remembers its face.
  REQUIRE(f.mesh.num_triangles() == 4);
  CHECK(f.mesh.F.row(0) == Eigen::RowVector3i(0, 1, 2));
  CHECK(f.mesh.F.row(1) == Eigen::RowVector3i(0, 2, 3));
  CHECK(f.mesh.F.row(2) == Eigen::RowVector3i(0, 1, 4));
  CHECK(f.mesh.F.row(3) == Eigen::RowVector3i(3, 4, 0));  // -2 -1 -5 of 5 vertices
  CHECK(f.triangle_face == std::vector<int>{0, 0, 1, 2});
  // Corners keep v/vt/vn, -1 where absent; relative vt indices count the 5 vt read so far.
  CHECK(f.corners[2].v == 2);
  CHECK(f.corners[2].vt == 2);
  CHECK(f.corners[2].vn == 0);
  CHECK(f.corners[5].vt == -1);
  CHECK(f.corners[5].vn == 0);
  CHECK(f.corners[7].vt == 4);
  CHECK(f.corners[8].vt == 3);
  CHECK(f.corners[9].vt == 2);
  CHECK(f.corners[9].vn == -1);
}

TEST_CASE("OBJ corner forms v, v/vt, v//vn, v/vt/vn and relative indices", "[obj]") {
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
      "f 1 2 3\n"
      "f 1/1 2/2 3/3\n"
      "f 1//1 2//1 3//1\n"
      "f 1/1/1 2/2/1 3/3/1\n"
      "f -3/-3/-1 -2/-2/-1 -1/-1/-1\n"
      "v 0 0 1\nv 1 0 1\nv 0 1 1\n"
      "f -3 -2 -1\n"
      "f +4 5 6\n";
  const ObjFile f = parse_obj(text, "forms.obj");
  REQUIRE(f.mesh.num_triangles() == 7);
  for (int t = 0; t < 5; ++t) CHECK(f.mesh.F.row(t) == Eigen::RowVector3i(0, 1, 2));
  CHECK(f.mesh.F.row(5) == Eigen::RowVector3i(3, 4, 5));  // relative to the 6 vertices read
  CHECK(f.mesh.F.row(6) == Eigen::RowVector3i(3, 4, 5));
  const auto corner = [&](int face, int k) { return f.corners[f.face_offsets[face] + k]; };
  CHECK((corner(0, 1).vt == -1 && corner(0, 1).vn == -1));
  CHECK((corner(1, 1).vt == 1 && corner(1, 1).vn == -1));
  CHECK((corner(2, 1).vt == -1 && corner(2, 1).vn == 0));
  CHECK((corner(3, 1).vt == 1 && corner(3, 1).vn == 0));
  CHECK((corner(4, 2).v == 2 && corner(4, 2).vt == 2 && corner(4, 2).vn == 0));
}

TEST_CASE("OBJ indices may refer to statements further down", "[obj]") {
  const ObjFile f = parse_obj("f 1/1 2/2 3/3\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n",
                              "forward.obj");
  CHECK(f.mesh.F.row(0) == Eigen::RowVector3i(0, 1, 2));
  CHECK(f.corners[2].vt == 2);
}

TEST_CASE("OBJ line endings, blanks, comments, byte order mark and continuations", "[obj]") {
  const std::string lf = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n";
  const ObjFile ref = parse_obj(lf, "lf.obj");
  const std::string variants[] = {
      "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nv 1 1 0\r\nf 1 2 4 3\r\n",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3",  // no final line break
      "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n",
      "  v\t0 0 0   \n\n\t\nv 1 0 0 # inline comment\nv 0 1 0\t\r\n# f 9 9 9\nv 1 1 0\n"
      "f 1 2 4 3  \t\n",
      "v 0 0 \\\n0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 \\\r\n 4 3\n",
  };
  for (const std::string& text : variants) {
    INFO(text);
    const ObjFile f = parse_obj(text, "variant.obj");
    CHECK(f.mesh.V == ref.mesh.V);
    CHECK(f.mesh.F == ref.mesh.F);
    CHECK(format_obj(f, f.mesh.V) == text);  // unchanged positions: the same bytes
  }
  // A comment ending in a backslash does not swallow the next line.
  CHECK(parse_obj("# C:\\meshes\\\n" + lf, "c.obj").mesh.num_vertices() == 4);
  // Line numbers in messages count physical lines, including joined ones.
  CHECK(obj_error("v 0 0 \\\n0\r\nv 1 0 0\r\n\r\nv 0 x 0\r\n") ==
        "bad.obj:5: v: coordinate y 'x' is not a number");
}

TEST_CASE("OBJ degenerate faces are not an error when reading", "[obj]") {
  const ObjFile f = parse_obj("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n", "flat.obj");
  CHECK(f.mesh.num_triangles() == 2);
}

TEST_CASE("malformed OBJ: messages name the file, the line and the field", "[obj][errors]") {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  CHECK(obj_error("v 0 0 0\nv 1 abc 0\n") == "bad.obj:2: v: coordinate y 'abc' is not a number");
  CHECK(obj_error("v 0 0 nan\n") == "bad.obj:1: v: coordinate z 'nan' is not finite");
  CHECK(obj_error("v -inf 0 0\n") == "bad.obj:1: v: coordinate x '-inf' is not finite");
  CHECK(obj_error("v 1e999 0 0\n") == "bad.obj:1: v: coordinate x '1e999' is not finite");
  CHECK(obj_error("v 1,5 0 0\n") == "bad.obj:1: v: coordinate x '1,5' is not a number");
  CHECK(obj_error("v 0 0\n") == "bad.obj:1: v: expected 3 coordinates (x y z), found 2");
  CHECK(obj_error("v 0 0 0 1 red\n") ==
        "bad.obj:1: v: extra value 2 (w or colour) 'red' is not a number");
  CHECK(obj_error(tri + "vt 0 x\n") == "bad.obj:4: vt: coordinate v 'x' is not a number");
  CHECK(obj_error(tri + "vt\n") == "bad.obj:4: vt: expected 1 to 3 values (u v w), found 0");
  CHECK(obj_error(tri + "vt 0 0 0 0\n") ==
        "bad.obj:4: vt: expected 1 to 3 values (u v w), found 4");
  CHECK(obj_error(tri + "vn 0 1\n") == "bad.obj:4: vn: expected 3 values (x y z), found 2");
  CHECK(obj_error(tri + "vn 0 1 0 1\n") == "bad.obj:4: vn: expected 3 values (x y z), found 4");
  CHECK(obj_error(tri + "vn 0 1 inf\n") == "bad.obj:4: vn: coordinate z 'inf' is not finite");

  CHECK(obj_error(tri + "f 1 0 3\n") ==
        "bad.obj:4: f: corner 2 '0': vertex index 0 is invalid (OBJ indices start at 1)");
  CHECK(obj_error(tri + "f 1 2 4\n") ==
        "bad.obj:4: f: corner 3 '4': vertex index 4 is out of range (the file has 3 vertices)");
  CHECK(obj_error(tri + "f 1 2 -4\n") ==
        "bad.obj:4: f: corner 3 '-4': relative vertex index -4 is out of range (3 vertices "
        "defined before this line)");
  CHECK(obj_error(tri + "vt 0 0\nf 1/1 2/2 3/3\n") ==
        "bad.obj:5: f: corner 2 '2/2': texture coordinate index 2 is out of range (the file has "
        "1 texture coordinates)");
  CHECK(obj_error(tri + "f 1//1 2//1 3//1\n") ==
        "bad.obj:4: f: corner 1 '1//1': normal index 1 is out of range (the file has 0 normals)");
  CHECK(obj_error(tri + "f 1/0 2/1 3/1\nvt 0 0\n") ==
        "bad.obj:4: f: corner 1 '1/0': texture coordinate index 0 is invalid (OBJ indices start "
        "at 1)");
  CHECK(obj_error(tri + "f 1 2 x\n") ==
        "bad.obj:4: f: corner 3 'x': vertex index 'x' is not an integer");
  CHECK(obj_error(tri + "f 1 2 3.0\n") ==
        "bad.obj:4: f: corner 3 '3.0': vertex index '3.0' is not an integer");
  CHECK(obj_error(tri + "f 1 2 99999999999\n") ==
        "bad.obj:4: f: corner 3 '99999999999': vertex index 99999999999 is out of range");
  for (const char* corner : {"3/1/1/1", "3/", "/3", "3//"}) {
    CHECK(obj_error(tri + "vt 0 0\nvn 0 0 1\nf 1 2 " + corner + "\n") ==
          "bad.obj:6: f: corner 3 '" + std::string(corner) +
              "': expected v, v/vt, v//vn or v/vt/vn");
  }
  CHECK(obj_error(tri + "f 1 2\n") == "bad.obj:4: f: a face needs at least 3 corners, found 2");
  CHECK(obj_error(tri + "f\n") == "bad.obj:4: f: a face needs at least 3 corners, found 0");
  CHECK(obj_error(tri + "vt 0 0\nf 1/1 2/1 3\n") ==
        "bad.obj:5: f: corner 3 '3' has the form v but corner 1 '1/1' has the form v/vt");
  CHECK(obj_error(tri + "vt 0 0\nvn 0 0 1\nf 1/1/1 2//1 3/1/1\n") ==
        "bad.obj:6: f: corner 2 '2//1' has the form v//vn but corner 1 '1/1/1' has the form "
        "v/vt/vn");

  CHECK(obj_error("") == "bad.obj: no vertices (no 'v' statement)");
  CHECK(obj_error("# only a comment\r\n\r\n") == "bad.obj: no vertices (no 'v' statement)");
  CHECK(obj_error(tri) == "bad.obj: no faces (no 'f' statement)");
}

TEST_CASE("read_obj names the path in its messages", "[obj][errors]") {
  sm::test::TempDir dir;
  const auto missing = dir / "missing.obj";
  const std::string io = error_of<IoError>([&] { read_obj(missing); });
  CHECK(io.find(missing.string()) != std::string::npos);
  const auto bad = dir / "bad.obj";
  write_obj(bad, parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "t.obj"), Positions::Zero(3, 3));
  const ObjFile f = read_obj(bad);
  CHECK(f.name == bad.string());
  CHECK(error_of<InputError>([&] { format_obj(f, Positions::Zero(2, 3)); }) ==
        "cannot write OBJ '" + bad.string() + "': 2 positions given for 3 vertices");
  Positions V = Positions::Zero(3, 3);
  V(1, 2) = std::nan("");
  CHECK(error_of<InputError>([&] { format_obj(f, V); }) ==
        "cannot write OBJ '" + bad.string() + "': vertex 2 has a non-finite coordinate");
}
