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
#include "config/config.hpp"
#include "config/reference.hpp"
#include "mesh/errors.hpp"
#include "pipeline/frame_output.hpp"
#include "pipeline/measure_files.hpp"
#include "pipeline/merge.hpp"
#include "pipeline/mesh_job.hpp"
#include "pipeline/mesh_report.hpp"
#include "pipeline/report.hpp"
#include "pipeline/run_text.hpp"
#include "pipeline/sequence_job.hpp"
#include "pipeline/shard.hpp"

namespace {

namespace fs = std::filesystem;

enum ExitCode : int {
  kOk = 0,
  kInternal = 1,
  kUsage = sm::cli::kUsageExit,  // usage and config errors
  kInput = 3,
  kIo = 4,
  kProcessing = 5,
  kInterrupted = 130,  // 128 + SIGINT
  kTerminated = 143,   // 128 + SIGTERM
};

// The help of each command: its description (usage, what it does) and footer (outputs, exit
// status); the options between them are listed from the option definitions below.
constexpr const char* kHelp = R"(Usage: seqmassage [options] CONFIG.json
       seqmassage measure [options] MESH REFERENCE   (see seqmassage measure --help)
       seqmassage merge [options] OUTPUT_DIR         (see seqmassage merge --help)
       seqmassage config --reference

Commands:
  (none)   run the job of CONFIG.json
  measure  print the paper's measures of a mesh against a reference mesh
  merge    combine the shards of a sequence job (--shard I/N) into the outputs of one run
  config   --reference: print every config key, its type, default and meaning (Markdown)

Runs the job of a JSON config file (see README.md; paths in it are relative to the file's folder),
by its "job" key:
  sequence    corrects texture swimming in a captured mesh sequence (Mesh Massage, section 3.1):
              every frame takes the template frame's triangle shapes and stays on its surface
  remesh      brings a remesh closer to its source surface (section 3.3)
  crossparam  copies the triangle shapes of a source mesh onto a target mesh with the same
              connectivity (section 3.2)
  smooth      evens out the triangles while keeping the surface and its sharp features (section 4)
)";

// The footer's outputs of a sequence come from the output registry (sm::outputs_help), between
// these two parts.
constexpr const char* kHelpInputs = R"(Inputs of a sequence ("input"): a folder of OBJ frames ("frames"), a glTF 2.0 animation ("gltf",
with "mesh", "animation" and "fps"), a PC2 or MDD point cache on a mesh ("pc2" or "mdd", with
"mesh": its OBJ, PLY or OFF), or a generated sequence ("synthetic").

Outputs of a sequence, under "output.dir":
)";

constexpr const char* kHelpFooter = R"(  records/<frame>.json        what made each frame, its summary row, its outputs' SHA-256
  summary.csv, report.json    one row per frame; config, totals, warnings, failures
A shard (--shard I/N) names its own summary.shard-I-of-N.csv, report.shard-I-of-N.json and
iterations.shard-I-of-N.csv; 'seqmassage merge' writes summary.csv, report.json,
iterations.csv, and sequence.glb or sequence.pc2/.mdd and rest.obj from them.
Outputs of the other jobs: <input file name> (in "output.format"), measures.csv (before and
after), report.json and, with "per_triangle_csv", triangles.csv.
--frames, --resume and --shard apply to sequences only. Every file is written to a temporary
name and renamed when complete, so a killed run leaves complete files only.

Exit status:
  0    every frame (or the mesh) was processed
  1    internal error (a bug; please report it)
  2    usage or config error: bad option, missing config file, invalid JSON, unknown key,
       wrong type or out-of-range value, an output folder that would overwrite an input
  3    input error: a malformed frame, template or glTF file (the message names the glTF
       element), frames with different vertex counts or faces; for merge, missing,
       incomplete or inconsistent shards (named, with the frames concerned)
  4    I/O error: a file or folder cannot be read or written
  5    processing error: some frames failed (the optimizer failed, non-finite positions, or
       more folded triangles than "checks" allow; reason in summary.csv and on stderr); they
       are written unchanged (or not at all: "output": {"on_failure": "skip"}) and the other
       frames are complete. For a single-mesh job, the optimizer failed: no mesh is written,
       report.json holds the reason
  130  interrupted (Ctrl-C, SIGINT): the frames in flight were finished; the frames done are
       written and listed in summary.csv; --resume continues
  143  terminated (SIGTERM, as schedulers send): the same as 130
A second SIGINT or SIGTERM ends the program at once; like SIGKILL, it leaves complete files
only, and --resume continues.
)";

constexpr const char* kMergeHelp = R"(Usage: seqmassage merge [options] OUTPUT_DIR

Combines the shards of a sequence job run with --shard I/N (every shard writing into OUTPUT_DIR)
into the outputs of one run: summary.csv and report.json, byte for byte what a single unsharded
run of the same config writes (with "output": {"timings": false}; with timings on, the seconds
differ), and for "format": "gltf" sequence.glb (for "pc2" or "mdd": sequence.pc2 or
sequence.mdd and rest.obj), assembled from every shard's positions/ files (this reads the
input again). It checks first that all N shard reports
(report.shard-I-of-N.json) are there and complete, that every shard ran the same job (the same
config apart from "threads" and "frames_in_flight", template and program: their hashes), and
that every selected frame is in exactly one shard, with its record and outputs. The shard files
are left in place.
)";

constexpr const char* kMergeHelpFooter = R"(Exit status: 0 merged; 3 missing or inconsistent shards or frames (the message names them and
the command that redoes them), nothing written; 4 I/O error; 5 merged, but some frames failed
(as for a run).
)";

constexpr const char* kMeasureHelp = R"(Usage: seqmassage measure [options] MESH REFERENCE

Prints the paper's measures of MESH against REFERENCE (any two .obj, .off or .ply meshes), the
same report as the remesh, crossparam and smooth jobs write:
  - Metro-style one-sided distances MESH -> REFERENCE and REFERENCE -> MESH (max, mean, RMS,
    absolute and relative to the bounding-box diagonal of both), sampled on vertices, edges and
    inside triangles, and the symmetric Hausdorff distance;
  - the radius ratio 2r/R of both meshes' triangles (min, mean; 1 = equilateral);
  - the shear distortion (eq. 8) of MESH against the --template, or against REFERENCE when it has
    MESH's connectivity (max, mean, p95, histogram);
  - REFERENCE's sharp edges: their distance to MESH, and with the same connectivity the change of
    their dihedral angles.
)";

constexpr const char* kMeasureHelpFooter = R"(Exit status: 0 success, 2 usage error, 3 input error (malformed mesh, template of another
connectivity), 4 I/O error.
)";

using sm::cli::UsageError;

// --threads N of every command: an integer in [0, 4096], 0 = one per core.
CLI::Option* add_threads(CLI::App& app, int& threads, const std::string& description) {
  return app.add_option("--threads", threads, description)
      ->type_name("N")
      ->transform(sm::cli::integer_in(0, 4096));
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

Args parse_args(int argc, char** argv) {
  Args out;
  CLI::App app(kHelp, "seqmassage");
  sm::cli::set_conventions(app, 24);
  app.footer(kHelpInputs + sm::outputs_help() + kHelpFooter);
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
  std::error_code ec;
  if (!fs::is_regular_file(out.config, ec))
    fail("config file '" + out.config.string() + "' " +
         (fs::exists(out.config, ec) ? "is not a file" : "does not exist"));
  return out;
}

std::atomic<bool> g_interrupted{false};
volatile std::sig_atomic_t g_signal = 0;  // the first SIGINT or SIGTERM received

extern "C" void on_stop_signal(int sig) {
  if (g_signal == 0) g_signal = sig;
  g_interrupted.store(true);
  // A second one ends the program at once (the default action): files stay complete anyway.
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  ::sigaction(SIGINT, &dfl, nullptr);
  ::sigaction(SIGTERM, &dfl, nullptr);
}

// Installs (or, with `on` false, removes) the SIGINT and SIGTERM handler.
void catch_stop_signals(bool on) {
  struct sigaction action {};
  action.sa_handler = on ? on_stop_signal : SIG_DFL;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
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

int run(const Args& args) {
  sm::AnyJobOptions any = sm::load_any_config(args.config);
  if (auto* mesh_job = std::get_if<sm::MeshJobOptions>(&any))
    return run_mesh_job(args, std::move(*mesh_job));
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
  hooks.cancel = &g_interrupted;
  hooks.progress = [&](const sm::FrameSummary& f, int done, int total, double elapsed) {
    progress.frame(f, done, total, elapsed);
  };
  catch_stop_signals(true);
  const sm::SequenceResult result = sm::run_sequence_job(plan, hooks);
  catch_stop_signals(false);
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
    std::cerr << "seqmassage: " << (g_signal == SIGTERM ? "terminated (SIGTERM)" : "interrupted")
              << " after " << result.frames.size() << " of " << plan.run_frames.size()
              << " frames; they are written and listed in " << shown(out / summary)
              << "; run again with --resume to finish\n";
    return g_signal == SIGTERM ? kTerminated : kInterrupted;
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

// "seqmassage measure ..." (argv[0] is "measure").
sm::MeasureFilesRequest parse_measure_args(int argc, char** argv) {
  sm::MeasureFilesRequest out;
  CLI::App app(kMeasureHelp, "seqmassage measure");
  sm::cli::set_conventions(app, 26);
  app.footer(kMeasureHelpFooter);
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

// "seqmassage merge [options] OUTPUT_DIR" (argv[0] is "merge").
int run_merge_command(int argc, char** argv) {
  bool quiet = false;
  std::vector<std::string> positional;
  CLI::App app(kMergeHelp, "seqmassage merge");
  sm::cli::set_conventions(app, 16);
  app.footer(kMergeHelpFooter);
  app.add_flag("-q,--quiet", quiet, "print nothing but errors");
  app.add_option("OUTPUT_DIR", positional);
  sm::cli::parse(app, argc, argv);
  if (positional.size() != 1)
    throw UsageError{"seqmassage merge",
                     "expected one output folder, got " + std::to_string(positional.size())};
  const fs::path dir = positional[0];
  const sm::MergeResult result = sm::merge_shards(dir);
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
  // trimmed after every free: about 5% of the crane job's CPU time went to the kernel. Keeping
  // them on the heap (blocks up to glibc's 32 MB cap) and the freed memory for reuse removes it;
  // peak memory is unchanged (bench_sequence's 50 vs 1000 frames shows that it stays flat).
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "merge") return guarded([&] { return run_merge_command(argc - 1, argv + 1); }, "");
  if (command == "config")
    return guarded(
        [&] {
          if (argc != 3 || std::string(argv[2]) != "--reference")
            throw UsageError{"seqmassage",
                             "config takes --reference (the configuration reference)"};
          std::cout << sm::config_reference();
          return int(kOk);
        },
        "");
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
