// Textured OBJ + MTL (the checker output): read back by the OBJ reader with the same positions,
// texture coordinates and corners; bad sizes and indices refused.
#include <catch2/catch.hpp>

#include "io/obj.hpp"
#include "io/obj_textured.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

TEST_CASE("a textured OBJ reads back with its positions, texture coordinates and corners") {
  const TriMesh grid = make_grid(3, 2, 1.5, 1.0);
  TexCoords uv(grid.V.rows() + 1, 2);
  for (Eigen::Index i = 0; i < grid.V.rows(); ++i) uv.row(i) << grid.V(i, 0) / 3.0, -grid.V(i, 1);
  uv.row(grid.V.rows()) << 0.1, 0.7;  // unused by any corner: still written
  Triangles uv_faces = grid.F;
  uv_faces(2, 1) = int(grid.V.rows());  // a corner with its own texture coordinate
  const std::string text =
      format_textured_obj(grid.V, grid.F, uv, uv_faces, "checker.mtl", "checker", "two\nlines");
  CHECK(text.rfind("# two\n# lines\nmtllib checker.mtl\nv ", 0) == 0);
  CHECK(text.find("\nusemtl checker\nf ") != std::string::npos);
  const ObjFile back = parse_obj(text, "textured.obj");
  CHECK(back.mesh.V == grid.V);
  CHECK(back.mesh.F == grid.F);
  CHECK(back.texcoords == uv);
  for (Eigen::Index t = 0; t < grid.F.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const ObjCorner& c = back.corners[size_t(3 * t + k)];
      CHECK(c.v == grid.F(t, k));
      CHECK(c.vt == uv_faces(t, k));
      CHECK(c.vn == -1);
    }
  CHECK(format_textured_obj(grid.V, grid.F, uv, uv_faces, "checker.mtl", "checker", "two\nlines") ==
        text);
}

TEST_CASE("a textured OBJ refuses sizes and indices that disagree") {
  const TriMesh grid = make_grid(2, 2, 1.0, 1.0);
  TexCoords uv = grid.V.leftCols(2);
  CHECK_THROWS_WITH(format_textured_obj(grid.V, grid.F, uv, grid.F.topRows(2), "m", "m"),
                    Catch::Contains("2 texture triangles for"));
  Triangles bad = grid.F;
  bad(1, 2) = int(uv.rows());
  CHECK_THROWS_WITH(format_textured_obj(grid.V, grid.F, uv, bad, "m", "m"),
                    Catch::Contains("triangle 2 refers to texture coordinate"));
  Positions nan = grid.V;
  nan(0, 1) = std::nan("");
  CHECK_THROWS_AS(format_textured_obj(nan, grid.F, uv, grid.F, "m", "m"), InputError);
}

TEST_CASE("the MTL names its material and texture") {
  CHECK(format_texture_mtl("checker", "checker.png") ==
        "# written by seqmassage\nnewmtl checker\nKa 1 1 1\nKd 1 1 1\nKs 0 0 0\nd 1\nillum 1\n"
        "map_Kd checker.png\n");
}
