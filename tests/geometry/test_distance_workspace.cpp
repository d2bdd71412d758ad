#include <catch2/catch.hpp>

#include <set>
#include <vector>

#include <tbb/parallel_for.h>

#include "geometry/distance.hpp"
#include "geometry/distance_meter.hpp"
#include "geometry/distance_workspace.hpp"
#include "mesh/primitives.hpp"

using namespace sm;

TEST_CASE("distance workspaces: each holder its own, kept when given back", "[distance]") {
  DistanceWorkspaces pool;
  const DistanceWorkspace* first = nullptr;
  {
    const DistanceWorkspaces::Lease a = pool.acquire();
    const DistanceWorkspaces::Lease b = pool.acquire();
    REQUIRE(a.get() != nullptr);
    CHECK(a.get() != b.get());
    first = a.get();
  }
  // Both were given back: the next two holders get those two, and no new one.
  const DistanceWorkspaces::Lease c = pool.acquire();
  const DistanceWorkspaces::Lease d = pool.acquire();
  CHECK(c.get() != d.get());
  CHECK((c.get() == first || d.get() == first));
}

TEST_CASE("distance workspaces under concurrent frames give each frame's own distances",
          "[distance]") {
  const TriMesh a = make_torus(30, 12, 2.0, 0.5);
  std::vector<TriMesh> targets;
  for (int k = 0; k < 8; ++k) {
    TriMesh b = a;
    b.V *= 1.0 + 0.01 * (k + 1);
    targets.push_back(b);
  }
  DistanceOptions o;
  o.adaptive = true;
  std::vector<double> alone(targets.size()), pooled(targets.size());
  for (size_t k = 0; k < targets.size(); ++k)
    alone[k] = one_sided_distance(targets[k], TriangleBvh(a), o).rms;
  // The meter leases one workspace per frame being measured.
  const DistanceMeter meter(a.F, a.num_vertices(), nullptr, o);
  const TriangleBvh bvh(a);
  const TrianglePlanes planes(a.V, a.F);
  tbb::parallel_for(size_t(0), targets.size(), [&](size_t k) {
    pooled[k] = meter.measure(a, bvh, planes, targets[k].V).moved_to_original.rms;
  });
  CHECK(pooled == alone);
}
