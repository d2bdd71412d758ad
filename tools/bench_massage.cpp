// Benchmark of the optimizer (issue 2): per-iteration stage timings on generated tori of about
// 4k, 10k, 16k, 64k and 150k vertices with a smooth tangential drift, and on the Vlasic crane
// (frame 5 against frame 0) when ../shared/data is present. Not a test: it asserts nothing.
// With --repeat R every case runs R times and the fastest run is reported (the machine is shared:
// the minimum is the least disturbed measurement). The quality columns (shear of eq. 8 against
// the template before and after, largest distance to the reference) show that a faster variant
// still does the same job.
//
//   bench_massage [--threads N] [--iterations K] [--solver iterative|direct] [--sizes a,b,...]
//                 [--repeat R] [--data DIR] ...    (bench_massage --help lists them all)
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/arguments.hpp"
#include "geometry/shear.hpp"
#include "io/mesh_file.hpp"
#include "massage/massage.hpp"
#include "mesh/primitives.hpp"
#include "core/timing.hpp"

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
    const auto t0 = Clock::now();
    const Massager massager(templ, options);
    const double setup = seconds_since(t0);
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
  bool verbose = false, exact = false;
  MassageOptions options;
  std::string solver, shape_target;
  std::vector<int> sizes = {4000, 10000, 16000, 64000, 150000};
  fs::path data = fs::path(SEQMASSAGE_SOURCE_DIR) / ".." / "shared" / "data";
  CLI::App app(
      "Usage: bench_massage [options]\n\n"
      "Per-iteration stage timings of the optimizer on generated tori and on the Vlasic crane\n"
      "(frame 5 against frame 0, when DIR holds it). Prints timings; asserts nothing.\n",
      "bench_massage");
  sm::cli::set_conventions(app, 30);
  app.add_option("--threads", threads, "worker threads")
      ->type_name("N")
      ->transform(sm::cli::integer_in(1, 4096));
  app.add_option("--iterations", options.iterations, "outer iterations of the optimizer")
      ->type_name("K")
      ->transform(sm::cli::integer_in(1, 100000));
  app.add_option("--solver", solver, "linear solver (default iterative)")
      ->type_name("iterative|direct")
      ->check(sm::cli::one_of({"iterative", "direct"}));
  app.add_option("--solver-tolerance", options.solver_tolerance,
                 "relative residual of the iterative solver")
      ->type_name("T")
      ->transform(sm::cli::number_in(0, 1, "in (0, 1)"));
  app.add_option("--shape-target", shape_target, "right-hand side of the shape system (default template)")
      ->type_name("zero|template")
      ->check(sm::cli::one_of({"zero", "template"}));
  std::string distance_term;
  app.add_option("--distance-term", distance_term,
                 "the distance term (default point; plane: eps 0.2, adapt 5)")
      ->type_name("point|plane")
      ->check(sm::cli::one_of({"point", "plane"}));
  app.add_flag("--exact", exact, "exact closest points instead of the local search");
  app.add_flag("--verbose", verbose, "every iteration's figures");
  app.add_option("--repeat", repeat, "run every case R times and report the fastest run")
      ->type_name("R")
      ->transform(sm::cli::integer_in(1, 1000));
  app.add_option("--sizes", sizes, "vertex counts of the tori (default 4000,...,150000)")
      ->type_name("A,B,...")
      ->delimiter(',')
      ->transform(sm::cli::integer_in(1, 100000000));
  app.add_option("--data", data, "the real data (default ../shared/data)")->type_name("DIR");
  if (const auto code = sm::cli::parse_or_exit(app, argc, argv)) return *code;
  if (!solver.empty())
    options.solver = solver == "direct" ? SolverKind::Direct : SolverKind::Iterative;
  if (!shape_target.empty())
    options.shape_target =
        shape_target == "template" ? ShapeTargetKind::Template : ShapeTargetKind::Zero;
  if (exact) options.closest_points = ClosestPointMode::Exact;
  if (distance_term == "plane") options.distance_term = DistanceTerm::Plane;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::printf(
      "bench_massage: %d thread(s), %d iterations, %s distance term, %s solver (tolerance %g), "
      "%s closest points, best of %d run(s)\n",
      threads, options.iterations,
      options.distance_term == DistanceTerm::Plane ? "plane" : "point",
      options.solver == SolverKind::Direct ? "direct" : "iterative",
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
