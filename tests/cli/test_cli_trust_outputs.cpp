// The output side of the trust boundary, from the command line: a second writer into an output
// folder (or shard) is refused with exit 4 naming the lock's holder, a lock left by a killed run
// is taken over with a warning and the outputs are those of a normal run; SIGHUP stops a run like
// SIGTERM; a closed stderr (SIGPIPE) does not end a run; merge's hint is a command.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <chrono>
#include <thread>

#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "pipeline/cluster/output_lock.hpp"
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

std::string host() {
  char buffer[256] = {};
  ::gethostname(buffer, sizeof buffer - 1);
  return buffer;
}

// Frames of a drifting tube in dir/in and a config writing dir/out (no timings).
void make_job(const fs::path& dir, int frames, const std::string& extra = "") {
  write_synthetic_sequence(make_synthetic_sequence(test::small_tube(frames)), dir / "in",
                           dir / "gt");
  write_text(dir / "job.json", R"({"job": "sequence", "input": {"frames": "in"},
    "output": {"dir": "out", "per_triangle_csv": true, "timings": false},
    "massage": {"iterations": 4}, "threads": 2)" +
                                   extra + "}");
}

bool has_lock_file(const fs::path& dir) {
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.path().filename().string().find("lock") != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("a second writer into an output folder or shard exits 4 naming the lock's holder",
          "[cli][trust][lock]") {
  test::TempDir dir("cli_lock");
  make_job(dir.path(), 4);
  const auto inputs = test::folder_bytes(dir / "in");
  const std::string pid = std::to_string(::getpid());
  {
    const OutputLock held = lock_output_folder(dir / "out");  // this test process holds it
    const test::CliRun r = test::run_cli(dir.path(), "job.json");
    CHECK(r.code == 4);
    CHECK_THAT(r.err, Contains("seqmassage: I/O error: output folder '") &&
                          Contains("' is in use: its lock file '") &&
                          Contains("out/.seqmassage.lock' is held by host " + host() + ", pid " +
                                   pid + ", since ") &&
                          Contains("one writer per output folder (and shard)"));
    CHECK(test::names_of(test::folder_bytes(dir / "out")) ==
          std::vector<std::string>{".seqmassage.lock"});  // nothing else written
    // A shard while a whole run holds the folder, and the same shard twice.
    CHECK(test::run_cli(dir.path(), "--shard 1/2 job.json").code == 4);
  }
  {
    const OutputLock shard = lock_output_folder(dir / "out", {1, 2});
    const test::CliRun r = test::run_cli(dir.path(), "--shard 1/2 job.json");
    CHECK(r.code == 4);
    CHECK_THAT(r.err, Contains(".seqmassage-shard-1-of-2.lock' is held by host " + host() +
                               ", pid " + pid));
    const test::CliRun merge = test::run_cli(dir.path(), "merge out");
    CHECK(merge.code == 4);
    CHECK_THAT(merge.err, Contains("held by the shards running there: shard 1/2 (host "));
    CHECK(test::run_cli(dir.path(), "-q --shard 0/2 job.json").code == 0);  // its neighbour runs
  }
  CHECK(test::folder_bytes(dir / "in") == inputs);
  CHECK_FALSE(has_lock_file(dir / "out"));
  for (const auto& entry : fs::recursive_directory_iterator(dir / "out"))
    CHECK(entry.path().string().find(".seqmassage-tmp") == std::string::npos);
}

TEST_CASE(
    "a lock left by a killed run is taken over with a warning; the outputs are a normal "
    "run's",
    "[cli][trust][lock]") {
  test::TempDir dir("cli_lock_stale");
  make_job(dir.path(), 4);
  REQUIRE(test::run_cli(dir.path(), "-q job.json").code == 0);
  CHECK_FALSE(has_lock_file(dir / "out"));
  const auto reference = test::folder_bytes(dir / "out");
  fs::remove_all(dir / "out");
  write_file_atomic(dir / "out/.seqmassage.lock",
                    "host " + host() + "\npid 999999999\nstarted 2026-01-01T00:00:00Z\n");
  const test::CliRun r = test::run_cli(dir.path(), "job.json");
  CHECK(r.code == 0);
  CHECK_THAT(r.err, Contains("seqmassage: warning: took over the lock file '") &&
                        Contains("' left by host " + host() + ", pid 999999999"));
  CHECK(test::folder_bytes(dir / "out") == reference);  // byte for byte, no lock file left
}

TEST_CASE("SIGHUP stops a run like SIGTERM (exit 129), and --resume finishes",
          "[cli][trust][signals]") {
  test::TempDir dir("cli_hup");
  SyntheticOptions tube = test::small_tube(200);
  tube.segments = 24;
  tube.rings = 24;
  write_synthetic_sequence(make_synthetic_sequence(tube), dir / "in", dir / "gt");
  write_text(dir / "job.json", R"({"job": "sequence", "input": {"frames": "in"},
    "output": {"dir": "out", "timings": false}, "massage": {"iterations": 8},
    "frames_in_flight": 2, "threads": 1})");
  const pid_t pid = test::spawn_cli(dir.path(), {"job.json"});
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (!fs::exists(dir / "out/records/frame_0002.json") && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(pid, SIGHUP);
  CHECK(test::wait_cli(pid) == 129);
  const nlohmann::json report = nlohmann::json::parse(read_file(dir / "out/report.json"));
  CHECK(report["interrupted"] == true);
  CHECK(int(report["totals"]["frames_written"]) < 200);
  CHECK_FALSE(has_lock_file(dir / "out"));
  const test::CliRun r = test::run_cli(dir.path(), "--resume --frames 0:4 job.json");
  CHECK(r.code == 0);
  CHECK_THAT(r.err, Contains("seqmassage: resume: "));
}

TEST_CASE("a closed stderr does not end a run (SIGPIPE ignored): the outputs complete",
          "[cli][trust][signals]") {
  test::TempDir dir("cli_pipe");
  make_job(dir.path(), 6);
  SECTION("stderr and stdout a pipe whose reader is gone") {
    int fds[2];
    REQUIRE(::pipe(fds) == 0);
    ::close(fds[0]);  // every write gets EPIPE (and SIGPIPE, unless ignored)
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
      if (::dup2(fds[1], 1) < 0 || ::dup2(fds[1], 2) < 0 || ::chdir(dir.path().c_str()) != 0)
        ::_exit(97);
      ::signal(SIGPIPE, SIG_DFL);  // as a shell starts it
      ::execl(SEQMASSAGE_BIN, SEQMASSAGE_BIN, "job.json", static_cast<char*>(nullptr));
      ::_exit(98);
    }
    ::close(fds[1]);
    CHECK(test::wait_cli(pid) == 0);
  }
  SECTION("stderr piped into head -c 10") {
    const std::string command = "cd " + test::shell_quote(dir.path().string()) + " && (" +
                                test::shell_quote(SEQMASSAGE_BIN) +
                                " job.json >/dev/null; echo $? >code.txt) 2>&1 | head -c 10 "
                                ">head.txt";
    REQUIRE(std::system(command.c_str()) == 0);
    CHECK(read_file(dir / "code.txt") == "0\n");
    CHECK(read_file(dir / "head.txt").size() == 10);
  }
  const auto rows = test::read_csv(dir / "out/summary.csv");
  CHECK(rows.size() == 1 + 6);
  CHECK(fs::exists(dir / "out/report.json"));
  CHECK(test::folder_bytes(dir / "out/records").size() == 6);
}

TEST_CASE("merge's hint for missing frames is the command that redoes their shard",
          "[cli][trust][merge]") {
  test::TempDir dir("cli_merge_hint");
  make_job(dir.path(), 6);
  for (const char* shard : {"0/3", "1/3", "2/3"})
    REQUIRE(test::run_cli(dir.path(), std::string("-q --shard ") + shard + " job.json").code == 0);
  fs::remove(dir / "out/records/frame_0003.json");
  fs::remove(dir / "out/records/frame_0005.json");
  const test::CliRun r = test::run_cli(dir.path(), "merge out");
  CHECK(r.code == 3);
  CHECK_THAT(r.err, Contains("missing or incomplete frames: frame 3 (frame_0003.obj), frame 5 "
                             "(frame_0005.obj) (first: frame 3 (frame_0003.obj): no record); "
                             "run their shards again: seqmassage --shard 1/3 --resume CONFIG; "
                             "seqmassage --shard 2/3 --resume CONFIG"));
  CHECK_THAT(r.err, Contains("(CONFIG: the config file the shards ran; then merge again: "
                             "seqmassage merge out)"));
  CHECK(r.err.find("(?)") == std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out/summary.csv"));
  // The hint, followed, merges.
  for (const char* shard : {"1/3", "2/3"})
    REQUIRE(
        test::run_cli(dir.path(), std::string("-q --shard ") + shard + " --resume job.json").code ==
        0);
  CHECK(test::run_cli(dir.path(), "merge -q out").code == 0);
  CHECK_FALSE(has_lock_file(dir / "out"));
}
