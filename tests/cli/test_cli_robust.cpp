// Unattended runs from the command line: SIGKILL at random moments leaves complete files only and
// --resume finishes with the bytes of an uninterrupted run; SIGTERM stops cleanly (exit 143);
// failed frames give exit 5; shards run as parallel processes and `seqmassage merge` combine into
// the bytes of one run, and merge names what is missing.
#include <catch2/catch.hpp>
#include <chrono>
#include <fstream>
#include <random>
#include <thread>

#include <sys/wait.h>

#include "io/atomic_file.hpp"
#include "io/obj.hpp"
#include "pipeline/cluster/frame_record.hpp"
#include "pipeline/sequence/synthetic.hpp"
#include "support/cli_process.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"
#include "support/text_files.hpp"

using namespace sm;
using test::write_text;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Clock = std::chrono::steady_clock;

namespace {

// A config reading the frames in `in`, writing to `out`: 8 iterations, per-triangle tables, no
// timings (every output byte reproducible).
std::string job(const std::string& extra = R"(, "threads": 2)") {
  return R"({"job": "sequence", "input": {"frames": "in"},
    "output": {"dir": "out", "per_triangle_csv": true, "timings": false},
    "massage": {"iterations": 8})" +
         extra + "}";
}

int count_records(const fs::path& out) {
  int n = 0;
  std::error_code ec;
  for (fs::directory_iterator it(out / "records", ec), end; !ec && it != end; it.increment(ec))
    n += it->path().extension() == ".json";
  return n;
}

bool is_temporary(const fs::path& p) {
  const std::string name = p.filename().string();
  return name.size() > kTempSuffix.size() &&
         name.compare(name.size() - kTempSuffix.size(), kTempSuffix.size(), kTempSuffix) == 0;
}

bool has_temporary(const fs::path& out) {
  std::error_code ec;
  for (fs::recursive_directory_iterator it(out, ec), end; !ec && it != end; it.increment(ec))
    if (is_temporary(it->path())) return true;
  return false;
}

// Whether `pid` has ended, leaving it to be reaped by test::wait_cli.
bool has_ended(pid_t pid) {
  siginfo_t info{};
  return ::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
         info.si_pid == pid;
}

// Checks that every file under `out` but temporaries is complete: OBJ frames parse with the
// template's vertex count, CSV tables have their header and whole rows, JSON parses, and every
// record's outputs are there with their size and SHA-256. Returns the number of temporaries.
int require_complete_files(const fs::path& out, int vertices) {
  int temporaries = 0;
  if (!fs::exists(out)) return 0;
  for (const auto& entry : fs::recursive_directory_iterator(out)) {
    if (!entry.is_regular_file()) continue;
    const fs::path& p = entry.path();
    INFO(p.string());
    if (is_temporary(p)) {
      ++temporaries;
      continue;
    }
    const std::string ext = p.extension().string();
    const std::string text = read_file(p);
    if (ext == ".obj") {
      CHECK(read_obj(p).mesh.num_vertices() == vertices);
    } else if (ext == ".csv") {
      REQUIRE_FALSE(text.empty());
      CHECK(text.back() == '\n');
      const size_t columns = std::count(text.begin(), text.begin() + text.find('\n'), ',');
      size_t at = 0;
      for (size_t end; (end = text.find('\n', at)) != std::string::npos; at = end + 1) {
        const std::string line = text.substr(at, end - at);
        if (line.find('"') == std::string::npos)
          CHECK(size_t(std::count(line.begin(), line.end(), ',')) == columns);
      }
    } else if (ext == ".json") {
      const nlohmann::json j = nlohmann::json::parse(text);
      if (p.parent_path().filename() == "records") {
        const FrameRecord r = frame_record_from_json(j);
        CHECK(check_recorded_outputs(r, out, true) == "");
      }
    } else if (ext == ".bin") {  // report_data/: the player's data, magic and counts first
      CHECK(text.rfind("SMHTML", 0) == 0);
      CHECK(text.size() > 16);
    } else if (ext == ".html") {  // report.html, whole
      CHECK(text.rfind("<!DOCTYPE html>", 0) == 0);
      CHECK(text.size() > 8);
      CHECK(text.compare(text.size() - 8, 8, "</html>\n") == 0);
    } else if (ext == ".lock") {  // the killed run's lock file: host and pid, taken over next
      CHECK(p.filename().string().rfind(".seqmassage", 0) == 0);
    } else {
      FAIL("unexpected file");
    }
  }
  return temporaries;
}

}  // namespace

TEST_CASE("SIGKILL at random moments leaves complete files; --resume ends with the same bytes") {
  test::TempDir dir("cli_kill");
  SyntheticOptions tube = test::small_tube(30);
  tube.segments = 24;
  tube.rings = 24;
  write_synthetic_sequence(make_synthetic_sequence(tube), dir / "in", dir / "gt");
  const int vertices = 24 * 25;
  write_text(dir / "job.json", job());

  const test::CliRun whole = test::run_cli(dir.path(), "-q job.json");
  REQUIRE(whole.code == 0);
  fs::rename(dir / "out", dir / "whole");  // same output path for both: report.json names it

  // Each round resumes and is killed at an event of the run, never after a guessed time: once a
  // random number of the remaining frames are recorded, and on odd rounds only when a temporary
  // is also on disk (a write in flight). The deadline only bounds a hung run.
  std::mt19937 rng(20240611);  // reproducible targets
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  int temporaries = 0, kills = 0;
  for (int round = 0; round < 6; ++round) {
    const int done = count_records(dir / "out");
    const int target = done + int(uniform(rng) * (30 - done) * 0.8);
    const bool mid_write = round % 2 == 1;
    const pid_t pid = test::spawn_cli(dir.path(), {"--resume", "job.json"});
    REQUIRE(pid > 0);
    const auto deadline = Clock::now() + std::chrono::seconds(120);
    while (Clock::now() < deadline && !has_ended(pid) &&
           (count_records(dir / "out") < target || (mid_write && !has_temporary(dir / "out"))))
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    ::kill(pid, SIGKILL);
    const int status = test::wait_cli(pid);
    kills += status == 128 + SIGKILL;
    INFO("round " << round << ", exit " << status << ", " << done << " frames done before");
    temporaries += require_complete_files(dir / "out", vertices);
  }
  // Most rounds die by the signal (one may finish first when its target is near the end and the
  // machine is fast).
  CHECK(kills >= 3);
  const test::CliRun last = test::run_cli(dir.path(), "--resume job.json");
  REQUIRE(last.code == 0);
  CHECK_THAT(last.err, Contains("seqmassage: resume: "));
  CHECK(require_complete_files(dir / "out", vertices) == 0);  // the killed writers' are gone
  test::compare_folders(dir / "whole", dir / "out");
  WARN("killed " << kills << " of 6 runs, " << temporaries << " temporaries seen after kills");
}

TEST_CASE("SIGTERM stops after the frames in flight with exit 143, and --resume finishes") {
  test::TempDir dir("cli_term");
  SyntheticOptions tube = test::small_tube(200);
  tube.segments = 24;
  tube.rings = 24;
  write_synthetic_sequence(make_synthetic_sequence(tube), dir / "in", dir / "gt");
  write_text(dir / "job.json", job(R"(, "frames_in_flight": 2, "threads": 1)"));  // slow
  const pid_t pid = test::spawn_cli(dir.path(), {"job.json"});
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (!fs::exists(dir / "out/records/frame_0002.json") && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(pid, SIGTERM);
  CHECK(test::wait_cli(pid) == 143);
  const nlohmann::json report = nlohmann::json::parse(read_file(dir / "out/report.json"));
  CHECK(report["interrupted"] == true);
  const int written = report["totals"]["frames_written"];
  CHECK(written < 200);
  CHECK(test::folder_bytes(dir / "out/records").size() == size_t(written));
  const test::CliRun r = test::run_cli(dir.path(), "--resume --frames 0:12 job.json");
  CHECK(r.code == 0);
  CHECK_THAT(r.err, Contains("seqmassage: resume: "));
}

TEST_CASE("failed frames exit with code 5 and are reported; with \"skip\" they are not written") {
  test::TempDir dir("cli_failed");
  write_synthetic_sequence(make_synthetic_sequence(test::small_tube(4)), dir / "in", dir / "gt");
  // A tracking glitch: one vertex of frame 2 flung 5 units away folds the corrected frame.
  test::edit_obj_vertices(dir / "in/frame_0002.obj", [](int v, double& x, double&, double&) {
    if (v == 40) x += 5.0;
  });
  // (Coordinates beyond 1e18 are an input error of the reader now, not an optimizer failure:
  // tests/cli/test_cli_trust.cpp; the optimizer's failure is tests/pipeline/run/test_numerical_safety.)
  write_text(dir / "job.json",
             job(R"(, "checks": {"max_folded_triangles": 0, "repair_folds": false})"));
  test::CliRun r = test::run_cli(dir.path(), "job.json");
  CHECK(r.code == 5);
  CHECK_THAT(r.err, Contains("seqmassage: frame 2 (frame_0002.obj) failed, written unchanged: "
                             "folded triangles: "));
  CHECK_THAT(r.err, Contains("more than checks.max_folded_triangles = 0"));
  CHECK_THAT(r.err, Contains("seqmassage: 1 of 4 frames failed (see out/summary.csv)"));
  CHECK(read_file(dir / "out/frames/frame_0002.obj") == read_file(dir / "in/frame_0002.obj"));
  CHECK_THAT(read_file(dir / "out/summary.csv"), Contains(",failed,\"folded triangles: "));

  write_text(dir / "job.json",
             R"({"job": "sequence", "input": {"frames": "in"},
      "output": {"dir": "out", "on_failure": "skip"}, "massage": {"iterations": 8},
      "checks": {"max_folded_triangles": 0, "repair_folds": false}})");
  r = test::run_cli(dir.path(), "job.json");
  CHECK(r.code == 5);
  CHECK_THAT(r.err, Contains("frame 2 (frame_0002.obj) failed, not written: folded triangles"));
  CHECK_FALSE(fs::exists(dir / "out/frames/frame_0002.obj"));
  CHECK(fs::exists(dir / "out/frames/frame_0003.obj"));
  CHECK(fs::exists(dir / "out/frames/frame_0001.obj"));
}

TEST_CASE("3 shards in parallel processes, merged, give the bytes of one run") {
  test::TempDir dir("cli_shards");
  write_synthetic_sequence(make_synthetic_sequence(test::small_tube(10)), dir / "in", dir / "gt");
  write_text(dir / "job.json", job());
  REQUIRE(test::run_cli(dir.path(), "-q job.json").code == 0);
  fs::rename(dir / "out", dir / "single");

  std::vector<pid_t> shards;
  for (int i = 0; i < 3; ++i)
    shards.push_back(
        test::spawn_cli(dir.path(), {"--shard", std::to_string(i) + "/3", "job.json"}));
  for (pid_t pid : shards) CHECK(test::wait_cli(pid) == 0);
  CHECK_FALSE(fs::exists(dir / "out/summary.csv"));
  CHECK(fs::exists(dir / "out/summary.shard-2-of-3.csv"));
  test::CliRun m = test::run_cli(dir.path(), "merge out");
  REQUIRE(m.code == 0);
  CHECK(m.out == "results: out/ (summary.csv, report.json, report.html)\n");
  CHECK(m.err == "seqmassage: merged 3 shards, 10 frames (0 failed)\n");
  test::compare_folders(dir / "single", dir / "out", ".shard-");
  CHECK(require_complete_files(dir / "out", 132) == 0);

  // One shard's output removed: merge names the shard and its frames, and writes nothing.
  fs::remove(dir / "out/summary.csv");
  fs::remove(dir / "out/report.json");
  fs::remove(dir / "out/report.shard-1-of-3.json");
  fs::remove(dir / "out/summary.shard-1-of-3.csv");
  for (int t = 3; t < 6; ++t) {
    const std::string name = "frame_000" + std::to_string(t);
    fs::remove(dir / ("out/frames/" + name + ".obj"));
    fs::remove(dir / ("out/distortion/" + name + ".csv"));
    fs::remove(dir / ("out/records/" + name + ".json"));
  }
  m = test::run_cli(dir.path(), "merge out");
  CHECK(m.code == 3);
  CHECK_THAT(m.err, Contains("cannot merge 3 shards:"));
  CHECK_THAT(m.err, Contains("shard 1/3: no report.shard-1-of-3.json; missing frames 3 "
                             "(frame_0003.obj) to 5 (frame_0005.obj); run it: seqmassage "
                             "--shard 1/3 --resume CONFIG"));
  CHECK_FALSE(fs::exists(dir / "out/summary.csv"));

  // The shard, run again (resuming: nothing of it is left, so all of it), completes the merge.
  REQUIRE(test::run_cli(dir.path(), "-q --shard 1/3 --resume job.json").code == 0);
  REQUIRE(test::run_cli(dir.path(), "merge -q out").code == 0);
  test::compare_folders(dir / "single", dir / "out", ".shard-");
}

TEST_CASE("merge: usage, help, and a folder without shards") {
  test::TempDir dir("cli_merge_usage");
  test::CliRun r = test::run_cli(dir.path(), "merge --help");
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("Usage: seqmassage merge [options] OUTPUT_DIR"));
  r = test::run_cli(dir.path(), "--help");
  CHECK_THAT(r.out, Contains("seqmassage merge [options] OUTPUT_DIR"));
  CHECK_THAT(r.out, Contains("--shard I/N"));
  CHECK_THAT(r.out, Contains("--resume"));
  CHECK_THAT(r.out, Contains("143  terminated (SIGTERM"));
  r = test::run_cli(dir.path(), "merge");
  CHECK(r.code == 2);
  r = test::run_cli(dir.path(), "merge .");
  CHECK(r.code == 3);
  CHECK_THAT(r.err, Contains("no shard reports (report.shard-I-of-N.json); run the shards with "
                             "--shard I/N first"));
  r = test::run_cli(dir.path(), "merge missing");
  CHECK(r.code == 4);
}
