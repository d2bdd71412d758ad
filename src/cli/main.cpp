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

#include "io/config.hpp"
#include "mesh/errors.hpp"
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
  kUsage = 2,  // usage and config errors
  kInput = 3,
  kIo = 4,
  kProcessing = 5,
  kInterrupted = 130,  // 128 + SIGINT
  kTerminated = 143,   // 128 + SIGTERM
};

constexpr const char* kHelp = R"(Usage: seqmassage [options] CONFIG.json
       seqmassage measure [options] MESH REFERENCE   (see seqmassage measure --help)
       seqmassage merge [options] OUTPUT_DIR         (see seqmassage merge --help)

Commands:
  (none)   run the job of CONFIG.json
  measure  print the paper's measures of a mesh against a reference mesh
  merge    combine the shards of a sequence job (--shard I/N) into the outputs of one run

Runs the job of a JSON config file (see README.md; paths in it are relative to the file's folder),
by its "job" key:
  sequence    corrects texture swimming in a captured mesh sequence (Mesh Massage, section 3.1):
              every frame takes the template frame's triangle shapes and stays on its surface
  remesh      brings a remesh closer to its source surface (section 3.3)
  crossparam  copies the triangle shapes of a source mesh onto a target mesh with the same
              connectivity (section 3.2)
  smooth      evens out the triangles while keeping the surface and its sharp features (section 4)

Options:
  -h, --help            print this help and exit
      --version         print the version and exit
      --threads N       worker threads (overrides "threads"; 0 = one per core; the frames
                        in flight at once are "frames_in_flight" in the config)
      --frames A:B[:STEP]
                        process the frames with index A, A+STEP, ... before B (0-based, in
                        natural order; B may be empty for "to the end"; a single index N is
                        N:N+1); overrides "input.range"
      --dry-run         check the config and every input, print what would be done, write
                        nothing
      --resume          skip the frames whose record (records/<frame>.json) shows complete
                        outputs made with the same config, template and input (sets "resume")
      --shard I/N       run shard I (0-based) of N: the I-th of N contiguous blocks of the
                        selected frames (sets "shard"); its summary and report are
                        summary.shard-I-of-N.csv and report.shard-I-of-N.json, and
                        'seqmassage merge OUTPUT_DIR' combines the shards
  -q, --quiet           no progress and no summary; errors and failed frames only

Inputs of a sequence ("input"): a folder of OBJ frames ("frames"), a glTF 2.0 animation ("gltf",
with "mesh", "animation" and "fps"), or a generated sequence ("synthetic").

Outputs of a sequence, under "output.dir":
  frames/<input name>.obj     the corrected frames ("format": "obj", the default)
  positions/<frame>.bin, sequence.glb
                              with "format": "gltf" (glTF input): each frame's corrected
                              positions, and the corrected animation as one GLB, a morph
                              target per frame (a shard writes positions/ only)
  distortion/<frame>.csv      shear per triangle before and after ("per_triangle_csv")
  colored/{before,after}/<frame>.ply
                              the shear (eq. 8) as colours, blue to red ("colored")
  checker/{before,after}/<frame>.obj, checker.mtl, checker.png
                              a checkerboard texture on the template's UVs ("checker")
  iterations.csv              the optimizer's figures, iteration by iteration ("iterations")
  records/<frame>.json        what made each frame, its summary row, its outputs' SHA-256
  summary.csv, report.json    one row per frame; config, totals, warnings, failures
A shard (--shard I/N) names its own summary.shard-I-of-N.csv, report.shard-I-of-N.json and
iterations.shard-I-of-N.csv; 'seqmassage merge' writes summary.csv, report.json,
iterations.csv and sequence.glb from them.
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
differ), and for "format": "gltf" sequence.glb, assembled from every shard's positions/ files
(this reads the glTF input again). It checks first that all N shard reports
(report.shard-I-of-N.json) are there and complete, that every shard ran the same job (the same
config apart from "threads" and "frames_in_flight", template and program: their hashes), and
that every selected frame is in exactly one shard, with its record and outputs. The shard files
are left in place.

Options:
  -h, --help    print this help and exit
  -q, --quiet   print nothing but errors

Exit status: 0 merged; 3 missing or inconsistent shards or frames (the message names them and
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

Options:
  -h, --help              print this help and exit
      --template T        shear of MESH against the mesh T (MESH's connectivity)
      --spacing X         sample spacing, fraction of the mean edge length (default 0.25)
      --feature-angle D   dihedral angle in degrees above which an edge is sharp (default 30)
      --csv FILE          also write the row as CSV (the columns of measures.csv)
      --json FILE         also write the measures as JSON
      --threads N         worker threads (0 = one per core)

Exit status: 0 success, 2 usage error, 3 input error (malformed mesh, template of another
connectivity), 4 I/O error.
)";

// A usage error of `command` ("seqmassage", "seqmassage measure"): printed with a pointer to its
// --help, exit 2.
struct UsageError {
  std::string command;
  std::string message;
};

// Help or version printed: exit 0.
struct InfoShown {};

// Walks a command's arguments: options, whose values are given as "--name VALUE" or
// "--name=VALUE", and positional arguments ("--" ends the options).
class ArgReader {
 public:
  ArgReader(std::string command, int argc, char** argv)
      : command_(std::move(command)), argc_(argc), argv_(argv) {}

  // The next option's name ("--threads", "-q"), or false when none is left; the positional
  // arguments on the way are collected.
  bool next(std::string& option) {
    while (++i_ < argc_) {
      std::string a = argv_[i_];
      inline_value_.reset();
      if (a == "--") {
        for (++i_; i_ < argc_; ++i_) positional_.push_back(argv_[i_]);
        return false;
      }
      if (a.size() <= 1 || a[0] != '-') {
        positional_.push_back(a);
        continue;
      }
      if (a.rfind("--", 0) == 0 && a.find('=') != std::string::npos) {
        inline_value_ = a.substr(a.find('=') + 1);
        a = a.substr(0, a.find('='));
      }
      option = a;
      return true;
    }
    return false;
  }
  bool has_value() const { return inline_value_.has_value(); }
  // The option's value, inline or the next argument; nullopt if there is none.
  std::optional<std::string> take() {
    if (inline_value_) return inline_value_;
    if (i_ + 1 < argc_) return std::string(argv_[++i_]);
    return std::nullopt;
  }
  // The option's value; a usage error `missing` if there is none.
  std::string value(const std::string& missing) {
    const auto v = take();
    if (!v) fail(missing);
    return *v;
  }
  [[noreturn]] void fail(const std::string& message) const { throw UsageError{command_, message}; }
  [[noreturn]] void unknown() const { fail("unknown option '" + std::string(argv_[i_]) + "'"); }
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::string command_;
  int argc_;
  char** argv_;
  int i_ = 0;
  std::optional<std::string> inline_value_;
  std::vector<std::string> positional_;
};

// --threads N: an integer in [0, 4096].
int thread_count(const ArgReader& args, const std::string& v) {
  if (v.empty() || v.size() > 4 || v.find_first_not_of("0123456789") != std::string::npos ||
      std::stoi(v) > 4096)
    args.fail("--threads: expected an integer in [0, 4096], got \"" + v + "\"");
  return std::stoi(v);
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
  ArgReader args("seqmassage", argc, argv);
  for (std::string a; args.next(a);) {
    if (a == "-h" || a == "--help") {
      std::cout << kHelp;
      throw InfoShown{};
    } else if (a == "--version") {
      const nlohmann::json v = sm::version_info();
      std::cout << "seqmassage " << v["seqmassage"].get<std::string>() << " (Eigen "
                << v["eigen"].get<std::string>() << ", oneTBB " << v["onetbb"].get<std::string>()
                << ", nlohmann-json " << v["nlohmann_json"].get<std::string>() << ", "
                << v["compiler"].get<std::string>() << ")\n";
      throw InfoShown{};
    } else if (a == "--threads") {
      out.threads = thread_count(args, args.value("--threads needs a value"));
    } else if (a == "--frames") {
      out.frames = args.value("--frames needs a value A:B[:STEP]");
    } else if (a == "--shard") {
      out.shard = args.value("--shard needs a value I/N");
    } else if (a == "--resume" && !args.has_value()) {
      out.resume = true;
    } else if (a == "--dry-run" && !args.has_value()) {
      out.dry_run = true;
    } else if ((a == "-q" || a == "--quiet") && !args.has_value()) {
      out.quiet = true;
    } else {
      args.unknown();
    }
  }
  const std::vector<std::string>& positional = args.positional();
  if (positional.empty()) args.fail("missing the config file (seqmassage CONFIG.json)");
  if (positional.size() > 1)
    args.fail("one config file only, got " + std::to_string(positional.size()));
  out.config = positional[0];
  std::error_code ec;
  if (!fs::is_regular_file(out.config, ec))
    args.fail("config file '" + out.config.string() + "' " +
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

int run_mesh_job(const Args& args, sm::MeshJobConfig config);

int run(const Args& args) {
  sm::AnyJobConfig any = sm::load_any_config(args.config);
  if (auto* mesh_job = std::get_if<sm::MeshJobConfig>(&any))
    return run_mesh_job(args, std::move(*mesh_job));
  sm::JobConfig config = std::get<sm::JobConfig>(std::move(any));
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
    print_results(out, sm::run_output_names(plan, result));
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

int run_mesh_job(const Args& args, sm::MeshJobConfig config) {
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
  ArgReader args("seqmassage measure", argc, argv);
  // A finite number in (low, high) after --name, else a usage error naming `range`.
  auto number = [&](const std::string& name, double low, double high, const std::string& range) {
    const std::string v = args.take().value_or("");
    try {
      size_t used = 0;
      const double x = std::stod(v, &used);
      if (used == v.size() && std::isfinite(x) && x > low && x < high) return x;
    } catch (const std::exception&) {
    }
    args.fail(name + ": expected a number " + range + ", got \"" + v + "\"");
  };
  for (std::string a; args.next(a);) {
    if (a == "-h" || a == "--help") {
      std::cout << kMeasureHelp;
      throw InfoShown{};
    } else if (a == "--template" || a == "--csv" || a == "--json") {
      const std::string v = args.take().value_or("");
      if (v.empty()) args.fail(a + " needs a file name");
      (a == "--template" ? out.templ : a == "--csv" ? out.csv : out.json) = v;
    } else if (a == "--spacing") {
      out.options.spacing = number(a, 0, INFINITY, "> 0");
    } else if (a == "--feature-angle") {
      out.options.feature_angle = number(a, 0, 180, "in (0, 180)");
    } else if (a == "--threads") {
      out.threads = thread_count(args, args.take().value_or(""));
    } else {
      args.unknown();
    }
  }
  if (args.positional().size() != 2)
    args.fail("expected two mesh files, MESH and REFERENCE, got " +
              std::to_string(args.positional().size()));
  out.mesh = args.positional()[0];
  out.reference = args.positional()[1];
  return out;
}

// "seqmassage merge [options] OUTPUT_DIR" (argv[0] is "merge").
int run_merge_command(int argc, char** argv) {
  bool quiet = false;
  ArgReader args("seqmassage merge", argc, argv);
  for (std::string a; args.next(a);) {
    if ((a == "-h" || a == "--help") && !args.has_value()) {
      std::cout << kMergeHelp;
      return kOk;
    } else if ((a == "-q" || a == "--quiet") && !args.has_value()) {
      quiet = true;
    } else {
      args.unknown();
    }
  }
  if (args.positional().size() != 1)
    args.fail("expected one output folder, got " + std::to_string(args.positional().size()));
  const fs::path dir = args.positional()[0];
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
    std::cerr << e.command << ": " << e.message << "\nTry '" << e.command << " --help'.\n";
    return kUsage;
  } catch (const InfoShown&) {
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
