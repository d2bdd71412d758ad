// The seqmassage command line, run as a subprocess on small generated sequences: outputs and
// their columns, determinism across thread counts, bad configs and inputs (exit code and message,
// nothing written), options, interruption.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "pipeline/sequence/synthetic.hpp"
#include "support/cli_process.hpp"
#include "support/gltf_models.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"
#include "support/text_files.hpp"

using namespace sm;
using test::read_csv;
using test::write_text;
namespace fs = std::filesystem;

namespace {

// A folder with frames in `in/` (5 frames of a 12×10 tube) and a config job.json reading them.
struct Fixture {
  test::TempDir dir;
  explicit Fixture(const std::string& name, const std::string& extra = "") : dir(name) {
    write_synthetic_sequence(make_synthetic_sequence(test::small_tube(5)), dir / "in", dir / "gt");
    config("job.json", "out", extra);
  }
  void config(const std::string& file, const std::string& out, const std::string& extra = "") {
    write_text(dir / file, R"({"job": "sequence", "input": {"frames": "in"},
      "output": {"dir": ")" + out +
                               R"(", "per_triangle_csv": true, "timings": false},
      "massage": {"iterations": 8})" +
                               extra + "}");
  }
};

}  // namespace

TEST_CASE("--help documents the options and exit codes, --version the version") {
  test::TempDir dir("cli_help");
  const test::CliRun help = test::run_cli(dir.path(), "--help");
  CHECK(help.code == 0);
  for (const char* text :
       {"Usage: seqmassage [options] CONFIG.json", "--threads N", "--frames A:B[:STEP]",
        "--dry-run", "--quiet", "Exit status:", "  0    every frame",
        "  2    usage or config error", "  3    input error", "  4    I/O error",
        "  5    processing error", "  130  interrupted"})
    CHECK_THAT(help.out, Catch::Contains(text));
  const test::CliRun version = test::run_cli(dir.path(), "--version");
  CHECK(version.code == 0);
  CHECK_THAT(version.out, Catch::StartsWith("seqmassage 0."));
}

TEST_CASE("--help names every command, option and output") {
  test::TempDir dir("cli_help_all");
  const std::string help = test::run_cli(dir.path(), "--help").out;
  for (const char* text :
       {// commands and their own help
        "seqmassage measure [options] MESH REFERENCE", "seqmassage measure --help",
        "seqmassage merge [options] OUTPUT_DIR", "seqmassage merge --help",
        // options
        "-h, --help", "--version", "--threads N", "\"threads\"", "\"frames_in_flight\"",
        "--frames A:B[:STEP]", "--dry-run", "--resume", "--shard I/N", "-q, --quiet",
        // jobs
        "sequence", "remesh", "crossparam", "smooth",
        // outputs of a sequence, of a shard and of the other jobs
        "frames/", "positions/", "sequence.glb", "distortion/", "colored/", ".ply", "checker/",
        "checker.mtl", "checker.png", "iterations.csv", "records/", "summary.csv", "report.json",
        "summary.shard-I-of-N.csv", "report.shard-I-of-N.json", "iterations.shard-I-of-N.csv",
        "measures.csv", "triangles.csv", "\"per_triangle_csv\"", "\"on_failure\"",
        // exit codes
        "  1    internal error", "  143  terminated"})
    CHECK_THAT(help, Catch::Contains(text));
  const test::CliRun measure = test::run_cli(dir.path(), "measure --help");
  CHECK(measure.code == 0);
  for (const char* text : {"--template T", "--spacing X", "--feature-angle D", "--csv FILE",
                           "--json FILE", "--threads N", "-h, --help"})
    CHECK_THAT(measure.out, Catch::Contains(text));
  const test::CliRun merge = test::run_cli(dir.path(), "merge --help");
  CHECK(merge.code == 0);
  for (const char* text : {"-q, --quiet", "-h, --help", "sequence.glb", "Exit status"})
    CHECK_THAT(merge.out, Catch::Contains(text));
}

TEST_CASE("a run writes the documented outputs, and corrects the frames") {
  Fixture f("cli_run");
  const test::CliRun r = test::run_cli(f.dir.path(), "job.json");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("results: "));
  CHECK_THAT(r.err, Catch::Contains("frame 5/5 frame_0004.obj: optimized"));  // not a terminal
  for (int t = 0; t < 5; ++t) {
    const std::string name = "frame_000" + std::to_string(t);
    CHECK(fs::exists(f.dir / ("out/frames/" + name + ".obj")));
    const auto table = read_csv(f.dir / ("out/distortion/" + name + ".csv"));
    REQUIRE(table.size() == 241);
    CHECK(table[0] == std::vector<std::string>{"triangle", "shear_before", "shear_after"});
  }
  CHECK(fs::exists(f.dir / "out/report.json"));
  const auto summary = read_csv(f.dir / "out/summary.csv");
  REQUIRE(summary.size() == 6);
  const std::vector<std::string> documented = {"frame",
                                               "file",
                                               "vertices",
                                               "triangles",
                                               "shear_max_before",
                                               "shear_mean_before",
                                               "shear_p95_before",
                                               "shear_max_after",
                                               "shear_mean_after",
                                               "shear_p95_after",
                                               "dist_out_to_in_max",
                                               "dist_out_to_in_rms",
                                               "dist_in_to_out_max",
                                               "dist_in_to_out_rms",
                                               "iterations",
                                               "seconds"};
  CHECK(std::vector<std::string>(summary[0].begin(), summary[0].begin() + 16) == documented);
  double before = 0, after = 0;
  for (int t = 1; t <= 5; ++t) {
    CHECK(summary[t][0] == std::to_string(t - 1));
    CHECK(summary[t][1] == "frame_000" + std::to_string(t - 1) + ".obj");
    CHECK(summary[t][2] == "132");
    CHECK(summary[t][3] == "240");
    before += std::stod(summary[t][5]);
    after += std::stod(summary[t][8]);
  }
  CHECK(after <= before);
  CHECK(summary[1][16] == "template");
  CHECK(summary[2][16] == "optimized");
  // The template frame is byte-identical to its input.
  CHECK(read_file(f.dir / "out/frames/frame_0000.obj") == read_file(f.dir / "in/frame_0000.obj"));
}

TEST_CASE("one and two threads write the same bytes") {
  Fixture f("cli_threads");
  f.config("job2.json", "out2");
  REQUIRE(test::run_cli(f.dir.path(), "--threads 1 -q job.json").code == 0);
  REQUIRE(test::run_cli(f.dir.path(), "--threads=2 -q job2.json").code == 0);
  int compared = 0;
  for (const auto& entry : fs::recursive_directory_iterator(f.dir / "out")) {
    const fs::path rel = fs::relative(entry.path(), f.dir / "out");
    // The reports hold the resolved config, which names the output folder and thread count.
    if (!entry.is_regular_file() || rel == "report.json" || rel == "report.html") continue;
    INFO(rel.string());
    CHECK(read_file(entry.path()) == read_file(f.dir / "out2" / rel));
    ++compared;
  }
  CHECK(compared == 22);  // 5 frames, 5 tables, 5 records, summary.csv, report_data/ (6 files)
}

TEST_CASE("bad configs exit with code 2, name the key and write nothing") {
  Fixture f("cli_bad_config");
  struct Case {
    std::string extra;
    std::string message;
  };
  const std::vector<Case> cases = {
      {R"(, "massage": {"iteratons": 3})",
       "job.json: massage.iteratons: unknown key (did you mean \"iterations\"?)"},
      {R"(, "massage": {"iterations": "ten"})",
       "job.json: massage.iterations: expected an integer >= 1, got \"ten\""},
      {R"(, "massage": {"mu": 2})",
       "job.json: massage.mu: expected \"auto\" or a number in [0, 1), got 2"},
      {R"(, "threads": 1, "threads": 2)",
       "job.json: threads: duplicate key (each key may appear once)"},
      {R"(, "thread": 2)", "job.json: thread: unknown key (did you mean \"threads\"?)"},
      {R"(, "template": {"frame": 7})",
       "job.json: template.frame: 7 is out of range (the sequence has 5 frames, 0 to 4)"},
  };
  for (const Case& c : cases) {
    // The Fixture's config has "massage"; these replace it.
    std::string text =
        R"({"job": "sequence", "input": {"frames": "in"}, "output": {"dir": "out"})" + c.extra +
        "}";
    write_text(f.dir / "job.json", text);
    const test::CliRun r = test::run_cli(f.dir.path(), "job.json");
    INFO(text);
    CHECK(r.code == 2);
    CHECK(r.err == "seqmassage: " + c.message + "\n");
    CHECK_FALSE(fs::exists(f.dir / "out"));
  }
  write_text(f.dir / "job.json", "{\"job\": \"sequence\", // a comment\n}");
  test::CliRun r = test::run_cli(f.dir.path(), "job.json");
  CHECK(r.code == 2);
  CHECK(r.err == "seqmassage: job.json: line 1, column 21: comments are not allowed in JSON\n");
  CHECK_FALSE(fs::exists(f.dir / "out"));
}

TEST_CASE("usage errors exit with code 2") {
  Fixture f("cli_usage");
  test::CliRun r = test::run_cli(f.dir.path(), "");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::StartsWith("seqmassage: missing the config file"));
  r = test::run_cli(f.dir.path(), "--bogus job.json");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::StartsWith("seqmassage: unknown option '--bogus'"));
  r = test::run_cli(f.dir.path(), "--threads many job.json");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::StartsWith("seqmassage: --threads: expected an integer in [0, 4096]"));
  r = test::run_cli(f.dir.path(), "job.json --threads");
  CHECK(r.code == 2);
  CHECK(r.err == "seqmassage: --threads needs a value N\nTry 'seqmassage --help'.\n");
  r = test::run_cli(f.dir.path(), "--frames 4:2 job.json");
  CHECK(r.code == 2);
  CHECK(r.err == "seqmassage: --frames: B must be >= A, got \"4:2\"\n");
  r = test::run_cli(f.dir.path(), "nowhere.json");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::StartsWith("seqmassage: config file 'nowhere.json' does not exist"));
  CHECK_FALSE(fs::exists(f.dir / "out"));
}

TEST_CASE("config --complete prints the config with every key; bad use exits with code 2") {
  Fixture f("cli_config_complete");
  const std::string before = read_file(f.dir / "job.json");
  test::CliRun r = test::run_cli(f.dir.path(), "config --complete job.json");
  CHECK(r.code == 0);
  CHECK(r.err == "");
  const nlohmann::json completed = nlohmann::json::parse(r.out);
  CHECK(completed["input"]["frames"] == "in");  // as written, not made absolute
  CHECK(completed["massage"]["iterations"] == 8);
  CHECK(completed["massage"]["mu"] == "auto");
  CHECK(completed["checks"]["repair_folds"] == true);
  CHECK(read_file(f.dir / "job.json") == before);  // printed, never written over
  write_text(f.dir / "bad.json", R"({"job": "sequence", "input": {"frames": "in"},
    "output": {"dir": "out"}, "massage": {"iteratons": 8}})");
  r = test::run_cli(f.dir.path(), "config --complete bad.json");
  CHECK(r.code == 2);
  CHECK(r.out == "");
  CHECK(r.err ==
        "seqmassage: bad.json: massage.iteratons: unknown key (did you mean \"iterations\"?)\n");
  for (const char* args : {"config", "config --complete", "config --bogus", "config --reference x"}) {
    INFO(args);
    r = test::run_cli(f.dir.path(), args);
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Catch::StartsWith("seqmassage: config takes --reference"));
  }
}

TEST_CASE("mismatched frames exit with code 3 and write nothing") {
  Fixture f("cli_mismatch");
  const SyntheticSequence other = make_synthetic_sequence(test::small_tube(5, 10));
  write_file_atomic(f.dir / "in/frame_0003.obj",
                    format_synthetic_obj(other, synthetic_frame(other, 3).drifted, "other"));
  const test::CliRun r = test::run_cli(f.dir.path(), "job.json");
  CHECK(r.code == 3);
  CHECK(r.err ==
        "seqmassage: input error: frame 3 (frame_0003.obj): 110 vertices, but the template, "
        "frame 0 (frame_0000.obj), has 132\n");
  CHECK_FALSE(fs::exists(f.dir / "out"));
}

TEST_CASE("a missing frame folder exits with code 4, an overwriting output with 2") {
  Fixture f("cli_io");
  fs::rename(f.dir / "in", f.dir / "frames");
  test::CliRun r = test::run_cli(f.dir.path(), "job.json");
  CHECK(r.code == 4);
  CHECK_THAT(r.err, Catch::StartsWith("seqmassage: I/O error: "));
  CHECK_THAT(r.err, Catch::Contains("in"));
  write_text(f.dir / "over.json",
             R"({"job": "sequence", "input": {"frames": "frames"}, "output": {"dir": "."}})");
  r = test::run_cli(f.dir.path(), "over.json");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::StartsWith("seqmassage: over.json: output.dir: writing "));
  CHECK_THAT(r.err, Catch::Contains("would overwrite an input file"));
  CHECK_FALSE(fs::exists(f.dir / "summary.csv"));
}

TEST_CASE("--dry-run checks and describes, --frames selects, --quiet is quiet") {
  Fixture f("cli_options");
  test::CliRun r = test::run_cli(f.dir.path(), "--dry-run job.json");
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("input: 5 OBJ frames in "));
  CHECK_THAT(r.out, Catch::Contains("template: frame 0 (frame_0000.obj), 132 vertices"));
  CHECK_THAT(r.out, Catch::Contains("dry run: nothing written"));
  CHECK_FALSE(fs::exists(f.dir / "out"));

  r = test::run_cli(f.dir.path(), "--quiet --frames 1:4:2 job.json");
  CHECK(r.code == 0);
  CHECK(r.out.empty());
  CHECK(r.err.empty());
  CHECK(fs::exists(f.dir / "out/frames/frame_0001.obj"));
  CHECK(fs::exists(f.dir / "out/frames/frame_0003.obj"));
  CHECK_FALSE(fs::exists(f.dir / "out/frames/frame_0000.obj"));
  CHECK_FALSE(fs::exists(f.dir / "out/frames/frame_0002.obj"));
  CHECK(read_csv(f.dir / "out/summary.csv").size() == 3);
}

TEST_CASE("a synthetic input runs without outside data and keeps the ground truth") {
  test::TempDir dir("cli_synthetic");
  write_text(dir / "demo.json", R"({"job": "sequence",
    "input": {"synthetic": {"frames": 4, "segments": 12, "rings": 10}},
    "output": {"dir": "demo"}, "massage": {"iterations": 8}})");
  const test::CliRun r = test::run_cli(dir.path(), "demo.json");
  REQUIRE(r.code == 0);
  CHECK(r.out == "results: demo/ (frames/, report_data/, records/, report.html, summary.csv, "
                 "report.json)\n");
  CHECK(fs::exists(dir / "demo/input/frame_0003.obj"));
  CHECK(fs::exists(dir / "demo/ground_truth/frame_0003.obj"));
  CHECK(fs::exists(dir / "demo/frames/frame_0003.obj"));
}

TEST_CASE("a glTF animation runs from the command line to sequence.glb") {
  test::TempDir dir("cli_gltf");
  fs::create_directories(dir / "takes");
  test::skinned_strip().save(dir / "takes/strip.glb", true);
  write_text(dir / "job.json", R"({"job": "sequence",
    "input": {"gltf": "takes/strip.glb", "mesh": "strip", "animation": 0, "fps": 10},
    "output": {"dir": "out", "format": "gltf", "timings": false}, "massage": {"iterations": 5},
    "checks": {"max_folded_fraction": null}})");
  test::CliRun r = test::run_cli(dir.path(), "--dry-run job.json");
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("12 glTF vertices welded to 10 (2 split copies merged)"));
  CHECK_THAT(r.out,
             Catch::Contains("  sequence.glb (11 frames, one morph target each, over 1 mesh"));
  CHECK_FALSE(fs::exists(dir / "out"));

  r = test::run_cli(dir.path(), "job.json");
  REQUIRE(r.code == 0);
  CHECK(r.out == "results: out/ (positions/, sequence.glb, report_data/, records/, report.html, "
                 "summary.csv, report.json)\n");
  CHECK_THAT(r.err, Catch::Contains("frame 11/11 frame_0010.obj: optimized"));
  test::require_valid_gltf(dir / "out/sequence.glb");
  const auto summary = read_csv(dir / "out/summary.csv");
  REQUIRE(summary.size() == 12);
  CHECK(summary[0][18] == "time");
  CHECK(summary[0][19] == "folded_triangles");
  CHECK(summary[11][1] == "frame_0010.obj");
  CHECK(summary[11][2] == "10");  // welded vertices
  CHECK(std::stod(summary[11][18]) == Approx(1.0));

  // Bad glTF: exit code 3, the file and the element named, nothing written.
  fs::remove_all(dir / "out");
  const std::string bytes = read_file(dir / "takes/strip.glb");
  write_file_atomic(dir / "takes/strip.glb", bytes.substr(0, 40));
  r = test::run_cli(dir.path(), "job.json");
  CHECK(r.code == 3);
  CHECK_THAT(r.err, Catch::StartsWith("seqmassage: input error: '") &&
                        Catch::Contains("strip.glb") && Catch::Contains("GLB"));
  CHECK_FALSE(fs::exists(dir / "out"));

  // A GLB output needs a glTF input.
  write_text(dir / "obj.json", R"({"job": "sequence", "input": {"frames": "takes"},
    "output": {"dir": "out", "format": "gltf"}})");
  r = test::run_cli(dir.path(), "obj.json");
  CHECK(r.code == 2);
  CHECK_THAT(r.err,
             Catch::StartsWith("seqmassage: obj.json: output.format: \"gltf\" needs a glTF input"));
}

TEST_CASE("Ctrl-C stops the run with code 130, the frames done are recorded") {
  test::TempDir dir("cli_interrupt");
  write_text(dir / "long.json", R"({"job": "sequence",
    "input": {"synthetic": {"frames": 400, "segments": 24, "rings": 40}},
    "output": {"dir": "out"}, "threads": 1})");
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    if (::chdir(dir.path().c_str()) != 0) ::_exit(99);
    std::freopen("/dev/null", "w", stderr);
    std::freopen("/dev/null", "w", stdout);
    ::execl(SEQMASSAGE_BIN, SEQMASSAGE_BIN, "long.json", static_cast<char*>(nullptr));
    ::_exit(98);
  }
  // Interrupt once the first frame is recorded: an event of the run, not a guess of its speed
  // (the deadline only bounds a hung run).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(dir / "out/records/frame_0000.json") &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  REQUIRE(fs::exists(dir / "out/records/frame_0000.json"));
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  const auto summary = read_csv(dir / "out/summary.csv");
  CHECK(summary.size() < 401);
  CHECK_THAT(read_file(dir / "out/report.json"), Catch::Contains("\"interrupted\": true"));
}
