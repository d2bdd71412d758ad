// Benchmark of the optimizer (issue 2): per-iteration stage timings on generated tori of about
// 4k, 10k, 16k, 64k and 150k vertices with a smooth tangential drift, and on the Vlasic crane
// (frame 5 against frame 0) when ../shared/data is present. Not a test: it asserts nothing.
// With --repeat R every case runs R times and the fastest run is reported (the machine is shared:
// the minimum is the least disturbed measurement). The quality columns (shear of eq. 8 against
// the template before and after, largest distance to the reference) show that a faster variant
// still does the same job.
//
//   bench_massage [--threads N] [--iterations K] [--solver iterative|direct] [--sizes a,b,...]
//                 [--repeat R] [--data DIR]
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/shear.hpp"
#include "io/mesh_file.hpp"
#include "massage/massage.hpp"
#include "mesh/primitives.hpp"

using namespace sm;
namespace fs = std::filesystem;

namespace {

// Torus with nu×nv vertices whose vertices slide along the surface by a smooth periodic field of
// amplitude `amp` edge lengths (exactly on the torus).
void drifted_torus(int nu, int nv, double amp, TriMesh& clean, TriMesh& drifted) {
  const double R = 2.0, r = 0.7;
  clean = make_torus(nu, nv, R, r);
  drifted = clean;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double u = 2 * M_PI * i / nu, w = 2 * M_PI * j / nv;
      const double du = amp * 2 * M_PI / nu * std::sin(3 * w + 2 * u) * std::cos(5 * u);
      const double dw = amp * 2 * M_PI / nv * std::cos(4 * u - w) * std::sin(2 * w + 1.0);
      const double uu = u + du, ww = w + dw;
      drifted.V.row(j * nu + i) << (R + r * std::cos(ww)) * std::cos(uu),
          (R + r * std::cos(ww)) * std::sin(uu), r * std::sin(ww);
    }
}

struct Totals {
  double closest = 0, assemble = 0, solve = 0;
  int solver_its = 0, exact = 0, iterations = 0;
};

double per_iteration(const MassageResult& r) {
  double s = 0.0;
  for (const IterationStats& it : r.iterations)
    s += it.seconds_closest + it.seconds_assemble + it.seconds_solve;
  return s / std::max<size_t>(1, r.iterations.size());
}

void report(const char* name, int n, double setup_s, const MassageResult& r, bool verbose,
            const Eigen::VectorXd& shear_before, const Eigen::VectorXd& shear_after) {
  Totals t;
  for (const IterationStats& it : r.iterations) {
    t.closest += it.seconds_closest;
    t.assemble += it.seconds_assemble;
    t.solve += it.seconds_solve;
    t.solver_its += it.solver_iterations;
    t.exact += it.exact_queries;
    ++t.iterations;
  }
  if (verbose) {
    std::printf("  %4s %10s %10s %10s %10s %8s %8s %12s %12s %12s\n", "it", "closest", "assemble",
                "solve", "total", "solver", "exact", "max M->N", "max N->M", "max move");
    for (const IterationStats& it : r.iterations)
      std::printf(
          "  %4d %8.2fms %8.2fms %8.2fms %8.2fms %8d %8d %12.3e %12.3e %12.3e\n", it.iteration,
          1e3 * it.seconds_closest, 1e3 * it.seconds_assemble, 1e3 * it.seconds_solve,
          1e3 * (it.seconds_closest + it.seconds_assemble + it.seconds_solve), it.solver_iterations,
          it.exact_queries, it.max_dist_m_to_n, it.max_dist_n_to_m, it.max_move);
  }
  const double per_it = (t.closest + t.assemble + t.solve) / std::max(1, t.iterations);
  std::printf(
      "%-22s n=%7d  setup %7.1f ms | per iteration %7.2f ms (closest %6.2f, assemble %6.2f, "
      "solve %6.2f; %4.1f solver its) | run %8.1f ms, %d its%s%s\n",
      name, n, 1e3 * setup_s, 1e3 * per_it, 1e3 * t.closest / t.iterations,
      1e3 * t.assemble / t.iterations, 1e3 * t.solve / t.iterations,
      double(t.solver_its) / t.iterations, 1e3 * r.seconds, t.iterations,
      r.stopped_early ? " (early stop)" : "", r.ok ? "" : (" FAILED: " + r.failure).c_str());
  const IterationStats last = r.iterations.empty() ? IterationStats{} : r.iterations.back();
  std::printf(
      "%-22s   quality: shear max %.4g -> %.4g, mean %.4g -> %.4g | max dist M->N %.3e, N->M "
      "%.3e\n",
      "", shear_before.maxCoeff(), shear_after.maxCoeff(), shear_before.mean(), shear_after.mean(),
      last.max_dist_m_to_n, last.max_dist_n_to_m);
}

void run_case(const char* name, const TriMesh& templ, const TriMesh& reference,
              const MassageOptions& options, bool verbose, int repeat) {
  double best_setup = 0.0;
  MassageResult best;
  for (int k = 0; k < repeat; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const Massager massager(templ, options);
    const double setup =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const Reference ref(reference, options.samples, "reference", massager.shared_topology());
    MassageResult r = massager.run(reference.V, ref);
    if (k == 0 || per_iteration(r) < per_iteration(best)) best = std::move(r);
    best_setup = k == 0 ? setup : std::min(best_setup, setup);
  }
  const Eigen::VectorXd before = shear_distortion(templ.V, reference.V, templ.F);
  const Eigen::VectorXd after = shear_distortion(templ.V, best.V, templ.F);
  report(name, templ.num_vertices(), best_setup, best, verbose, before, after);
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 1;
  int repeat = 1;
  bool verbose = false;
  MassageOptions options;
  std::vector<int> sizes = {4000, 10000, 16000, 64000, 150000};
  fs::path data = fs::path(SEQMASSAGE_SOURCE_DIR) / ".." / "shared" / "data";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--threads")
      threads = std::stoi(next());
    else if (a == "--iterations")
      options.iterations = std::stoi(next());
    else if (a == "--solver")
      options.solver = next() == "direct" ? SolverKind::Direct : SolverKind::Iterative;
    else if (a == "--shape-target")
      options.shape_target =
          next() == "template" ? ShapeTargetKind::Template : ShapeTargetKind::Zero;
    else if (a == "--exact")
      options.closest_points = ClosestPointMode::Exact;
    else if (a == "--solver-tolerance")
      options.solver_tolerance = std::stod(next());
    else if (a == "--verbose")
      verbose = true;
    else if (a == "--repeat")
      repeat = std::max(1, std::stoi(next()));
    else if (a == "--data")
      data = next();
    else if (a == "--sizes") {
      sizes.clear();
      std::string s = next();
      for (size_t p = 0; p < s.size();) {
        const size_t q = s.find(',', p);
        sizes.push_back(std::stoi(s.substr(p, q - p)));
        p = q == std::string::npos ? s.size() : q + 1;
      }
    } else {
      std::fprintf(stderr,
                   "usage: bench_massage [--threads N] [--iterations K] [--solver iterative|direct]"
                   " [--solver-tolerance T] [--shape-target zero|template] [--exact] [--verbose] "
                   "[--repeat R] [--sizes 4000,10000]"
                   " [--data DIR]\n");
      return 2;
    }
  }
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::printf(
      "bench_massage: %d thread(s), %d iterations, %s solver (tolerance %g), %s closest points, "
      "best of %d run(s)\n",
      threads, options.iterations, options.solver == SolverKind::Direct ? "direct" : "iterative",
      options.solver_tolerance,
      options.closest_points == ClosestPointMode::Exact ? "exact" : "local", repeat);
  for (int size : sizes) {
    const int nv = std::max(8, static_cast<int>(std::round(std::sqrt(size / 2.0))));
    const int nu = std::max(8, size / nv);
    TriMesh clean, drifted;
    drifted_torus(nu, nv, 0.4, clean, drifted);
    const std::string name = "torus " + std::to_string(nu) + "x" + std::to_string(nv);
    run_case(name.c_str(), clean, drifted, options, verbose, repeat);
  }
  const fs::path crane = data / "sequences" / "vlasic_crane";
  if (fs::exists(crane / "frame_0000.obj") && fs::exists(crane / "frame_0005.obj")) {
    const TriMesh f0 = read_mesh(crane / "frame_0000.obj");
    const TriMesh f5 = read_mesh(crane / "frame_0005.obj");
    run_case("crane frame 5 vs 0", f0, f5, options, verbose, repeat);
  } else {
    std::printf("crane: skipped, %s not found\n", crane.string().c_str());
  }
  return 0;
}
