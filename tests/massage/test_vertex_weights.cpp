// Per-vertex weights (massage.vertex_weights, docs/method-vertex-weights.md): weight 1 everywhere
// is today's result bit for bit, weight 0 keeps a vertex exactly at its start, weights between
// move it less, and the Massager validates them.
#include <catch2/catch.hpp>

#include "massage/massage.hpp"
#include "core/errors.hpp"
#include "support/drift.hpp"
#include "support/error_of.hpp"

using namespace sm;

namespace {

MassageResult run_with(const test::Scenario& s, std::vector<double> weights,
                       MassageOptions o = {}) {
  o.vertex_weights = std::move(weights);
  const Massager m(s.templ, o);
  const Reference ref(s.drifted, o.samples, "reference", m.shared_topology());
  MassageResult r = m.run(s.drifted.V, ref);
  REQUIRE(r.ok);
  return r;
}

// Mean distance the vertices `in` moved from the start.
double mean_move(const test::Scenario& s, const Positions& V, const std::vector<int>& in) {
  double sum = 0.0;
  for (int i : in) sum += (V.row(i) - s.drifted.V.row(i)).norm();
  return sum / static_cast<double>(in.size());
}

}  // namespace

TEST_CASE("vertex weights of 1 everywhere give the unweighted result bit for bit",
          "[massage][weights]") {
  const test::Scenario s = test::rolled_grid(24, 14, 9.0, 0.3, 21);
  const int n = s.templ.num_vertices();
  for (ShapeTargetKind target : {ShapeTargetKind::Template, ShapeTargetKind::Zero}) {
    MassageOptions o;
    o.shape_target = target;
    const MassageResult plain = run_with(s, {}, o);
    const MassageResult ones = run_with(s, std::vector<double>(size_t(n), 1.0), o);
    CHECK(plain.V == ones.V);
    CHECK(plain.iterations.size() == ones.iterations.size());
  }
}

TEST_CASE("vertex weight 0 keeps a region exactly at its start; less weight moves less",
          "[massage][weights]") {
  const test::Scenario s = test::rolled_grid(24, 14, 9.0, 0.3, 22);
  const int n = s.templ.num_vertices();
  // The region: the vertices of the left third of the grid (x below a third of the width).
  const double x_cut = s.templ.V.col(0).minCoeff() +
                       (s.templ.V.col(0).maxCoeff() - s.templ.V.col(0).minCoeff()) / 3.0;
  std::vector<int> region, outside;
  for (int i = 0; i < n; ++i) (s.templ.V(i, 0) < x_cut ? region : outside).push_back(i);
  REQUIRE(region.size() > 20);

  auto weights_in_region = [&](double w) {
    std::vector<double> weights(size_t(n), 1.0);
    for (int i : region) weights[size_t(i)] = w;
    return weights;
  };
  const MassageResult zero = run_with(s, weights_in_region(0.0));
  for (int i : region) CHECK(zero.V.row(i) == s.drifted.V.row(i));
  CHECK(mean_move(s, zero.V, outside) > 0.0);  // the rest is still massaged

  double previous = -1.0;
  for (double w : {0.0, 0.1, 0.3, 0.6, 1.0}) {
    const double moved = mean_move(s, run_with(s, weights_in_region(w)).V, region);
    INFO("weight " << w << ": mean move in the region " << moved);
    CHECK(moved > previous);  // monotone: more weight, more movement
    previous = moved;
  }
}

TEST_CASE("vertex weights are validated: count and range", "[massage][weights]") {
  const test::Scenario s = test::rolled_grid(8, 6, 5.0, 0.2, 23);
  const int n = s.templ.num_vertices();
  MassageOptions o;
  o.vertex_weights.assign(size_t(n - 1), 1.0);
  // The Massager names the member; the jobs and Python add the config path (with_option_path).
  CHECK(test::error_of([&] { Massager(s.templ, o); }) ==
        "vertex_weights: expected " + std::to_string(n) +
            " weights (one per template vertex), got " + std::to_string(n - 1));
  o.vertex_weights.assign(size_t(n), 0.5);
  o.vertex_weights[3] = 1.5;
  CHECK(test::error_of([&] { with_option_path("massage", [&] { Massager(s.templ, o); }); }) ==
        "massage.vertex_weights[3]: expected a number in [0, 1], got 1.5");
  o.vertex_weights[3] = std::nan("");
  CHECK_THROWS_AS(Massager(s.templ, o), OptionError);
  CHECK(test::error_of([&] { Massager(s.templ, o); }) ==
        "vertex_weights[3]: expected a number in [0, 1], got nan");
}
