// Timing of the hot closest-point queries on ~160k-vertex meshes: BVH build and refit, exact
// queries near, far outside and deep inside, the local walk and how often its answer is not the
// global minimum, and one Metro-style distance. Run: build/tools/bench_bvh
#include <chrono>
#include <iostream>
#include <random>

#include "geometry/bvh.hpp"
#include "geometry/distance.hpp"
#include "geometry/surface_walk.hpp"
#include "mesh/primitives.hpp"
#include "mesh/topology.hpp"

using namespace sm;

int main() {
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  const std::vector<std::pair<const char*, TriMesh>> meshes = {
      {"icosphere(7)", make_icosphere(7, 1.0)}, {"torus(400x400)", make_torus(400, 400, 2.0, 0.6)}};
  for (const auto& [name, mesh] : meshes) {
    auto t0 = Clock::now();
    const TriangleBvh bvh(mesh);
    auto t1 = Clock::now();
    const Topology topo = build_topology(mesh);
    TriangleBvh refitted(mesh);
    auto t2 = Clock::now();
    refitted.refit(mesh.V);
    auto t3 = Clock::now();
    std::cout << name << ": " << mesh.num_vertices() << " vertices, " << mesh.num_triangles()
              << " triangles; build " << 1e3 * seconds(t0, t1) << " ms, refit "
              << 1e3 * seconds(t2, t3) << " ms\n";

    // Exact queries: every vertex moved off the surface by a small random offset (the
    // correspondence queries of an iteration), and far queries.
    const double h = mean_edge_length(mesh);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int n = mesh.num_vertices();
    std::vector<Vec3> near(n);
    for (int i = 0; i < n; ++i) near[i] = mesh.vertex(i) + 0.5 * h * Vec3(u(rng), u(rng), u(rng));
    std::vector<SurfacePoint> corr(n);
    double checksum = 0.0;
    t0 = Clock::now();
    for (int i = 0; i < n; ++i) corr[i] = bvh.closest(near[i]);
    t1 = Clock::now();
    for (const SurfacePoint& s : corr) checksum += s.dist2;
    std::cout << "  exact query, near: " << 1e9 * seconds(t0, t1) / n << " ns/query\n";
    // Far queries: outside the model, one to two bounding-box diagonals from its centre.
    const Vec3 centre =
        0.5 * (mesh.V.colwise().minCoeff() + mesh.V.colwise().maxCoeff()).transpose();
    const double diag = bounding_box_diagonal(mesh.V);
    std::vector<Vec3> far(20000);
    for (Vec3& p : far)
      p = centre + diag * (1.0 + 0.5 * (1.0 + u(rng))) * Vec3(u(rng), u(rng), u(rng)).normalized();
    t0 = Clock::now();
    for (const Vec3& p : far) checksum += bvh.closest(p).dist2;
    t1 = Clock::now();
    std::cout << "  exact query, far outside: " << 1e9 * seconds(t0, t1) / far.size()
              << " ns/query\n";
    // Inside, near the middle: almost every triangle is about as far as the closest one, so
    // box bounds prune little (the worst case of any bounding volume hierarchy).
    std::vector<Vec3> deep(200);
    for (Vec3& p : deep) p = centre + 0.05 * diag * Vec3(u(rng), u(rng), u(rng));
    t0 = Clock::now();
    for (const Vec3& p : deep) checksum += bvh.closest(p).dist2;
    t1 = Clock::now();
    std::cout << "  exact query, near the centre: " << 1e9 * seconds(t0, t1) / deep.size()
              << " ns/query\n";

    // The walk: the queries move by a tenth of an edge, each starts at its last correspondence.
    std::vector<Vec3> moved(n);
    for (int i = 0; i < n; ++i) moved[i] = near[i] + 0.1 * h * Vec3(u(rng), u(rng), u(rng));
    int failed = 0, wrong = 0;
    SurfacePoint out;
    t0 = Clock::now();
    for (int i = 0; i < n; ++i) {
      if (walk_closest(mesh.V, mesh.F, topo, moved[i], corr[i].triangle, 8, out))
        checksum += out.dist2;
      else
        ++failed;
    }
    t1 = Clock::now();
    std::cout << "  walk (moved 0.1 edge): " << 1e9 * seconds(t0, t1) / n << " ns/query, " << failed
              << " ran out of steps\n";
    t0 = Clock::now();
    for (int i = 0; i < n; ++i) {
      const SurfacePoint exact = bvh.closest(moved[i]);
      if (walk_closest(mesh.V, mesh.F, topo, moved[i], corr[i].triangle, 8, out) &&
          out.dist2 > exact.dist2 * (1.0 + 1e-12) + 1e-300)
        ++wrong;
    }
    t1 = Clock::now();
    std::cout << "  walk results that are not the global minimum: " << wrong << " of " << n
              << " (checksum " << checksum << ")\n";
  }
  const TriMesh a = make_icosphere(7, 1.0);
  TriMesh b = a;
  b.V *= 1.01;
  const auto t0 = Clock::now();
  const DistanceStats d = one_sided_distance(a, TriangleBvh(b));
  const auto t1 = Clock::now();
  std::cout << "one_sided_distance icosphere(7) -> scaled copy: " << d.samples << " samples in "
            << 1e3 * seconds(t0, t1) << " ms (all threads), max " << d.max << "\n";
  return 0;
}
