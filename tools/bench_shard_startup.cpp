// Benchmark of what every shard of a sequence job pays once, before its frames (issue 17): on a
// generated bending tube of each size, written as OBJ frames like a captured sequence,
//   template      reading the template frame (read_mesh)
//   weights       compute_weights on it (mean value weights, as the job)
//   system        the rest of the Massager's construction (A, the sparsity pattern, the ILU
//                 schedule, the template's BVH, the topology): Massager() minus weights
//   plan          plan_sequence_job of a shard of one frame: lists the folder, reads the template
//                 and the frame (checked), builds the Massager: template + weights + system + a
//                 frame's read
//   first, steady run_sequence_job of the shard's frames (default 5), one after the other: the
//                 first frame, then the median of the others (from the job's progress hook)
// start-up = plan + (first - steady): the cost of a task beyond its frames' own (conservative: it
// counts one frame read twice), and "frames for 1%" the frames a task needs so that start-up is
// under 1% of its work: 99 * start-up / steady. Each in wall time and in the process's CPU time
// (one thread: the work itself, whatever else the machine runs). Medians over --repeat runs. Not
// a test: it asserts nothing.
//
//   bench_shard_startup [--sizes 10000,150000] [--frames K] [--threads T] [--repeat R] [--keep DIR]
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/weights.hpp"
#include "config/config.hpp"
#include "io/mesh_file.hpp"
#include "massage/massage.hpp"
#include "core/timing.hpp"
#include "pipeline/run/sequence_job.hpp"
#include "pipeline/sequence/synthetic.hpp"

using namespace sm;
namespace fs = std::filesystem;

namespace {

struct Times {
  double templ = 0, weights = 0, system = 0, plan = 0, first = 0, steady = 0;
};

// Wall and CPU time since construction.
struct Stopwatch {
  Clock::time_point wall = Clock::now();
  std::clock_t cpu = std::clock();
  double wall_s() const { return seconds_since(wall); }
  double cpu_s() const { return double(std::clock() - cpu) / CLOCKS_PER_SEC; }
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A tube of about n vertices: `segments` around, rings + 1 along, edges of similar length.
SyntheticOptions tube(int n, int frames) {
  SyntheticOptions c;
  c.frames = frames;
  c.segments = std::max(8, static_cast<int>(std::sqrt(n * 0.6)));
  c.rings = std::max(1, n / c.segments - 1);
  return c;
}

SequenceJobOptions job_config(const fs::path& frames, const fs::path& out, int threads) {
  return parse_config(
      nlohmann::json{{"job", "sequence"},
                     {"threads", threads},
                     {"input", {{"frames", frames.string()}}},
                     {"output", {{"dir", out.string()}}}},
      frames.parent_path());
}

// One run: [0] wall times, [1] CPU times.
std::array<Times, 2> measure(const fs::path& frames, const fs::path& out, int count, int threads) {
  std::array<Times, 2> t;
  const auto take = [&](const Stopwatch& w, double Times::*field) {
    t[0].*field = w.wall_s();
    t[1].*field = w.cpu_s();
  };
  Stopwatch w;
  const TriMesh templ = read_mesh(frames / "frame_0000.obj");
  take(w, &Times::templ);
  SequenceJobOptions config = job_config(frames, out, threads);
  w = Stopwatch();
  const ShapeWeights weights =
      compute_weights(templ, config.massage.weights, config.massage.boundary_weights);
  take(w, &Times::weights);
  w = Stopwatch();
  { const Massager massager(templ, config.massage); }
  take(w, &Times::system);
  for (Times& x : t) x.system -= x.weights;

  config.input.range.start = 1;
  config.input.range.stop = 2;
  w = Stopwatch();
  { const SequencePlan one = plan_sequence_job(config); }
  take(w, &Times::plan);

  fs::remove_all(out);
  config.input.range.stop = 1 + count;
  const SequencePlan plan = plan_sequence_job(config);
  std::vector<double> wall, cpu;  // at each frame's end, since the run's start
  RunHooks hooks;
  w = Stopwatch();
  hooks.progress = [&](const FrameSummary&, int, int, double) {
    wall.push_back(w.wall_s());
    cpu.push_back(w.cpu_s());
  };
  run_sequence_job(plan, hooks);
  for (int k = 0; k < 2; ++k) {
    const std::vector<double>& at = k == 0 ? wall : cpu;
    std::vector<double> steps;
    for (size_t i = 1; i < at.size(); ++i) steps.push_back(at[i] - at[i - 1]);
    t[k].first = at.empty() ? 0.0 : at.front();
    t[k].steady = median(steps);
  }
  return t;
}

std::vector<int> parse_list(const char* s) {
  std::vector<int> v;
  for (const char* p = s; *p;) {
    v.push_back(std::atoi(p));
    while (*p && *p != ',') ++p;
    if (*p == ',') ++p;
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes = {10000, 150000};
  int frames = 5, threads = 1, repeat = 3;
  fs::path keep;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
    if (a != "--sizes" && a != "--frames" && a != "--threads" && a != "--repeat" && a != "--keep") {
      std::fprintf(stderr,
                   "usage: bench_shard_startup [--sizes a,b] [--frames K] [--threads T] "
                   "[--repeat R] [--keep DIR]\n");
      return 2;
    }
    if (!value) {
      std::fprintf(stderr, "%s needs a value\n", a.c_str());
      return 2;
    }
    if (a == "--sizes") sizes = parse_list(value);
    if (a == "--frames") frames = std::max(2, std::atoi(value));
    if (a == "--threads") threads = std::max(1, std::atoi(value));
    if (a == "--repeat") repeat = std::max(1, std::atoi(value));
    if (a == "--keep") keep = value;
    ++i;
  }
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const fs::path dir = keep.empty() ? fs::temp_directory_path() / "bench_shard_startup" : keep;

  std::printf("per-task start-up of a shard, %d thread%s, a shard of %d frames, median of %d\n",
              threads, threads == 1 ? "" : "s", frames, repeat);
  std::printf("%9s %5s %9s %9s %9s %9s %9s %9s %9s %11s\n", "vertices", "time", "template",
              "weights", "system", "plan", "first", "steady", "start-up", "frames 1%");
  for (int n : sizes) {
    const fs::path frames_dir = dir / ("tube_" + std::to_string(n));
    const SyntheticSequence seq = make_synthetic_sequence(tube(n, frames + 1));
    if (!fs::exists(frames_dir / "input" / synthetic_frame_name(seq, frames)))
      write_synthetic_sequence(seq, frames_dir / "input", frames_dir / "ground_truth");
    std::vector<std::array<Times, 2>> runs;
    for (int r = 0; r < repeat; ++r)
      runs.push_back(measure(frames_dir / "input", frames_dir / "out", frames, threads));
    for (int k = 0; k < 2; ++k) {
      const auto med = [&](double Times::*field) {
        std::vector<double> v;
        for (const auto& t : runs) v.push_back(t[k].*field);
        return median(v);
      };
      const double steady = med(&Times::steady);
      const double startup = med(&Times::plan) + med(&Times::first) - steady;
      std::printf("%9d %5s %7.0f ms %6.0f ms %6.0f ms %6.0f ms %6.0f ms %6.0f ms %6.0f ms %11.0f\n",
                  static_cast<int>(seq.rest.num_vertices()), k == 0 ? "wall" : "CPU",
                  1e3 * med(&Times::templ), 1e3 * med(&Times::weights),
                  1e3 * med(&Times::system), 1e3 * med(&Times::plan), 1e3 * med(&Times::first),
                  1e3 * steady, 1e3 * startup, steady > 0 ? 99.0 * startup / steady : 0.0);
    }
    std::fflush(stdout);
  }
  if (keep.empty()) fs::remove_all(dir);
  return 0;
}
