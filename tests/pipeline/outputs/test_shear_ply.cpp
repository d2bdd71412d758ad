// Shear colours (the paper's Figure 4): the blue-red scale at its stops and in between, the
// fixed range, and both PLY layouts read back by the PLY reader with the colours they should have.
#include <catch2/catch.hpp>

#include "geometry/shear.hpp"
#include "io/ply.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"
#include "pipeline/outputs/shear_ply.hpp"

using namespace sm;
using Rgb = std::array<uint8_t, 3>;

TEST_CASE("the blue-red scale: blue, cyan, green, yellow, red, linear in between") {
  CHECK(scale_color(0.0) == Rgb{0, 0, 255});
  CHECK(scale_color(0.25) == Rgb{0, 255, 255});
  CHECK(scale_color(0.5) == Rgb{0, 255, 0});
  CHECK(scale_color(0.75) == Rgb{255, 255, 0});
  CHECK(scale_color(1.0) == Rgb{255, 0, 0});
  CHECK(scale_color(0.125) == Rgb{0, 128, 255});  // 127.5 rounds up
  CHECK(scale_color(0.6) == Rgb{102, 255, 0});
  CHECK(scale_color(-3.0) == scale_color(0.0));
  CHECK(scale_color(7.0) == scale_color(1.0));
  CHECK(scale_color(std::nan("")) == scale_color(1.0));
}

TEST_CASE("shear maps to the scale by a fixed maximum; degenerate triangles are red") {
  CHECK(shear_scale_position(0.0, 0.1) == 0.0);
  CHECK(shear_scale_position(0.05, 0.1) == 0.5);
  CHECK(shear_scale_position(0.3, 0.1) == 1.0);
  CHECK(shear_scale_position(INFINITY, 0.1) == 1.0);
  CHECK(shear_color(0.025, 0.1) == Rgb{0, 255, 255});
  CHECK(shear_color(INFINITY, 0.1) == Rgb{255, 0, 0});
}

TEST_CASE("per-face PLY: split vertices carry their triangle's colour, as do the faces") {
  const TriMesh templ = make_icosphere(1, 1.0);
  TriMesh frame = templ;
  for (Eigen::Index i = 0; i < frame.V.rows(); ++i) frame.V(i, 0) *= 1.0 + 0.05 * (i % 4);
  const Eigen::VectorXd shear = shear_distortion(templ.V, frame.V, templ.F);
  const std::string ply = format_shear_ply(frame.V, frame.F, shear, 0.1, ShearColorMode::Faces);
  CHECK(ply.find("format binary_little_endian 1.0") != std::string::npos);
  PlyColors colors;
  const TriMesh back = parse_ply(ply, "faces.ply", &colors);
  const Eigen::Index m = templ.F.rows();
  REQUIRE(back.num_vertices() == 3 * m);
  REQUIRE(back.num_triangles() == m);
  REQUIRE(colors.face.size() == size_t(m));
  REQUIRE(colors.vertex.size() == size_t(3 * m));
  int distinct = 0;
  for (Eigen::Index t = 0; t < m; ++t) {
    const Rgb expected = shear_color(shear[t], 0.1);
    CHECK(colors.face[size_t(t)] == expected);
    distinct += t > 0 && expected != colors.face[size_t(t - 1)];
    for (int k = 0; k < 3; ++k) {
      CHECK(back.F(t, k) == 3 * t + k);
      CHECK(colors.vertex[size_t(3 * t + k)] == expected);
      CHECK(back.V.row(3 * t + k) == frame.V.row(frame.F(t, k)));
    }
  }
  CHECK(distinct > 5);  // the test mesh is not uniformly distorted
}

TEST_CASE("per-vertex PLY: the mesh's own vertices, coloured by the mean of their triangles") {
  const TriMesh mesh = make_grid(2, 1, 2.0, 1.0);  // 6 vertices, 4 triangles
  Eigen::VectorXd shear(4);
  shear << 0.0, 0.1, 0.05, INFINITY;
  PlyColors colors;
  const TriMesh back = parse_ply(
      format_shear_ply(mesh.V, mesh.F, shear, 0.2, ShearColorMode::Vertices), "v.ply", &colors);
  CHECK(back.V == mesh.V);
  CHECK(back.F == mesh.F);
  for (Eigen::Index t = 0; t < 4; ++t) CHECK(colors.face[size_t(t)] == shear_color(shear[t], 0.2));
  const double position[4] = {0.0, 0.5, 0.25, 1.0};
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    double sum = 0;
    int count = 0;
    for (Eigen::Index t = 0; t < 4; ++t)
      for (int k = 0; k < 3; ++k)
        if (mesh.F(t, k) == v) sum += position[t], ++count;
    REQUIRE(count > 0);
    CHECK(colors.vertex[size_t(v)] == scale_color(sum / count));
  }
}

TEST_CASE("shear PLY refuses sizes that disagree") {
  const TriMesh mesh = make_grid(1, 1, 1.0, 1.0);
  CHECK_THROWS_WITH(
      format_shear_ply(mesh.V, mesh.F, Eigen::VectorXd::Zero(3), 0.1, ShearColorMode::Faces),
      Catch::Contains("3 values for 2 triangles"));
  CHECK_THROWS_AS(
      format_shear_ply(mesh.V, mesh.F, Eigen::VectorXd::Zero(2), 0.0, ShearColorMode::Faces),
      InputError);
}
