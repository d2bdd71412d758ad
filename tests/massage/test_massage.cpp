#include <catch2/catch.hpp>

#include <tbb/parallel_for.h>

#include <numeric>

#include "core/errors.hpp"
#include "geometry/shear.hpp"
#include "massage/massage.hpp"
#include "mesh/primitives.hpp"
#include "support/drift.hpp"

using namespace sm;

namespace {

// Distance of every vertex to the cylinder of radius R around the axis (0, t, R).
double max_distance_to_cylinder(const Positions& V, double R) {
  double d = 0.0;
  for (int i = 0; i < V.rows(); ++i)
    d = std::max(d, std::abs(std::hypot(V(i, 0), V(i, 2) - R) - R));
  return d;
}

// Distance to the torus-arc tube of test::bent_tube (centre-line circle of radius Rb around
// (-Rb, 0, 0) in the xz plane, tube radius r).
double max_distance_to_bent_tube(const Positions& V, double Rb, double r) {
  double d = 0.0;
  for (int i = 0; i < V.rows(); ++i) {
    const double rho = std::hypot(V(i, 0) + Rb, V(i, 2));
    d = std::max(d, std::abs(std::hypot(rho - Rb, V(i, 1)) - r));
  }
  return d;
}

MassageResult massage(const test::Scenario& s, MassageOptions o = {}) {
  const Massager m(s.templ, o);
  const Reference ref(s.drifted, o.samples, "reference", m.shared_topology());
  MassageResult r = m.run(s.drifted.V, ref);
  REQUIRE(r.ok);
  return r;
}

}  // namespace

TEST_CASE("drift recovery on an isometric deformation (grid rolled onto a cylinder)",
          "[massage][acceptance]") {
  for (unsigned seed : {1u, 2u, 3u}) {
    const double R = 12.0;
    const test::Scenario s = test::rolled_grid(40, 24, R, 0.35, seed);
    const double h = mean_edge_length(s.templ);
    const Eigen::VectorXd before = shear_distortion(s.templ.V, s.drifted.V, s.templ.F);
    const MassageResult r = massage(s);
    const Eigen::VectorXd after = shear_distortion(s.templ.V, r.V, s.templ.F);
    INFO("seed " << seed << ": max shear " << before.maxCoeff() << " -> " << after.maxCoeff()
                 << ", mean " << before.mean() << " -> " << after.mean());
    CHECK(after.maxCoeff() <= 0.1 * before.maxCoeff());
    CHECK(max_distance_to_cylinder(r.V, R) <= 0.05 * h);
    CHECK(r.folded_triangles == 0);
  }
}

TEST_CASE("drift reduction on a stretching deformation (bending tube)", "[massage][acceptance]") {
  for (unsigned seed : {4u, 5u}) {
    const double r = 1.0, L = 8.0, Rb = 4.0;
    const test::Scenario s = test::bent_tube(32, 40, r, L, Rb, 0.35, seed);
    const double h = mean_edge_length(s.templ);
    const Eigen::VectorXd before = shear_distortion(s.templ.V, s.drifted.V, s.templ.F);
    const MassageResult res = massage(s);
    const Eigen::VectorXd after = shear_distortion(s.templ.V, res.V, s.templ.F);
    INFO("seed " << seed << ": max shear " << before.maxCoeff() << " -> " << after.maxCoeff()
                 << ", mean " << before.mean() << " -> " << after.mean());
    CHECK(after.maxCoeff() <= 0.7 * before.maxCoeff());
    CHECK(after.mean() <= before.mean());
    CHECK(max_distance_to_bent_tube(res.V, Rb, r) <= 0.05 * h);
  }
}

TEST_CASE("the iterative and the direct solver give the same result", "[massage]") {
  const test::Scenario s = test::rolled_grid(20, 12, 8.0, 0.3, 9);
  MassageOptions direct;
  direct.solver = SolverKind::Direct;
  const MassageResult a = massage(s), b = massage(s, direct);
  CHECK((a.V - b.V).cwiseAbs().maxCoeff() < 1e-6 * mean_edge_length(s.templ));
}

TEST_CASE("pinned vertices do not move", "[massage]") {
  const test::Scenario s = test::rolled_grid(16, 10, 6.0, 0.3, 11);
  MassageOptions o;
  o.pin_boundary = true;
  o.pinned = {100, 101};
  const Massager m(s.templ, o);
  const Reference ref(s.drifted, o.samples);
  const MassageResult r = m.run(s.drifted.V, ref);
  REQUIRE(r.ok);
  const Topology& t = m.topology();
  int moved_free = 0;
  for (int i = 0; i < r.V.rows(); ++i) {
    if (t.is_boundary_vertex[i] || i == 100 || i == 101)
      CHECK(r.V.row(i) == s.drifted.V.row(i));
    else if (r.V.row(i) != s.drifted.V.row(i))
      ++moved_free;
  }
  CHECK(moved_free > 0);
}

TEST_CASE("a Massager is reusable and thread-safe, and results are deterministic", "[massage]") {
  const test::Scenario s = test::rolled_grid(20, 14, 9.0, 0.3, 13);
  const Massager m(s.templ, MassageOptions{});
  const Reference ref(s.drifted, SampleKind::Vertices, "reference", m.shared_topology());
  const MassageResult serial = m.run(s.drifted.V, ref);
  std::vector<Positions> out(8);
  tbb::parallel_for(0, 8, [&](int k) { out[k] = m.run(s.drifted.V, ref).V; });
  for (const Positions& V : out) CHECK(V == serial.V);  // bitwise equal
}

TEST_CASE("the iteration observer sees every iterate of the run and changes nothing", "[massage]") {
  const test::Scenario s = test::bent_tube(16, 20, 1.0, 6.0, 5.0, 0.35, 5);
  MassageOptions o;
  o.iterations = 6;
  o.tolerance = 0.0;
  const Massager m(s.templ, o);
  const Reference ref(s.drifted, o.samples, "reference", m.shared_topology());
  std::vector<IterationStats> seen;
  std::vector<Positions> iterates;
  const MassageResult observed =
      m.run(s.drifted.V, ref, [&](const IterationStats& it, const Positions& V) {
        seen.push_back(it);
        iterates.push_back(V);
      });
  const MassageResult plain = m.run(s.drifted.V, ref);
  REQUIRE(observed.ok);
  CHECK(observed.V == plain.V);  // bitwise
  REQUIRE(seen.size() == observed.iterations.size());
  for (size_t k = 0; k < seen.size(); ++k) {
    CHECK(seen[k].iteration == int(k) + 1);
    CHECK(seen[k].energy == observed.iterations[k].energy);
  }
  CHECK(iterates.back() == observed.V);
  // The j-th iterate is where a run limited to j iterations ends.
  MassageOptions three = o;
  three.iterations = 3;
  CHECK(Massager(s.templ, three).run(s.drifted.V, ref).V == iterates[2]);
}

TEST_CASE("the result does not depend on how the caller labels the mesh", "[massage]") {
  // The Massager works in its own (banded) labels: the caller's vertex and triangle order may
  // change the rounding, nothing more. Both runs also keep the caller's labels on the way out.
  const test::Scenario s = test::bent_tube(24, 30, 1.0, 6.0, 5.0, 0.35, 17);
  const int n = s.templ.num_vertices(), m = s.templ.num_triangles();
  std::vector<int> perm(n), tris(m);  // old vertex i -> perm[i]; new triangle k = old tris[k]
  for (int i = 0; i < n; ++i) perm[i] = (i * 7919) % n;
  for (int t = 0; t < m; ++t) tris[t] = (t * 104729) % m;
  REQUIRE(std::gcd(7919, n) == 1);
  REQUIRE(std::gcd(104729, m) == 1);
  auto relabel = [&](const TriMesh& mesh) {
    TriMesh out{Positions(n, 3), Triangles(m, 3)};
    for (int i = 0; i < n; ++i) out.V.row(perm[i]) = mesh.V.row(i);
    for (int k = 0; k < m; ++k)
      for (int c = 0; c < 3; ++c) out.F(k, c) = perm[mesh.F(tris[k], c)];
    return out;
  };
  const test::Scenario shuffled{relabel(s.templ), relabel(s.clean), relabel(s.drifted)};
  const double h = mean_edge_length(s.templ);
  // Labels decide the order of sums (μ, Lawson's mean, the shape target's rings) and which of
  // two equally close triangles a walk settles on; 15 Lawson iterations carry such rounding
  // along, to about 1e-5 edge lengths here.
  const MassageResult a = massage(s);
  const MassageResult b = massage(shuffled);
  double worst = 0.0;
  for (int i = 0; i < n; ++i) worst = std::max(worst, (a.V.row(i) - b.V.row(perm[i])).norm());
  INFO("largest difference " << worst / h << " mean edge lengths");
  CHECK(worst < 1e-4 * h);
  CHECK(a.iterations.size() == b.iterations.size());
  const Eigen::VectorXd sa = shear_distortion(s.templ.V, a.V, s.templ.F);
  const Eigen::VectorXd sb = shear_distortion(shuffled.templ.V, b.V, shuffled.templ.F);
  CHECK(sb.mean() == Approx(sa.mean()).epsilon(1e-4));
  CHECK(sb.maxCoeff() == Approx(sa.maxCoeff()).epsilon(1e-3));
}

TEST_CASE("iteration statistics are reported and the energy is finite", "[massage]") {
  const test::Scenario s = test::rolled_grid(12, 8, 6.0, 0.3, 17);
  MassageOptions o;
  o.iterations = 5;
  o.tolerance = 0.0;
  const MassageResult r = massage(s, o);
  REQUIRE(r.iterations.size() == 5);
  for (const IterationStats& it : r.iterations) {
    CHECK(std::isfinite(it.energy));
    CHECK(it.mu > 0.0);
    CHECK(it.mu < 1.0);
    CHECK(it.max_dist_m_to_n >= it.rms_dist_m_to_n);
    CHECK(it.seconds_solve >= 0.0);
  }
  CHECK_FALSE(r.stopped_early);
}

TEST_CASE("extra samples on edges and faces recover the drift as vertex samples do",
          "[massage]") {
  // The rolled grid is isometric, so the drift-free answer is known: every kind of sample must
  // bring the shear down and keep the vertices on the cylinder.
  const double R = 6.0;
  const test::Scenario s = test::rolled_grid(12, 8, R, 0.3, 19);
  const double h = mean_edge_length(s.templ);
  const double before = shear_distortion(s.templ.V, s.drifted.V, s.templ.F).maxCoeff();
  for (SampleKind k : {SampleKind::Edges, SampleKind::Faces}) {
    MassageOptions o;
    o.samples = k;
    const MassageResult r = massage(s, o);
    const double after = shear_distortion(s.templ.V, r.V, s.templ.F).maxCoeff();
    INFO("samples " << static_cast<int>(k) << ": max shear " << before << " -> " << after);
    CHECK(after <= 0.2 * before);
    CHECK(max_distance_to_cylinder(r.V, R) <= 0.05 * h);
    CHECK(r.folded_triangles == 0);
  }
}

TEST_CASE("invalid options and inputs are rejected with the key or the mesh named", "[massage]") {
  const TriMesh g = make_grid(3, 3, 1.0, 1.0);  // 3 × 3 cells: 16 vertices
  // The Massager names the member (OptionError); the jobs add the config path.
  const auto refused = [&](const MassageOptions& options) -> std::string {
    try {
      Massager(g, options);
    } catch (const OptionError& e) {
      return e.key() + " | " + e.reason();
    }
    return "accepted";
  };
  MassageOptions o;
  o.iterations = 0;
  CHECK(refused(o) == "iterations | expected an integer >= 1, got 0");
  o = {};
  o.mu = 1.0;
  CHECK(refused(o) == "mu | expected a number in [0, 1), got 1");
  o = {};
  o.pinned = {99};
  CHECK(refused(o) == "pinned | vertex 99 is out of range (the mesh has 16 vertices)");
  CHECK_THROWS_WITH(with_option_path("massage", [&] { Massager(g, o); }),
                    "massage.pinned: vertex 99 is out of range (the mesh has 16 vertices)");
  TriMesh bad = g;
  bad.V(2, 0) = std::nan("");
  CHECK_THROWS_WITH(Massager(bad, MassageOptions{}, "rest.obj"), Catch::Contains("rest.obj"));
  const Massager m(g, MassageOptions{});
  const Reference ref(g, SampleKind::Vertices);
  Positions start = g.V;
  start(0, 0) = std::numeric_limits<double>::infinity();
  const MassageResult r = m.run(start, ref);
  CHECK_FALSE(r.ok);
  CHECK_THAT(r.failure, Catch::Contains("NaN or infinite"));
}
