// Benchmark of the sequence job (issue 3). Not a test: it asserts nothing.
//
//  1. Stages, one thread, in this process, on ../shared/data/sequences/vlasic_crane: every frame
//     goes through the steps of the job's per-frame work (sequence_job.cpp, process_frame) one
//     after the other, each timed in CPU time of the thread: read (file and OBJ parse), optimize
//     (Reference and Massager::run), measure (shear of eq. 8 before and after, Metro-style
//     distances both ways, sampled as the job's default "measures"), write (corrected OBJ and
//     per-triangle CSV formatted and written atomically), hash (SHA-256 of the input and both
//     outputs, as the frame record holds them).
//  2. The whole job: `seqmassage CONFIG --quiet` on the crane, with 1 and 2 threads, as a child
//     process: wall time (planning, reading, writing included), frames/s and peak memory (max
//     RSS), best of --repeat runs; "cores busy" (CPU / wall) and "frames in progress at once"
//     (the sum of summary.csv's per-frame seconds / wall) tell a pipeline that does not overlap
//     its frames (the second near 1 with 2 threads) from a machine whose cores are taken by
//     other processes (the second near 2, the first near 1).
//  3. Memory against sequence length: the generated bending-tube sequence (configs/demo.json
//     style, "input": {"synthetic": ...}) with 50 and with 1000 frames, 2 threads: max RSS of
//     each; it must not grow with the number of frames.
//
//  4. With --tables (or --spacing-table, --iterations-table): the option tables of
//     bench_sequence_tables.cpp: the distances' cost and accuracy per sampling on the crane, and
//     quality against massage.iterations (--iterations LIST, default 5,8,10,12,15) and, at the
//     largest count, against massage.tolerance (--tolerances LIST, default 1e-3,3e-3) on the
//     crane and the samba.
//
//   bench_sequence [--data DIR] [--repeat R] [--long N] [--short N] [--no-memory] [--no-stages]
//                  [--no-job] [--keep DIR] [--seqmassage PATH] [--tables] [--spacing-table]
//                  [--iterations-table] [--iterations LIST] [--tolerances LIST]   (see --help)
//
// --seqmassage times another build's executable (e.g. a baseline) in parts 2 and 3.
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "cli/arguments.hpp"
#include "geometry/distance.hpp"
#include "geometry/distance_meter.hpp"
#include "geometry/shear.hpp"
#include "io/atomic_file.hpp"
#include "io/frame_folder.hpp"
#include "io/obj.hpp"
#include "io/sha256.hpp"
#include "massage/massage.hpp"
#include "core/timing.hpp"
#include "pipeline/outputs/output_distortion.hpp"
#include "pipeline/report/report.hpp"
#include "pipeline/sequence/sequence_options.hpp"

using namespace sm;
namespace fs = std::filesystem;

void spacing_table(const fs::path& dir);
void iterations_table(const fs::path& dir, const std::vector<int>& counts,
                      const std::vector<double>& tolerances);

namespace {

std::vector<std::string> split_list(const std::string& list) {
  std::vector<std::string> items;
  for (size_t at = 0; at < list.size();) {
    const size_t comma = std::min(list.find(',', at), list.size());
    items.push_back(list.substr(at, comma - at));
    at = comma + 1;
  }
  return items;
}

struct ChildRun {
  bool ok = false;
  double seconds = 0.0;      ///< wall
  double cpu_seconds = 0.0;  ///< user + system: the work done, less sensitive to other load
  long max_rss_kb = 0;
  /// Sum of the frames' processing times (summary.csv "seconds"): divided by the wall time, the
  /// frames processed at once on average (what the pipeline overlaps, whatever the cores give).
  double frame_seconds = 0.0;
};

// Runs `seqmassage config --quiet [--threads N]` and measures it from here: wall time and the
// child's peak resident set.
const char* g_seqmassage = SEQMASSAGE_BIN;

ChildRun run_job(const fs::path& config, int threads, const fs::path& log) {
  ChildRun run;
  const std::string threads_arg = std::to_string(threads);
  const auto t0 = Clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) return run;
  if (pid == 0) {
    std::FILE* out = std::fopen(log.c_str(), "w");
    if (out) {
      ::dup2(::fileno(out), 1);
      ::dup2(::fileno(out), 2);
    }
    ::execl(g_seqmassage, g_seqmassage, config.c_str(), "--quiet", "--threads", threads_arg.c_str(),
            static_cast<char*>(nullptr));
    std::_Exit(127);
  }
  int status = 0;
  struct rusage usage {};
  if (::wait4(pid, &status, 0, &usage) != pid) return run;
  run.seconds = seconds_since(t0);
  run.max_rss_kb = usage.ru_maxrss;
  run.cpu_seconds = usage.ru_utime.tv_sec + 1e-6 * usage.ru_utime.tv_usec + usage.ru_stime.tv_sec +
                    1e-6 * usage.ru_stime.tv_usec;
  run.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  return run;
}

// The sum of summary.csv's per-frame seconds (each frame's processing, wall), 0 if unreadable.
double frame_seconds(const fs::path& summary) {
  std::ifstream in(summary);
  std::string line;
  if (!std::getline(in, line)) return 0.0;
  int column = 0, seconds_column = -1;
  for (const std::string& name : split_list(line)) {
    if (name == "seconds") seconds_column = column;
    ++column;
  }
  double sum = 0.0;
  while (seconds_column >= 0 && std::getline(in, line)) {
    const std::vector<std::string> cells = split_list(line);
    if (int(cells.size()) > seconds_column && !cells[size_t(seconds_column)].empty())
      sum += std::stod(cells[size_t(seconds_column)]);
  }
  return sum;
}

ChildRun best_of(const fs::path& config, int threads, const fs::path& log, int repeat,
                 const fs::path& summary = {}) {
  ChildRun best;
  for (int k = 0; k < repeat; ++k) {
    ChildRun r = run_job(config, threads, log);
    if (!r.ok) return r;
    if (!summary.empty()) r.frame_seconds = frame_seconds(summary);
    if (k == 0 || r.seconds < best.seconds) best = r;
  }
  return best;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

std::string json_path(const fs::path& p) {
  std::string s;
  for (char c : p.string()) {
    if (c == '"' || c == '\\') s += '\\';
    s += c;
  }
  return "\"" + s + "\"";
}

// CPU time of the calling thread: the stages run on one thread, and CPU time is not inflated
// when other processes take the cores (wall time is, on a shared machine).
double thread_seconds() {
  timespec ts{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// Stage timings of the per-frame work, one thread, mirroring process_frame; the first frame is
// the template. `quiet`: the summary only, not a line per frame.
void stages(const fs::path& crane, const fs::path& scratch, bool quiet) {
  tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
  const std::vector<fs::path> frames = list_frames(crane, ".obj");
  const double t_setup = thread_seconds();
  const TriMesh templ = read_obj(frames.front()).mesh;
  const MassageOptions options;
  const Massager massager(templ, options, "template");
  // As the job's frame processor: layout built once, workspace pooled.
  const DistanceMeter meter(templ.F, templ.num_vertices(), massager.shared_topology(),
                            default_sequence_measures());
  const double setup = thread_seconds() - t_setup;
  double read = 0, optimize = 0, measure = 0, write = 0, hash = 0, shear = 0, distance = 0;
  double hashed = 0;  // bytes
  // Inside optimize: the frame's Reference, and the iterations' own timers (wall time of the
  // thread, which on one thread is close to its CPU time).
  double reference_seconds = 0, closest = 0, assemble = 0, solve = 0;
  int iterations = 0, count = 0;
  size_t hashes = 0;
  fs::create_directories(scratch / "frames");
  fs::create_directories(scratch / "distortion");
  for (size_t k = 1; k < frames.size(); ++k) {
    double t0 = thread_seconds();
    const std::string bytes = read_file(frames[k]);
    const ObjFile file = parse_obj(bytes, frames[k].string());
    read += (thread_seconds() - t0);

    t0 = thread_seconds();
    const Reference reference(file.mesh, options.samples, "frame", massager.shared_topology(),
                              &massager.template_bvh());
    reference_seconds += thread_seconds() - t0;
    const MassageResult result = massager.run(file.mesh.V, reference);
    optimize += (thread_seconds() - t0);
    iterations += static_cast<int>(result.iterations.size());
    for (const IterationStats& it : result.iterations) {
      closest += it.seconds_closest;
      assemble += it.seconds_assemble;
      solve += it.seconds_solve;
    }

    t0 = thread_seconds();
    const Eigen::VectorXd before = shear_distortion(templ.V, file.mesh.V, templ.F);
    const Eigen::VectorXd after = shear_distortion(templ.V, result.V, templ.F);
    const DistortionSummary sb = summarize_distortion(before), sa = summarize_distortion(after);
    const double t_shear = (thread_seconds() - t0);
    const FrameDistances distances =
        meter.measure(file.mesh, reference.bvh(), reference.planes(), result.V);
    measure += (thread_seconds() - t0);
    shear += t_shear;
    distance += (thread_seconds() - t0) - t_shear;

    t0 = thread_seconds();
    const std::string obj = format_obj(file, result.V);
    const std::string csv = format_distortion_csv(before, after);
    write_file_atomic(scratch / "frames" / frames[k].filename(), obj);
    write_file_atomic(
        scratch / "distortion" / fs::path(frames[k].filename()).replace_extension(".csv"), csv);
    write += (thread_seconds() - t0);

    t0 = thread_seconds();  // the frame record's hashes: the input as read, the two outputs
    hashes += sha256_hex(bytes).size() + sha256_hex(obj).size() + sha256_hex(csv).size();
    hash += (thread_seconds() - t0);
    hashed += double(bytes.size() + obj.size() + csv.size());
    ++count;
    if (!quiet)
      std::printf(
        "  %s: shear max %.4g -> %.4g, mean %.4g -> %.4g | dist out->in max %.3e rms %.3e, "
        "in->out max %.3e rms %.3e | %d its\n",
        frames[k].filename().string().c_str(), sb.max, sa.max, sb.mean, sa.mean, distances.moved_to_original.max,
        distances.moved_to_original.rms, distances.original_to_moved.max, distances.original_to_moved.rms, static_cast<int>(result.iterations.size()));
  }
  const double total = read + optimize + measure + write + hash;
  std::printf(
      "stages, 1 thread, CPU time, %d optimized frames of %d vertices (template setup %.1f ms,"
      " once):\n"
      "  read     %7.1f ms/frame  (%4.1f%%)\n"
      "  optimize %7.1f ms/frame  (%4.1f%%)  %.1f ms per iteration, %.1f iterations/frame\n"
      "           reference %.1f ms, iterations: closest %.1f, assemble %.1f, solve %.1f ms, "
      "the rest (run set-up, relabelling, fold check) %.1f ms\n"
      "  measure  %7.1f ms/frame  (%4.1f%%)  shear %.1f ms, distances %.1f ms\n"
      "  write    %7.1f ms/frame  (%4.1f%%)  formatted, written atomically\n"
      "  hash     %7.2f ms/frame  (%4.1f%%)  SHA-256 of the input and outputs for the record, "
      "%.0f MB/s\n"
      "  total    %7.1f ms/frame, %.1f frames/s on one thread\n",
      count, templ.num_vertices(), 1e3 * setup, 1e3 * read / count, 100 * read / total,
      1e3 * optimize / count, 100 * optimize / total, 1e3 * optimize / iterations,
      double(iterations) / count, 1e3 * reference_seconds / count, 1e3 * closest / count,
      1e3 * assemble / count, 1e3 * solve / count,
      1e3 * (optimize - reference_seconds - closest - assemble - solve) / count,
      1e3 * measure / count, 100 * measure / total, 1e3 * shear / count,
      1e3 * distance / count, 1e3 * write / count, 100 * write / total, 1e3 * hash / count,
      100 * hash / total, hashed / hash / 1e6, 1e3 * total / count,
      count / total);
  if (hashes == 0) std::printf("(no frame)\n");
}

}  // namespace

int main(int argc, char** argv) {
  fs::path data = fs::path(SEQMASSAGE_SOURCE_DIR) / ".." / "shared" / "data";
  fs::path keep, stages_dir;
  bool quiet_frames = false;
  std::string seqmassage = g_seqmassage;
  int repeat = 3, short_frames = 50, long_frames = 1000;
  bool no_memory = false, no_stages = false, no_job = false, tables = false, spacing = false,
       iterations = false;
  std::vector<int> iteration_counts = {5, 8, 10, 12, 15};
  std::vector<double> tolerances = {1e-3, 3e-3};
  CLI::App app(
      "Usage: bench_sequence [options]\n\n"
      "The sequence job's per-frame stages on the Vlasic crane (one thread, CPU time), the whole\n"
      "job as a child process (wall time, peak memory), memory against sequence length and, on\n"
      "request, the option tables. Prints timings; asserts nothing.\n",
      "bench_sequence");
  sm::cli::set_conventions(app, 30);
  app.add_option("--data", data, "the real data (default ../shared/data)")->type_name("DIR");
  app.add_option("--repeat", repeat, "whole job: best of R runs (default 3)")
      ->type_name("R")
      ->transform(sm::cli::integer_in(1, 1000));
  app.add_option("--short", short_frames, "memory: the shorter generated sequence (default 50)")
      ->type_name("N")
      ->transform(sm::cli::integer_in(2, 100000));
  app.add_option("--long", long_frames, "memory: the longer generated sequence (default 1000)")
      ->type_name("N")
      ->transform(sm::cli::integer_in(2, 100000));
  app.add_option("--stages-dir", stages_dir,
                 "the per-frame stages on this folder of OBJ frames (the first is the template) "
                 "instead of the crane")
      ->type_name("DIR");
  app.add_flag("--quiet-frames", quiet_frames, "stages: the summary only, no line per frame");
  app.add_flag("--no-memory", no_memory, "skip memory against sequence length");
  app.add_flag("--no-stages", no_stages, "skip the per-frame stages");
  app.add_flag("--no-job", no_job, "skip the whole job");
  app.add_option("--keep", keep, "scratch folder, kept (default: a temporary one, removed)")
      ->type_name("DIR");
  app.add_option("--seqmassage", seqmassage, "the executable timed in the whole job and memory")
      ->type_name("PATH")
      ->check(CLI::ExistingFile.description(""));
  app.add_flag("--tables", tables, "both option tables");
  app.add_flag("--spacing-table", spacing, "the distances' cost and accuracy per sampling");
  app.add_flag("--iterations-table", iterations,
               "quality against massage.iterations and massage.tolerance");
  app.add_option("--iterations", iteration_counts, "iteration counts of that table (5,8,10,12,15)")
      ->type_name("LIST")
      ->delimiter(',')
      ->transform(sm::cli::integer_in(1, 10000));
  // massage.tolerance >= 0: above the largest negative double
  app.add_option("--tolerances", tolerances, "tolerances of that table (1e-3,3e-3)")
      ->type_name("LIST")
      ->delimiter(',')
      ->transform(sm::cli::number_in(-std::numeric_limits<double>::denorm_min(), INFINITY, ">= 0"));
  if (const auto code = sm::cli::parse_or_exit(app, argc, argv)) return *code;
  g_seqmassage = seqmassage.c_str();
  const bool memory = !no_memory, stage_timings = !no_stages, job = !no_job;
  if (tables) spacing = iterations = true;
  const fs::path scratch =
      keep.empty() ? fs::temp_directory_path() / ("bench_sequence." + std::to_string(::getpid()))
                   : keep;
  fs::create_directories(scratch);
  std::printf("bench_sequence: seqmassage %s, scratch %s\n", g_seqmassage,
              scratch.string().c_str());

  const fs::path crane = data / "sequences" / "vlasic_crane";
  if (!stages_dir.empty()) {
    if (stage_timings) stages(stages_dir, scratch / "stages", quiet_frames);
  } else if (!fs::exists(crane / "frame_0000.obj")) {
    std::printf("crane: skipped, %s not found (the real data lives in ../shared/data)\n",
                crane.string().c_str());
  } else if (stage_timings) {
    stages(crane, scratch / "stages", quiet_frames);
  }
  if (job && fs::exists(crane / "frame_0000.obj")) {
    const int frames = static_cast<int>(list_frames(crane, ".obj").size());
    const fs::path config = scratch / "crane.json";
    write_text(config, "{ \"job\": \"sequence\", \"input\": { \"frames\": " +
                           json_path(fs::absolute(crane)) +
                           " },\n  \"output\": { \"dir\": " + json_path(scratch / "crane") +
                           ", \"per_triangle_csv\": true },\n  \"template\": { \"frame\": 0 } }\n");
    std::printf(
        "whole job, `seqmassage crane.json --quiet --threads N` (%d frames, I/O included, "
        "best of %d):\n",
        frames, repeat);
    for (int threads : {1, 2}) {
      const ChildRun r = best_of(config, threads, scratch / "crane.log", repeat,
                                 scratch / "crane" / "summary.csv");
      if (!r.ok) {
        std::printf("  %d thread(s): FAILED, see %s\n", threads,
                    (scratch / "crane.log").string().c_str());
        continue;
      }
      std::printf(
          "  %d thread(s): %7.3f s wall (%6.3f s CPU, %.2f cores busy), %6.1f frames/s, max RSS "
          "%6.1f MB; frames in progress at once %.2f\n",
          threads, r.seconds, r.cpu_seconds, r.cpu_seconds / r.seconds, frames / r.seconds,
          r.max_rss_kb / 1024.0, r.frame_seconds / r.seconds);
    }
  }

  if (memory) {
    std::printf("memory against sequence length (generated bending tube, 2 threads):\n");
    for (int frames : {short_frames, long_frames}) {
      const fs::path config = scratch / ("tube" + std::to_string(frames) + ".json");
      write_text(config, "{ \"job\": \"sequence\", \"input\": { \"synthetic\": { \"frames\": " +
                             std::to_string(frames) + " } },\n  \"output\": { \"dir\": " +
                             json_path(scratch / ("tube" + std::to_string(frames))) +
                             ", \"per_triangle_csv\": true } }\n");
      const ChildRun r = run_job(config, 2, scratch / "tube.log");
      if (!r.ok) {
        std::printf("  %5d frames: FAILED, see %s\n", frames,
                    (scratch / "tube.log").string().c_str());
        continue;
      }
      std::printf("  %5d frames: max RSS %6.1f MB, %7.2f s wall (%7.2f s CPU), %6.1f frames/s\n",
                  frames, r.max_rss_kb / 1024.0, r.seconds, r.cpu_seconds, frames / r.seconds);
    }
  }
  if (spacing) {
    if (fs::exists(crane / "frame_0000.obj"))
      spacing_table(crane);
    else
      std::printf("spacing table: skipped, %s not found\n", crane.string().c_str());
  }
  if (iterations) {
    for (const char* name : {"vlasic_crane", "vlasic_samba"}) {
      const fs::path dir = data / "sequences" / name;
      if (fs::exists(dir / "frame_0000.obj"))
        iterations_table(dir, iteration_counts, tolerances);
      else
        std::printf("iterations table: %s skipped, not found\n", dir.string().c_str());
    }
  }
  if (keep.empty()) fs::remove_all(scratch);
  return 0;
}
