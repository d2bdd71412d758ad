// The synthetic drifted sequence: deterministic, on the tube's surface, undrifted at frame 0 and
// at both ends, written as OBJ files that read back exactly.
#include <catch2/catch.hpp>
#include <cmath>

#include "io/obj.hpp"
#include "core/errors.hpp"
#include "pipeline/sequence/synthetic.hpp"
#include "support/temp_dir.hpp"

using namespace sm;

namespace {

SyntheticOptions small_config() {
  SyntheticOptions c;
  c.frames = 5;
  c.segments = 12;
  c.rings = 10;
  return c;
}

// Largest distance of the vertices to the smooth tube bent with curvature kappa (kappa > 0).
double distance_to_bent_tube(const Positions& V, double kappa, double r) {
  double d = 0.0;
  for (int i = 0; i < V.rows(); ++i) {
    const double rho = std::hypot(V(i, 0) + 1.0 / kappa, V(i, 2));
    d = std::max(d, std::abs(std::hypot(rho - 1.0 / kappa, V(i, 1)) - r));
  }
  return d;
}

}  // namespace

TEST_CASE("the synthetic sequence is deterministic") {
  const SyntheticSequence a = make_synthetic_sequence(small_config());
  const SyntheticSequence b = make_synthetic_sequence(small_config());
  CHECK(a.F == b.F);
  CHECK(a.uv == b.uv);
  for (int t = 0; t < 5; ++t) {
    CHECK(synthetic_frame(a, t).drifted == synthetic_frame(b, t).drifted);
    CHECK(synthetic_frame(a, t).clean == synthetic_frame(b, t).clean);
  }
  SyntheticOptions other = small_config();
  other.seed = 2;
  CHECK(synthetic_frame(make_synthetic_sequence(other), 4).drifted !=
        synthetic_frame(a, 4).drifted);
}

TEST_CASE("frame 0 is the straight, undrifted tube") {
  const SyntheticSequence seq = make_synthetic_sequence(small_config());
  const SyntheticFrame f = synthetic_frame(seq, 0);
  CHECK(f.clean == seq.rest.V);
  CHECK(f.drifted == seq.rest.V);
  CHECK(seq.rest.num_vertices() == 12 * 11);
  CHECK(seq.F.rows() == 2 * 12 * 10);
}

TEST_CASE("drifted vertices slide on the bent tube's surface, not at its ends") {
  const SyntheticOptions c = small_config();
  const SyntheticSequence seq = make_synthetic_sequence(c);
  const SyntheticFrame last = synthetic_frame(seq, c.frames - 1);
  const double kappa = c.bend * M_PI / 180.0 / c.length;
  const double h = c.length / c.rings;
  CHECK(distance_to_bent_tube(last.clean, kappa, c.radius) < 1e-12);
  CHECK(distance_to_bent_tube(last.drifted, kappa, c.radius) < 1e-12);
  const Eigen::VectorXd moved = (last.drifted - last.clean).rowwise().norm();
  CHECK(moved.maxCoeff() > 0.2 * h);
  CHECK(moved.maxCoeff() < 2.0 * c.drift * h);
  for (int i = 0; i < c.segments; ++i) {
    CHECK(moved[i] < 1e-12);                         // first ring
    CHECK(moved[c.rings * c.segments + i] < 1e-12);  // last ring
  }
}

TEST_CASE("texture coordinates have their own seam column") {
  const SyntheticSequence seq = make_synthetic_sequence(small_config());
  CHECK(seq.uv.rows() == 13 * 11);
  for (int t = 0; t < seq.F_uv.rows(); ++t) {
    double lo = 1.0, hi = 0.0;
    for (int c = 0; c < 3; ++c) {
      lo = std::min(lo, seq.uv(seq.F_uv(t, c), 0));
      hi = std::max(hi, seq.uv(seq.F_uv(t, c), 0));
    }
    CHECK(hi - lo <= 1.0 / 12 + 1e-12);  // no triangle wraps around the texture
  }
}

TEST_CASE("synthetic frames are written as OBJ files that read back exactly") {
  const SyntheticSequence seq = make_synthetic_sequence(small_config());
  const SyntheticFrame f = synthetic_frame(seq, 3);
  const ObjFile obj = parse_obj(format_synthetic_obj(seq, f.drifted, "frame 3"), "frame_0003.obj");
  CHECK(obj.mesh.V == f.drifted);
  CHECK(obj.mesh.F == seq.F);
  CHECK(obj.texcoords.rows() == seq.uv.rows());

  test::TempDir dir("synthetic");
  CHECK(write_synthetic_sequence(seq, dir / "in", dir / "gt") == 5);
  CHECK(read_obj(dir / "in" / "frame_0004.obj").mesh.V == synthetic_frame(seq, 4).drifted);
  CHECK(read_obj(dir / "gt" / "frame_0004.obj").mesh.V == synthetic_frame(seq, 4).clean);
}

TEST_CASE("synthetic frame names and invalid configs") {
  SyntheticOptions c = small_config();
  CHECK(synthetic_frame_name(make_synthetic_sequence(c), 7) == "frame_0007.obj");
  c.frames = 12345;
  CHECK(synthetic_frame_name(make_synthetic_sequence(c), 7) == "frame_00007.obj");
  c = small_config();
  c.bend = 300.0;
  c.radius = 1.0;
  CHECK_THROWS_AS(make_synthetic_sequence(c), ConfigError);
  CHECK_THROWS_AS(synthetic_frame(make_synthetic_sequence(small_config()), 5), InputError);
}

TEST_CASE("the rolled sheet is isometric: every edge keeps its length, drifted vertices stay on "
          "the cylinder and the boundary does not move") {
  SyntheticOptions c = small_config();
  c.shape = SyntheticShape::RolledSheet;
  c.bend = 270.0;
  const SyntheticSequence seq = make_synthetic_sequence(c);
  CHECK(seq.rest.num_vertices() == c.segments * (c.rings + 1));
  CHECK(seq.F.rows() == 2 * (c.segments - 1) * c.rings);
  const SyntheticFrame first = synthetic_frame(seq, 0), last = synthetic_frame(seq, c.frames - 1);
  CHECK(first.clean == seq.rest.V);
  CHECK(first.drifted == seq.rest.V);
  // Edges of the grid: straight along, chords of the roll across (equal to the flat length up
  // to the chord's sagitta, tiny at these sizes), so compare the along ones exactly.
  const double width = 2.0 * M_PI * c.radius;
  const double R = width / (c.bend * M_PI / 180.0);  // radius of the roll at the last frame
  for (int v = 0; v < last.clean.rows(); ++v) {
    CHECK(std::abs(std::hypot(last.clean(v, 0), last.clean(v, 2) - R) - R) < 1e-12);
    CHECK(std::abs(std::hypot(last.drifted(v, 0), last.drifted(v, 2) - R) - R) < 1e-12);
  }
  for (int v = 0; v + c.segments < last.clean.rows(); ++v)
    CHECK(std::abs((last.clean.row(v + c.segments) - last.clean.row(v)).norm() -
                   c.length / c.rings) < 1e-12);
  const Eigen::VectorXd moved = (last.drifted - last.clean).rowwise().norm();
  CHECK(moved.maxCoeff() > 0.1 * c.length / c.rings);
  for (int v = 0; v < last.clean.rows(); ++v) {
    const int i = v % c.segments, j = v / c.segments;
    if (i == 0 || i == c.segments - 1 || j == 0 || j == c.rings) CHECK(moved[v] < 1e-12);
  }
  const std::string obj = format_synthetic_obj(seq, last.drifted, "x");
  CHECK(obj.find("g sheet\n") != std::string::npos);
}

TEST_CASE("the drift keys change the field, their defaults keep the tube's bytes") {
  const SyntheticSequence base = make_synthetic_sequence(small_config());
  SyntheticOptions same = small_config();
  same.drift_waves = 6;
  same.drift_cycles = 4.0;
  CHECK(synthetic_frame(make_synthetic_sequence(same), 4).drifted ==
        synthetic_frame(base, 4).drifted);
  SyntheticOptions more = small_config();
  more.drift_waves = 3;
  more.drift_cycles = 8.0;
  CHECK(synthetic_frame(make_synthetic_sequence(more), 4).drifted !=
        synthetic_frame(base, 4).drifted);
  SyntheticOptions bad = small_config();
  bad.drift_waves = 0;
  CHECK_THROWS_AS(check_synthetic_options(bad), ConfigError);
}
