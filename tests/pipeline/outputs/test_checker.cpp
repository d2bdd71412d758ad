// The checker output's texture coordinates and texture: the input's own UVs by fan triangulation,
// charts by normal axis (consistent per triangle, never mirrored, split at chart borders), the
// choice between them, and the checkerboard image.
#include <catch2/catch.hpp>

#include "io/obj.hpp"
#include "mesh/primitives.hpp"
#include "pipeline/outputs/checker.hpp"

using namespace sm;

namespace {

double uv_area(const CornerUv& uv, Eigen::Index t) {
  const Eigen::RowVector2d a = uv.uv.row(uv.faces(t, 0)), b = uv.uv.row(uv.faces(t, 1)),
                           c = uv.uv.row(uv.faces(t, 2));
  return 0.5 * ((b - a)[0] * (c - a)[1] - (b - a)[1] * (c - a)[0]);
}

}  // namespace

TEST_CASE("input texture coordinates follow the OBJ's fan triangulation") {
  const ObjFile obj = parse_obj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
      "f 1/1 2/2 3/3 4/4\nf 2/5 5/2 3/3\n",
      "quad.obj");
  const std::optional<CornerUv> uv = input_uv(obj, obj.mesh.F);
  REQUIRE(uv);
  CHECK(uv->source == "input");
  CHECK(uv->uv == obj.texcoords);
  Triangles expected(3, 3);
  expected << 0, 1, 2, 0, 2, 3, 4, 1, 2;
  CHECK(uv->faces == expected);

  const ObjFile partial =
      parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n", "p.obj");
  CHECK_FALSE(input_uv(partial, partial.mesh.F));  // a face without vt
  const ObjFile none = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "n.obj");
  CHECK_FALSE(input_uv(none, none.mesh.F));
  Triangles other = obj.mesh.F;
  other(0, 0) = 4;
  CHECK_FALSE(input_uv(obj, other));  // not the template's triangles
}

TEST_CASE("charts by normal axis: one chart per triangle, never mirrored, split at borders") {
  for (const TriMesh& mesh :
       {make_icosphere(2, 1.0), make_box(3, 1.0, 2.0, 0.5), make_torus(24, 12, 1.0, 0.3)}) {
    const CornerUv uv = chart_uv(mesh, 0.5);
    CHECK(uv.source == "charts");
    REQUIRE(uv.faces.rows() == mesh.F.rows());
    CHECK(uv.uv.rows() > mesh.V.rows());  // vertices on chart borders have several rows
    CHECK(uv.uv.minCoeff() >= 0.0);
    const double scale = 1.0 / (0.5 * 0.5);  // model area -> uv area
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t) {
      // The chart's projection keeps orientation: the uv area is the model area times the
      // (positive) dominant normal component.
      const Vec3 a = mesh.V.row(mesh.F(t, 0)), b = mesh.V.row(mesh.F(t, 1)),
                 c = mesh.V.row(mesh.F(t, 2));
      const Vec3 n = (b - a).cross(c - a);
      const double area = 0.5 * n.norm();
      const double dominant = n.cwiseAbs().maxCoeff() / n.norm();
      CHECK(uv_area(uv, t) == Approx(area * dominant * scale).epsilon(1e-9));
    }
    // A uv row belongs to one vertex.
    std::vector<int> vertex_of(size_t(uv.uv.rows()), -1);
    for (Eigen::Index t = 0; t < mesh.F.rows(); ++t)
      for (int k = 0; k < 3; ++k) {
        int& owner = vertex_of[size_t(uv.faces(t, k))];
        CHECK((owner < 0 || owner == mesh.F(t, k)));
        owner = mesh.F(t, k);
      }
  }
}

TEST_CASE("a flat grid is one chart: the projection is the positions scaled") {
  TriMesh grid = make_grid(4, 3, 2.0, 1.5);
  grid.V.col(0).array() += 7.0;
  const CornerUv uv = chart_uv(grid, 2.0);
  CHECK(uv.uv.rows() == grid.V.rows());
  for (Eigen::Index t = 0; t < grid.F.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Eigen::RowVector3d p = grid.V.row(grid.F(t, k));
      CHECK(uv.uv(uv.faces(t, k), 0) == Approx((p[0] - 7.0) / 2.0));
      CHECK(uv.uv(uv.faces(t, k), 1) == Approx((p[1] - grid.V.col(1).minCoeff()) / 2.0));
    }
}

TEST_CASE("template_uv prefers the template's own coordinates unless charts are asked for") {
  const ObjFile obj = parse_obj(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.2 0.2\nvt 0.8 0.2\nvt 0.2 0.8\nf 1/1 2/2 3/3\n", "t.obj");
  CheckerOutputOptions options;
  CHECK(template_uv(obj.mesh, &obj, options).source == "input");
  CHECK(template_uv(obj.mesh, nullptr, options).source == "charts");
  options.uv = CheckerUvSource::Charts;
  const CornerUv charts = template_uv(obj.mesh, &obj, options);
  CHECK(charts.source == "charts");
  // period = cells × cell_size × mean edge length
  const double period = 8 * 4.0 * mean_edge_length(obj.mesh);
  CHECK(charts.uv(charts.faces(0, 1), 0) == Approx(1.0 / period));
}

TEST_CASE("the checkerboard texture alternates squares, light at the top left") {
  const Image8 image = checker_texture(8);
  CHECK(image.width == 256);
  CHECK(image.height == 256);
  CHECK(image.channels == 3);
  const auto pixel = [&](int x, int y) {
    const size_t at = (size_t(y) * 256 + size_t(x)) * 3;
    return std::array<uint8_t, 3>{image.pixels[at], image.pixels[at + 1], image.pixels[at + 2]};
  };
  const std::array<uint8_t, 3> light{235, 235, 235}, dark{45, 50, 70};
  CHECK(pixel(0, 0) == light);
  CHECK(pixel(31, 31) == light);
  CHECK(pixel(32, 0) == dark);
  CHECK(pixel(0, 32) == dark);
  CHECK(pixel(32, 32) == light);
  CHECK(pixel(255, 255) == light);
  CHECK(checker_texture(64).width == 512);  // at least 8 pixels per square
  CHECK(checker_texture(1).width == 256);
}
