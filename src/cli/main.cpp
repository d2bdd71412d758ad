/// seqmassage: the command line. Parses arguments, runs the job of a config file with a progress
/// display, and is the only place that catches exceptions, mapping them to exit codes.
#include <malloc.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "cli/arguments.hpp"
#include "cli/help.hpp"
#include "cli/signals.hpp"
#include "config/config.hpp"
#include "config/complete.hpp"
#include "config/reference.hpp"
#include "core/errors.hpp"
#include "core/options_table.hpp"
#include "pipeline/mesh_jobs/measure_files.hpp"
#include "pipeline/cluster/merge.hpp"
#include "pipeline/mesh_jobs/mesh_job.hpp"
#include "pipeline/mesh_jobs/mesh_report.hpp"
#include "pipeline/report/report.hpp"
#include "pipeline/run/sequence_report.hpp"
#include "pipeline/mesh_jobs/mesh_job_text.hpp"
#include "pipeline/report/run_text.hpp"
#include "pipeline/run/sequence_job.hpp"
#include "pipeline/sequence/shard.hpp"
#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/track/track_job.hpp"
#include "pipeline/track/track_merge.hpp"

namespace {

namespace fs = std::filesystem;

enum ExitCode : int {
  kOk = 0,
  kInternal = 1,
  kUsage = sm::cli::kUsageExit,  // usage and config errors
  kInput = 3,
  kIo = 4,
  kProcessing = 5,
};  // a run stopped by a signal: 128 + its number (sm::cli::stopped_exit_code)

using sm::cli::UsageError;

// --threads N of every command: an integer in [0, sm::kMaxThreads], 0 = one per core.
CLI::Option* add_threads(CLI::App& app, int& threads, const std::string& description) {
  return app.add_option("--threads", threads, description)
      ->type_name("N")
      ->transform(sm::cli::integer_in(0, sm::kMaxThreads));
}

// "seqmassage 0.1.0 (Eigen 3.4.0, oneTBB 2021.8, nlohmann-json 3.11.2, gcc 12.2.0)"
std::string version_text() {
  const nlohmann::json v = sm::version_info();
  return "seqmassage " + v["seqmassage"].get<std::string>() + " (Eigen " +
         v["eigen"].get<std::string>() + ", oneTBB " + v["onetbb"].get<std::string>() +
         ", nlohmann-json " + v["nlohmann_json"].get<std::string>() + ", " +
         v["compiler"].get<std::string>() + ")\n";
}

struct Args {
  fs::path config;
  std::optional<int> threads;
  std::optional<std::string> frames;
  std::optional<std::string> shard;
  bool resume = false;
  bool dry_run = false;
  bool quiet = false;
};

// A config file named on the command line is a regular file, checked the same way by every
// command that takes one (running it, `config --complete`): one message, one exit code (usage).
void check_config_path(const fs::path& config) {
  std::error_code ec;
  if (!fs::is_regular_file(config, ec))
    throw UsageError{"seqmassage", "config file '" + config.string() + "' " +
                                       (fs::exists(config, ec) ? "is not a file"
                                                               : "does not exist")};
}

Args parse_args(int argc, char** argv) {
  Args out;
  CLI::App app(sm::cli::kHelp, "seqmassage");
  sm::cli::set_conventions(app, 24);
  app.footer(sm::cli::run_help_footer());
  app.set_version_flag("--version", version_text, "print the version and exit");
  int threads = 0;
  std::string frames, shard;
  std::vector<std::string> positional;
  const CLI::Option* threads_given =
      add_threads(app, threads,
                  "worker threads (overrides \"threads\"; 0 = one per core; the frames\n"
                  "in flight at once are \"frames_in_flight\" in the config)");
  const CLI::Option* frames_given =
      app.add_option("--frames", frames,
                     "process the frames with index A, A+STEP, ... before B (0-based, in\n"
                     "natural order; B may be empty for \"to the end\"; a single index N is\n"
                     "N:N+1); overrides \"input.range\"")
          ->type_name("A:B[:STEP]");
  app.add_flag("--dry-run", out.dry_run,
               "check the config and every input, print what would be done, write\nnothing");
  app.add_flag("--resume", out.resume,
               "skip the frames whose record (records/<frame>.json) shows complete\n"
               "outputs made with the same config, template and input (sets \"resume\")");
  const CLI::Option* shard_given =
      app.add_option("--shard", shard,
                     "run shard I (0-based) of N: the I-th of N contiguous blocks of the\n"
                     "selected frames (sets \"shard\"); its summary and report are\n"
                     "summary.shard-I-of-N.csv and report.shard-I-of-N.json, and\n"
                     "'seqmassage merge OUTPUT_DIR' combines the shards")
          ->type_name("I/N");
  app.add_flag("-q,--quiet", out.quiet, "no progress and no summary; errors and failed frames only");
  app.add_option("CONFIG", positional);
  sm::cli::parse(app, argc, argv);
  if (threads_given->count() > 0) out.threads = threads;
  if (frames_given->count() > 0) out.frames = frames;
  if (shard_given->count() > 0) out.shard = shard;

  const auto fail = [](const std::string& message) { throw UsageError{"seqmassage", message}; };
  if (positional.empty()) fail("missing the config file (seqmassage CONFIG.json)");
  if (positional.size() > 1)
    fail("one config file only, got " + std::to_string(positional.size()));
  out.config = positional[0];
  check_config_path(out.config);
  return out;
}

std::string shown(const fs::path& p) {
  std::error_code ec;
  const fs::path rel = fs::proximate(p, ec);
  return ec ? p.string() : rel.string();
}

// Progress on stderr: a bar redrawn in place on a terminal, one line per frame otherwise.
class Progress {
 public:
  Progress(bool quiet, bool terminal, sm::OnFailure on_failure)
      : quiet_(quiet), terminal_(terminal), on_failure_(on_failure) {}

  void frame(const sm::FrameSummary& f, int done, int total, double elapsed) {
    if (f.status == sm::FrameStatus::Failed) {
      clear();
      std::cerr << "seqmassage: " << sm::frame_failure_text(f, on_failure_) << "\n";
    }
    if (quiet_) return;
    if (terminal_) {
      std::cerr << "\r" << sm::progress_bar_text(done, total, elapsed) << "   " << std::flush;
      drawn_ = true;
      if (done == total) clear();
    } else {
      std::cerr << sm::frame_progress_text(f, done, total, elapsed) << "\n";
    }
  }

  void clear() {
    if (drawn_) std::cerr << "\r" << std::string(79, ' ') << "\r" << std::flush;
    drawn_ = false;
  }

 private:
  bool quiet_;
  bool terminal_;
  sm::OnFailure on_failure_;
  bool drawn_ = false;
};

// "results: DIR/ (a, b, c)" on stdout.
void print_results(const fs::path& dir, const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
  std::cout << "results: " << shown(dir) << "/ (" << list << ")\n";
}

int run_mesh_job(const Args& args, sm::MeshJobOptions config);
int run_track(const Args& args, sm::TrackJobOptions config);

int run(const Args& args) {
  sm::AnyJobOptions any = sm::load_any_config(args.config);
  if (auto* mesh_job = std::get_if<sm::MeshJobOptions>(&any))
    return run_mesh_job(args, std::move(*mesh_job));
  if (auto* track_job = std::get_if<sm::TrackJobOptions>(&any))
    return run_track(args, std::move(*track_job));
  sm::SequenceJobOptions config = std::get<sm::SequenceJobOptions>(std::move(any));
  if (args.threads) config.threads = *args.threads;
  if (args.frames) config.input.range = sm::parse_frame_range(*args.frames, "--frames");
  if (args.shard) config.shard = sm::parse_shard(*args.shard, "--shard");
  if (args.resume) config.resume = true;
  const sm::SequencePlan plan = sm::plan_sequence_job(config);
  if (args.dry_run) {
    std::cout << sm::describe_plan(plan) << "dry run: nothing written\n";
    return kOk;
  }
  if (!args.quiet) {
    for (const std::string& w : plan.warnings) std::cerr << "seqmassage: warning: " << w << "\n";
    std::cerr << "seqmassage: " << sm::run_start_text(plan) << "\n";
  }

  Progress progress(args.quiet, ::isatty(STDERR_FILENO) == 1, plan.config.output.on_failure);
  sm::RunHooks hooks;
  hooks.cancel = &sm::cli::stop_requested();
  hooks.notice = [&](const std::string& w) {
    if (!args.quiet) std::cerr << "seqmassage: warning: " << w << "\n";
  };
  hooks.progress = [&](const sm::FrameSummary& f, int done, int total, double elapsed) {
    progress.frame(f, done, total, elapsed);
  };
  sm::cli::catch_stop_signals(true);
  const sm::SequenceResult result = sm::run_sequence_job(plan, hooks);
  sm::cli::catch_stop_signals(false);
  progress.clear();

  const fs::path& out = plan.config.output.dir;
  const std::string summary = sm::summary_file_name(plan.config.shard);
  if (!args.quiet) {
    if (plan.config.resume) std::cerr << "seqmassage: " << sm::resume_text(result) << "\n";
    std::cerr << "seqmassage: " << sm::run_end_text(result) << "\n";
    print_results(out, sm::run_output_names(plan));
    if (plan.config.shard.sharded() && !result.interrupted)
      std::cout << "when every shard is done: seqmassage merge " << shown(out) << "\n";
  }
  if (result.interrupted) {
    const int sig = sm::cli::stop_signal();
    std::cerr << "seqmassage: " << sm::cli::stopped_text(sig) << " after " << result.frames.size()
              << " of " << plan.run_frames.size()
              << " frames; they are written and listed in " << shown(out / summary)
              << "; run again with --resume to finish\n";
    return sm::cli::stopped_exit_code(sig);
  }
  if (result.failed > 0) {
    std::cerr << "seqmassage: " << result.failed << " of " << result.frames.size()
              << " frames failed (see " << shown(out / summary) << ")\n";
    return kProcessing;
  }
  return kOk;
}

// ---------------------------------------------------------------------------------------------
// The single-mesh jobs (remesh, crossparam, smooth) and the measure and merge commands.

int run_mesh_job(const Args& args, sm::MeshJobOptions config) {
  for (const auto& [given, option] :
       {std::pair{args.frames.has_value(), "--frames"},
        std::pair{args.shard.has_value(), "--shard"}, std::pair{args.resume, "--resume"}})
    if (given)
      throw sm::ConfigError(std::string(option) + ": only for \"job\": \"sequence\" (this is a " +
                            sm::job_name(config.job) + " job)");
  if (args.threads) config.threads = *args.threads;
  const sm::MeshJobPlan plan = sm::plan_mesh_job(config);
  if (args.dry_run) {
    std::cout << sm::describe_mesh_plan(plan) << "dry run: nothing written\n";
    return kOk;
  }
  if (!args.quiet) {
    for (const std::string& w : plan.warnings) std::cerr << "seqmassage: warning: " << w << "\n";
    std::cerr << "seqmassage: " << sm::mesh_job_start_text(plan) << "\n";
  }
  const sm::MeshJobResult result = sm::run_mesh_job(plan);
  for (size_t i = plan.warnings.size(); i < result.warnings.size(); ++i)
    std::cerr << "seqmassage: warning: " << result.warnings[i] << "\n";
  const fs::path& out = plan.config.output.dir;
  if (!args.quiet) {
    std::cout << sm::format_mesh_job_table(plan, result);
    std::cerr << "seqmassage: " << sm::mesh_job_end_text(result) << "\n";
    print_results(out, sm::mesh_job_output_names(plan, result));
  }
  if (!result.ok()) {
    std::cerr << "seqmassage: the optimizer failed, no mesh written: " << result.massage.failure
              << " (see " << shown(out / "report.json") << ")\n";
    return kProcessing;
  }
  return kOk;
}

// The track job: frames in order, one progress line each; lost frames are listed and end the
// run with the processing exit code, like failed frames of a sequence.
int run_track(const Args& args, sm::TrackJobOptions config) {
  if (args.resume && !args.quiet)  // the scheduler scripts pass it for every job
    std::cerr << "seqmassage: warning: --resume: a track job keeps no per-frame records; the "
                 "frames are tracked again\n";
  if (args.shard) config.shard = sm::parse_shard(*args.shard, "--shard");
  if (args.threads) config.threads = *args.threads;
  if (args.frames) config.input.range = sm::parse_frame_range(*args.frames, "--frames");
  const sm::TrackPlan plan = sm::plan_track_job(config);
  if (args.dry_run) {
    std::cout << sm::describe_track_plan(plan) << "dry run: nothing written\n";
    return kOk;
  }
  if (!args.quiet)
    for (const std::string& w : plan.warnings) std::cerr << "seqmassage: warning: " << w << "\n";
  sm::TrackHooks hooks;
  hooks.cancel = &sm::cli::stop_requested();
  hooks.progress = [&](const sm::TrackRow& r, int done, int total, double elapsed) {
    if (args.quiet && r.status != sm::TrackStatus::Lost) return;
    char line[256];
    std::snprintf(line, sizeof line,
                  "frame %d (%s) %d/%d: %s, to raw %.3f, from raw %.3f (p99 %.2f), folded %d, "
                  "%.0f s",
                  r.frame, r.file.c_str(), done, total,
                  std::string(sm::name_of(r.status, sm::kTrackStatusNames)).c_str(),
                  r.fit.to_raw_mean, r.fit.from_raw_mean, r.fit.from_raw_p99, r.fit.folded,
                  elapsed);
    std::cerr << "seqmassage: " << line << "\n";
  };
  sm::cli::catch_stop_signals(true);
  const sm::TrackResult result = sm::run_track_job(plan, hooks);
  sm::cli::catch_stop_signals(false);
  const fs::path& out = plan.config.output.dir;
  if (!args.quiet) {
    std::cerr << "seqmassage: tracked " << result.frames.size() << " frames (" << result.lost
              << " lost, " << result.recovered << " recovered) in " << std::lround(result.seconds)
              << " s\n";
    std::vector<std::string> names = sm::result_names(plan.outputs.outputs, {});
    names.push_back(sm::summary_file_name(plan.config.shard));
    names.push_back(sm::report_file_name(plan.config.shard));
    print_results(out, names);
    if (plan.config.shard.sharded() && !result.interrupted)
      std::cout << "when every shard is done: seqmassage merge " << shown(out) << "\n";
  }
  if (result.interrupted) {
    const int sig = sm::cli::stop_signal();
    std::cerr << "seqmassage: " << sm::cli::stopped_text(sig) << " after " << result.frames.size()
              << " of " << plan.block.size() << " frames; they are written and listed in "
              << shown(out / sm::summary_file_name(plan.config.shard)) << "\n";
    return sm::cli::stopped_exit_code(sig);
  }
  if (result.lost > 0) {
    for (const sm::TrackRow& r : result.frames)
      if (r.status == sm::TrackStatus::Lost)
        std::cerr << "seqmassage: frame " << r.frame << " (" << r.file << ") lost: " << r.beyond
                  << "\n";
    std::cerr << "seqmassage: " << result.lost << " of " << result.frames.size()
              << " frames lost (written as their best attempt; see "
              << shown(out / sm::summary_file_name(plan.config.shard)) << ")\n";
    return kProcessing;
  }
  return kOk;
}

// "seqmassage measure ..." (argv[0] is "measure").
sm::MeasureFilesRequest parse_measure_args(int argc, char** argv) {
  sm::MeasureFilesRequest out;
  CLI::App app(sm::cli::kMeasureHelp, "seqmassage measure");
  sm::cli::set_conventions(app, 26);
  app.footer(sm::cli::kMeasureHelpFooter);
  const CLI::Validator file_name(
      [](std::string& v) { return v.empty() ? "expected a file name, got \"\"" : ""; }, "");
  std::string templ, csv, json;
  std::vector<std::string> positional;
  app.add_option("--template", templ, "shear of MESH against the mesh T (MESH's connectivity)")
      ->type_name("T")
      ->check(file_name);
  app.add_option("--spacing", out.options.spacing,
                 "sample spacing, fraction of the mean edge length (default 0.25)")
      ->type_name("X")
      ->transform(sm::cli::number_in(0, INFINITY, "> 0"));
  app.add_option("--feature-angle", out.options.feature_angle,
                 "dihedral angle in degrees above which an edge is sharp (default 30)")
      ->type_name("D")
      ->transform(sm::cli::number_in(0, 180, "in (0, 180)"));
  app.add_option("--csv", csv, "also write the row as CSV (the columns of measures.csv)")
      ->type_name("FILE")
      ->check(file_name);
  app.add_option("--json", json, "also write the measures as JSON")
      ->type_name("FILE")
      ->check(file_name);
  add_threads(app, out.threads, "worker threads (0 = one per core)");
  app.add_option("MESH REFERENCE", positional);
  sm::cli::parse(app, argc, argv);
  if (positional.size() != 2)
    throw UsageError{"seqmassage measure", "expected two mesh files, MESH and REFERENCE, got " +
                                               std::to_string(positional.size())};
  out.mesh = positional[0];
  out.reference = positional[1];
  out.templ = templ;
  out.csv = csv;
  out.json = json;
  return out;
}

// `seqmassage merge` of a track job's shards: lost frames end it with the processing exit code.
int merge_track(const fs::path& dir, bool quiet) {
  const sm::TrackMergeResult result = sm::merge_track_shards(dir);
  if (!quiet) {
    for (const std::string& w : result.notices) std::cerr << "seqmassage: warning: " << w << "\n";
    std::cerr << "seqmassage: merged " << result.shards << " shards, " << result.frames.size()
              << " frames (" << result.lost << " lost, " << result.recovered << " recovered)\n";
    std::string seams;
    for (const sm::TrackSeam& seam : result.seams)
      seams += (seams.empty() ? "" : ", ") + std::to_string(seam.frame);
    if (!seams.empty())
      std::cerr << "seqmassage: seams (tracked from the template, not the frame before): frames "
                << seams << "\n";
    print_results(dir, result.written);
  }
  for (const sm::TrackRow& r : result.frames)
    if (r.status == sm::TrackStatus::Lost)
      std::cerr << "seqmassage: frame " << r.frame << " (" << r.file << ") lost: " << r.beyond
                << "\n";
  return result.lost > 0 ? kProcessing : kOk;
}

// "seqmassage merge [options] OUTPUT_DIR" (argv[0] is "merge").
int run_merge_command(int argc, char** argv) {
  bool quiet = false;
  std::vector<std::string> positional;
  CLI::App app(sm::cli::kMergeHelp, "seqmassage merge");
  sm::cli::set_conventions(app, 16);
  app.footer(sm::cli::kMergeHelpFooter);
  app.add_flag("-q,--quiet", quiet, "print nothing but errors");
  app.add_option("OUTPUT_DIR", positional);
  sm::cli::parse(app, argc, argv);
  if (positional.size() != 1)
    throw UsageError{"seqmassage merge",
                     "expected one output folder, got " + std::to_string(positional.size())};
  const fs::path dir = positional[0];
  if (sm::shard_job(dir) == "track") return merge_track(dir, quiet);
  const sm::MergeResult result = sm::merge_shards(dir);
  for (const std::string& w : result.notices)
    if (!quiet) std::cerr << "seqmassage: warning: " << w << "\n";
  if (!quiet) {
    std::cerr << "seqmassage: merged " << result.shards << " shards, " << result.frames.size()
              << " frames (" << result.failed << " failed)\n";
    print_results(dir, result.written);
  }
  if (result.failed > 0) {
    for (const sm::FrameSummary& f : result.frames)
      if (f.status == sm::FrameStatus::Failed)
        std::cerr << "seqmassage: frame " << f.frame << " (" << f.file << ") failed: " << f.failure
                  << "\n";
    return kProcessing;
  }
  return kOk;
}

// Runs `body`, mapping the library's exceptions to exit codes (the only place that catches).
template <class Body>
int guarded(Body&& body, const std::string& config_name) {
  try {
    return body();
  } catch (const UsageError& e) {
    return sm::cli::report(e);
  } catch (const sm::cli::InfoShown&) {
    return kOk;
  } catch (const sm::ConfigError& e) {
    const std::string what = e.what();  // command-line options name themselves
    std::cerr << "seqmassage: "
              << (what.rfind("--", 0) == 0 || config_name.empty() ? "" : config_name + ": ") << what
              << "\n";
    return kUsage;
  } catch (const sm::OptionError& e) {  // the jobs name the path (with_option_path): a fallback
    std::cerr << "seqmassage: " << e.what() << "\n";
    return kUsage;
  } catch (const sm::InputError& e) {
    std::cerr << "seqmassage: input error: " << e.what() << "\n";
    return kInput;
  } catch (const sm::IoError& e) {
    std::cerr << "seqmassage: I/O error: " << e.what() << "\n";
    return kIo;
  } catch (const sm::SolverError& e) {
    std::cerr << "seqmassage: processing error: " << e.what() << "\n";
    return kProcessing;
  } catch (const std::exception& e) {
    std::cerr << "seqmassage: internal error: " << e.what() << "\n";
    return kInternal;
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Every frame allocates and frees the same few large arrays (positions, grids, systems). With
  // glibc's defaults each of them is a fresh mmap whose pages fault in again, and the heap is
  // trimmed after every free, so a long sequence spends a share of its CPU time in the kernel.
  // Keeping them on the heap (blocks up to glibc's 32 MB cap) and the freed memory for reuse
  // removes it without raising peak memory (docs/performance.md has the figures).
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  // A closed stderr or stdout (piped into `head`) must not end a run: its writes fail, the
  // outputs still complete.
  sm::cli::ignore_broken_pipes();
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "merge") return guarded([&] { return run_merge_command(argc - 1, argv + 1); }, "");
  if (command == "config") {
    const std::string what = argc > 2 ? argv[2] : "";
    const std::string file = what == "--complete" && argc == 4 ? argv[3] : "";
    return guarded(
        [&] {
          if (what == "--reference" && argc == 3)
            std::cout << sm::config_reference();
          else if (!file.empty()) {
            check_config_path(file);
            std::cout << sm::complete_config_file(file);
          }
          else
            throw UsageError{"seqmassage",
                             "config takes --reference (the configuration reference) or "
                             "--complete FILE (FILE with every key spelled out)"};
          return int(kOk);
        },
        file);
  }
  if (command == "measure")
    return guarded(
        [&] {
          std::cout << sm::measure_files(parse_measure_args(argc - 1, argv + 1)).table;
          return int(kOk);
        },
        "");
  std::string config_name;
  return guarded(
      [&] {
        const Args args = parse_args(argc, argv);
        config_name = args.config.string();
        return run(args);
      },
      config_name);
}
