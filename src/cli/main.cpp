/// seqmassage: the command line. Parses arguments, runs the job of a config file with a progress
/// display, and is the only place that catches exceptions, mapping them to exit codes.
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
      --threads N       worker threads (overrides "threads"; 0 = one per core)
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

Outputs (under "output.dir"): for a sequence, frames/<input name>.obj (or, with "format": "gltf",
positions/<frame>.bin and sequence.glb), distortion/<frame>.csv (with "per_triangle_csv"),
records/<frame>.json (what made each frame, its summary row and its outputs' SHA-256),
summary.csv (one row per frame) and report.json; for the other jobs, <input file name> (in
"output.format"), measures.csv (before and after), report.json and, with "per_triangle_csv",
triangles.csv. --frames, --resume and --shard apply to sequences only. Every file is written
to a temporary name and renamed when complete, so a killed run leaves complete files only.

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

struct Args {
  fs::path config;
  std::optional<int> threads;
  std::optional<std::string> frames;
  std::optional<std::string> shard;
  bool resume = false;
  bool dry_run = false;
  bool quiet = false;
};

// nullopt: exit with `exit_code` (help, version, usage error).
std::optional<Args> parse_args(int argc, char** argv, int& exit_code) {
  Args args;
  std::vector<std::string> positional;
  auto usage = [&](const std::string& message) {
    std::cerr << "seqmassage: " << message << "\nTry 'seqmassage --help'.\n";
    exit_code = kUsage;
    return std::nullopt;
  };
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    std::optional<std::string> value;
    if (a.rfind("--", 0) == 0 && a.find('=') != std::string::npos) {
      value = a.substr(a.find('=') + 1);
      a = a.substr(0, a.find('='));
    }
    auto take = [&]() -> std::optional<std::string> {
      if (value) return value;
      if (i + 1 < argc) return std::string(argv[++i]);
      return std::nullopt;
    };
    if (a == "-h" || a == "--help") {
      std::cout << kHelp;
      exit_code = kOk;
      return std::nullopt;
    } else if (a == "--version") {
      const nlohmann::json v = sm::version_info();
      std::cout << "seqmassage " << v["seqmassage"].get<std::string>() << " (Eigen "
                << v["eigen"].get<std::string>() << ", oneTBB " << v["onetbb"].get<std::string>()
                << ", nlohmann-json " << v["nlohmann_json"].get<std::string>() << ", "
                << v["compiler"].get<std::string>() << ")\n";
      exit_code = kOk;
      return std::nullopt;
    } else if (a == "--threads") {
      const auto v = take();
      if (!v) return usage("--threads needs a value");
      if (v->empty() || v->size() > 4 || v->find_first_not_of("0123456789") != std::string::npos)
        return usage("--threads: expected an integer in [0, 4096], got \"" + *v + "\"");
      const int n = std::stoi(*v);
      if (n > 4096) return usage("--threads: expected an integer in [0, 4096], got \"" + *v + "\"");
      args.threads = n;
    } else if (a == "--frames") {
      const auto v = take();
      if (!v) return usage("--frames needs a value A:B[:STEP]");
      args.frames = *v;
    } else if (a == "--shard") {
      const auto v = take();
      if (!v) return usage("--shard needs a value I/N");
      args.shard = *v;
    } else if (a == "--resume" && !value) {
      args.resume = true;
    } else if (a == "--dry-run" && !value) {
      args.dry_run = true;
    } else if ((a == "-q" || a == "--quiet") && !value) {
      args.quiet = true;
    } else if (a == "--") {
      for (++i; i < argc; ++i) positional.push_back(argv[i]);
    } else if (a.size() > 1 && a[0] == '-') {
      return usage("unknown option '" + std::string(argv[i]) + "'");
    } else {
      positional.push_back(a);
    }
  }
  if (positional.empty()) return usage("missing the config file (seqmassage CONFIG.json)");
  if (positional.size() > 1)
    return usage("one config file only, got " + std::to_string(positional.size()));
  args.config = positional[0];
  std::error_code ec;
  if (!fs::is_regular_file(args.config, ec))
    return usage("config file '" + args.config.string() + "' " +
                 (fs::exists(args.config, ec) ? "is not a file" : "does not exist"));
  return args;
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

std::string clock_text(double seconds) {
  if (!(seconds >= 0) || seconds > 359999) return "--:--";
  const long s = static_cast<long>(seconds + 0.5);
  char buffer[32];
  if (s >= 3600)
    std::snprintf(buffer, sizeof buffer, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(buffer, sizeof buffer, "%ld:%02ld", s / 60, s % 60);
  return buffer;
}

std::string fixed(double x, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, x);
  return buffer;
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
      std::cerr << "seqmassage: frame " << f.frame << " (" << f.file << ") failed, "
                << (on_failure_ == sm::OnFailure::Skip ? "not written" : "written unchanged")
                << (f.resumed ? " (in an earlier run)" : "") << ": " << f.failure << "\n";
    }
    if (quiet_) return;
    const double rate = elapsed > 0 ? done / elapsed : 0.0;
    const double eta = rate > 0 ? (total - done) / rate : -1.0;
    if (terminal_) {
      const int width = 30;
      const int filled = total > 0 ? width * done / total : width;
      std::string bar(filled, '#');
      bar += std::string(width - filled, '.');
      std::cerr << "\r[" << bar << "] " << done << "/" << total << " frames  " << fixed(rate, 2)
                << " frames/s  ETA " << clock_text(eta) << "   " << std::flush;
      drawn_ = true;
      if (done == total) clear();
    } else {
      std::cerr << "frame " << done << "/" << total << " " << f.file << ": "
                << sm::status_name(f.status) << (f.resumed ? " (kept from an earlier run)" : "")
                << ", mean shear " << fixed(f.shear_before.mean, 4) << " -> "
                << fixed(f.shear_after.mean, 4) << ", " << f.iterations << " iterations, "
                << fixed(rate, 2) << " frames/s, ETA " << clock_text(eta) << "\n";
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
    std::cerr << "seqmassage: " << plan.run_frames.size() << " frames";
    if (plan.config.shard.sharded())
      std::cerr << " (" << sm::shard_label(plan.config.shard) << " of " << plan.selected.size()
                << " selected)";
    std::cerr << ", template " << plan.template_source << ", " << plan.threads << " threads"
              << (plan.config.resume ? ", resuming" : "") << "\n";
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
  const std::string report = sm::report_file_name(plan.config.shard);
  if (!args.quiet) {
    double before = 0, after = 0;
    for (const sm::FrameSummary& f : result.frames) {
      before += f.shear_before.mean;
      after += f.shear_after.mean;
    }
    const double n = std::max<size_t>(1, result.frames.size());
    if (plan.config.resume) {
      std::cerr << "seqmassage: resume: " << result.resumed << " frames kept from earlier runs, "
                << result.frames.size() - size_t(result.resumed) << " processed";
      std::string why;
      for (const auto& [reason, count] : result.redone)
        why += (why.empty() ? "" : ", ") + std::to_string(count) + " " + reason;
      std::cerr << (why.empty() ? "" : " (" + why + ")") << "\n";
    }
    std::cerr << "seqmassage: " << result.frames.size() << " frames in " << fixed(result.seconds, 1)
              << " s (" << result.failed << " failed), mean shear " << fixed(before / n, 4)
              << " -> " << fixed(after / n, 4) << "\n";
    const bool glb = plan.config.output.format == sm::OutputFormat::Gltf;
    const bool sharded = plan.config.shard.sharded();
    std::cout << "results: " << shown(out) << "/ ("
              << (glb ? (sharded ? "positions/, " : "sequence.glb, ") : "frames/, ")
              << (plan.config.output.per_triangle_csv ? "distortion/, " : "") << summary << ", "
              << report << ")\n";
    if (sharded && !result.interrupted)
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
// The single-mesh jobs (remesh, crossparam, smooth) and the measure command.

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
    std::cerr << "seqmassage: " << sm::job_name(config.job) << " " << plan.mesh_name << " ("
              << plan.mesh.num_vertices() << " vertices), " << config.massage.iterations
              << " iterations, " << plan.threads << " threads\n";
  }
  const sm::MeshJobResult result = sm::run_mesh_job(plan);
  for (size_t i = plan.warnings.size(); i < result.warnings.size(); ++i)
    std::cerr << "seqmassage: warning: " << result.warnings[i] << "\n";
  const fs::path& out = plan.config.output.dir;
  if (!args.quiet) {
    std::vector<sm::MeasureRow> rows = {
        {"before", plan.mesh_name, plan.reference_name, &result.before}};
    if (result.after)
      rows.push_back({"after", plan.mesh_name, plan.reference_name, &*result.after});
    const sm::QualitySummary reference_quality =
        sm::summarize_quality(sm::radius_ratio(plan.reference));
    std::cout << sm::format_measures_table(
        rows, config.job == sm::JobKind::Remesh ? &reference_quality : nullptr, plan.template_name);
    std::cerr << "seqmassage: " << result.massage.iterations.size() << " iterations in "
              << fixed(result.seconds_massage, 2) << " s (whole run " << fixed(result.seconds, 2)
              << " s)\n";
    std::cout << "results: " << shown(out) << "/ ("
              << (result.ok() ? plan.output_mesh.filename().string() + ", " : "")
              << "measures.csv, report.json"
              << (plan.config.output.per_triangle_csv ? ", triangles.csv" : "") << ")\n";
  }
  if (!result.ok()) {
    std::cerr << "seqmassage: the optimizer failed, no mesh written: " << result.massage.failure
              << " (see " << shown(out / "report.json") << ")\n";
    return kProcessing;
  }
  return kOk;
}

// Parses "seqmassage measure ..." (argv[0] is "measure"); nullopt: exit with `exit_code`.
std::optional<sm::MeasureFilesRequest> parse_measure_args(int argc, char** argv, int& exit_code) {
  sm::MeasureFilesRequest args;
  std::vector<std::string> positional;
  auto usage = [&](const std::string& message) {
    std::cerr << "seqmassage measure: " << message << "\nTry 'seqmassage measure --help'.\n";
    exit_code = kUsage;
    return std::nullopt;
  };
  auto number = [](const std::string& text, double& out) {
    try {
      size_t used = 0;
      out = std::stod(text, &used);
      return used == text.size() && std::isfinite(out);
    } catch (const std::exception&) {
      return false;
    }
  };
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    std::optional<std::string> value;
    if (a.rfind("--", 0) == 0 && a.find('=') != std::string::npos) {
      value = a.substr(a.find('=') + 1);
      a = a.substr(0, a.find('='));
    }
    auto take = [&]() -> std::optional<std::string> {
      if (value) return value;
      if (i + 1 < argc) return std::string(argv[++i]);
      return std::nullopt;
    };
    if (a == "-h" || a == "--help") {
      std::cout << kMeasureHelp;
      exit_code = kOk;
      return std::nullopt;
    } else if (a == "--template" || a == "--csv" || a == "--json") {
      const auto v = take();
      if (!v || v->empty()) return usage(a + " needs a file name");
      (a == "--template" ? args.templ : a == "--csv" ? args.csv : args.json) = *v;
    } else if (a == "--spacing") {
      const auto v = take();
      double x = 0;
      if (!v || !number(*v, x) || !(x > 0))
        return usage("--spacing: expected a number > 0, got \"" + v.value_or("") + "\"");
      args.options.spacing = x;
    } else if (a == "--feature-angle") {
      const auto v = take();
      double x = 0;
      if (!v || !number(*v, x) || !(x > 0 && x < 180))
        return usage("--feature-angle: expected a number in (0, 180), got \"" + v.value_or("") +
                     "\"");
      args.options.feature_angle = x;
    } else if (a == "--threads") {
      const auto v = take();
      if (!v || v->empty() || v->size() > 4 ||
          v->find_first_not_of("0123456789") != std::string::npos || std::stoi(*v) > 4096)
        return usage("--threads: expected an integer in [0, 4096], got \"" + v.value_or("") + "\"");
      args.threads = std::stoi(*v);
    } else if (a == "--") {
      for (++i; i < argc; ++i) positional.push_back(argv[i]);
    } else if (a.size() > 1 && a[0] == '-') {
      return usage("unknown option '" + std::string(argv[i]) + "'");
    } else {
      positional.push_back(a);
    }
  }
  if (positional.size() != 2)
    return usage("expected two mesh files, MESH and REFERENCE, got " +
                 std::to_string(positional.size()));
  args.mesh = positional[0];
  args.reference = positional[1];
  return args;
}

// "seqmassage merge [options] OUTPUT_DIR" (argv[0] is "merge").
int run_merge_command(int argc, char** argv) {
  bool quiet = false;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::cout << kMergeHelp;
      return kOk;
    } else if (a == "-q" || a == "--quiet") {
      quiet = true;
    } else if (a == "--") {
      for (++i; i < argc; ++i) positional.push_back(argv[i]);
    } else if (a.size() > 1 && a[0] == '-') {
      std::cerr << "seqmassage merge: unknown option '" << a
                << "'\nTry 'seqmassage merge --help'.\n";
      return kUsage;
    } else {
      positional.push_back(a);
    }
  }
  if (positional.size() != 1) {
    std::cerr << "seqmassage merge: expected one output folder, got " << positional.size()
              << "\nTry 'seqmassage merge --help'.\n";
    return kUsage;
  }
  const fs::path dir = positional[0];
  const sm::MergeResult result = sm::merge_shards(dir);
  if (!quiet) {
    std::cerr << "seqmassage: merged " << result.shards << " shards, " << result.frames.size()
              << " frames (" << result.failed << " failed)\n";
    std::string files;
    for (const std::string& f : result.written) files += (files.empty() ? "" : ", ") + f;
    std::cout << "results: " << shown(dir) << "/ (" << files << ")\n";
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

int run_measure(const sm::MeasureFilesRequest& request) {
  std::cout << sm::measure_files(request).table;
  return kOk;
}

// Runs `body`, mapping the library's exceptions to exit codes (the only place that catches).
template <class Body>
int guarded(Body&& body, const std::string& config_name) {
  try {
    return body();
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
  int exit_code = kOk;
  if (argc > 1 && std::string(argv[1]) == "merge")
    return guarded([&] { return run_merge_command(argc - 1, argv + 1); }, "");
  if (argc > 1 && std::string(argv[1]) == "measure") {
    const auto args = parse_measure_args(argc - 1, argv + 1, exit_code);
    if (!args) return exit_code;
    return guarded([&] { return run_measure(*args); }, "");
  }
  const std::optional<Args> args = parse_args(argc, argv, exit_code);
  if (!args) return exit_code;
  return guarded([&] { return run(*args); }, args->config.string());
}
