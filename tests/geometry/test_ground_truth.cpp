// The ground-truth error split into its parts along and off the true surface.
#include <catch2/catch.hpp>

#include "geometry/ground_truth.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

TEST_CASE("a slide along a flat grid is tangential, a lift off it normal, both in units") {
  const TriMesh truth = make_grid(4, 4, 1.0, 1.0);  // in the plane z = 0
  Positions V = truth.V;
  V.col(0).array() += 0.3;  // slide
  V(5, 2) = 0.4;            // and lift one vertex
  const CorrespondenceError e = correspondence_error(V, truth, 0.5);
  const int n = truth.num_vertices();
  CHECK(e.tangential_mean == Approx(0.6));
  CHECK(e.tangential_max == Approx(0.6));
  CHECK(e.normal_max == Approx(0.8));
  CHECK(e.normal_mean == Approx(0.8 / n));
  CHECK(e.max == Approx(1.0));
  CHECK(e.mean == Approx(((n - 1) * 0.6 + 1.0) / n));
  const CorrespondenceError zero = correspondence_error(truth.V, truth, 1.0);
  CHECK(zero.max == 0.0);
  CHECK(zero.tangential_max == 0.0);
}
