// An output folder others can write to, and results that travelled before they are published:
// links planted at the temporary names, a symlinked sub-folder, a symlinked or hard-linked lock
// are never written through; merge refuses an output whose bytes are not its record's, a link in
// place of an output and a report whose config hash is not its config's; --resume does not trust a
// record naming a file outside the folder; an input inside the output folder is never overwritten;
// a missing config file gets one message and one exit code from every command.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <functional>

#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "io/sha256.hpp"
#include "pipeline/sequence/synthetic.hpp"
#include "support/cli_process.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"
#include "support/text_files.hpp"

using namespace sm;
using test::write_text;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using json = nlohmann::json;

namespace {

std::string host_tag() {
  char buffer[256] = {};
  ::gethostname(buffer, sizeof buffer - 1);
  std::string host = buffer[0] ? buffer : "localhost";
  for (char& c : host)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return host;
}

// Frames of a drifting tube in dir/in and a config job.json writing dir/out (no timings).
void make_job(const fs::path& dir, int frames, const std::string& extra = "") {
  write_synthetic_sequence(make_synthetic_sequence(test::small_tube(frames)), dir / "in",
                           dir / "gt");
  write_text(dir / "job.json", R"({"job": "sequence", "input": {"frames": "in"},
    "output": {"dir": "out", "timings": false},
    "massage": {"iterations": 3}, "threads": 2)" +
                                   extra + "}");
}

// Every file below `dir` (links not followed) whose name holds a temporary's or a lock's suffix.
std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.find(std::string(kTempSuffix)) != std::string::npos ||
        name.find(".lock") != std::string::npos)
      found.push_back(it->path().lexically_relative(dir).string());
  }
  return found;
}

// Runs seqmassage with `args` in `cwd`, after `plant(pid)` has run with the pid the run will have
// (the child waits on a pipe until the parent has planted what it wants).
test::CliRun run_after_planting(const fs::path& cwd, std::vector<std::string> args,
                                const std::function<void(pid_t)>& plant) {
  const fs::path out = cwd / ".stdout", err = cwd / ".stderr";
  args.insert(args.begin(), SEQMASSAGE_BIN);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int go[2];
  REQUIRE(::pipe(go) == 0);
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    char c;
    ::close(go[1]);
    if (::read(go[0], &c, 1) != 1) ::_exit(95);
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (o < 0 || e < 0 || ::dup2(o, 1) < 0 || ::dup2(e, 2) < 0 || ::chdir(cwd.c_str()) != 0)
      ::_exit(97);
    ::execv(argv[0], argv.data());
    ::_exit(98);
  }
  ::close(go[0]);
  plant(pid);
  const char c = 'g';
  REQUIRE(::write(go[1], &c, 1) == 1);
  ::close(go[1]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return test::finished_run(status, out, err);
}

}  // namespace

TEST_CASE("links planted at the predictable temporary names are never followed",
          "[cli][trust][shared]") {
  test::TempDir dir("shared_tmp");
  make_job(dir.path(), 4);
  const fs::path victim = dir / "victim.txt";
  write_text(victim, "not the run's to write\n");
  const std::string victim_hash = sha256_file(victim);
  // A clean run first: the names its outputs have, and the bytes they must have.
  REQUIRE(test::run_cli(dir.path(), "-q job.json").code == 0);
  const auto expected = test::folder_bytes(dir / "out");
  fs::remove_all(dir / "out");
  std::vector<fs::path> planted;
  const test::CliRun r = run_after_planting(dir.path(), {"-q", "job.json"}, [&](pid_t pid) {
    // The names the old scheme gave: <file>.<host>-<pid>.<counter>.seqmassage-tmp.
    const std::string tag = "." + host_tag() + "-" + std::to_string(pid) + ".";
    for (const auto& [name, bytes] : expected)
      for (int n = 0; n < 40; ++n) {
        const fs::path link = dir / "out" / (name + tag + std::to_string(n) + std::string(kTempSuffix));
        fs::create_directories(link.parent_path());  // every output folder (frames/, records/, ...)
        fs::create_symlink(victim, link);
        planted.push_back(link);
      }
  });
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(sha256_file(victim) == victim_hash);
  for (const fs::path& link : planted) CHECK(fs::is_symlink(link));  // left as they were
  for (const fs::path& link : planted) fs::remove(link);
  CHECK(leftovers(dir / "out").empty());
  // The outputs are regular files with the clean run's bytes.
  const auto got = test::folder_bytes(dir / "out");
  CHECK(test::names_of(got) == test::names_of(expected));
  for (const auto& [name, bytes] : expected) {
    INFO(name);
    CHECK(!fs::is_symlink(dir / "out" / name));
    CHECK(got.at(name) == bytes);
  }
}

TEST_CASE("a link at an output file is replaced, never followed", "[cli][trust][shared]") {
  test::TempDir dir("shared_dest");
  make_job(dir.path(), 3);
  const fs::path victim = dir / "victim.txt";
  write_text(victim, "keep me\n");
  const std::string victim_hash = sha256_file(victim);
  fs::create_directories(dir / "out");
  fs::create_symlink(victim, dir / "out/summary.csv");
  const test::CliRun r = test::run_cli(dir.path(), "-q job.json");
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(sha256_file(victim) == victim_hash);
  CHECK(!fs::is_symlink(dir / "out/summary.csv"));
  CHECK(fs::is_regular_file(dir / "out/summary.csv"));
  CHECK(leftovers(dir / "out").empty());
}

TEST_CASE("a symlinked sub-folder of the output folder is refused, nothing written through it",
          "[cli][trust][shared]") {
  for (const std::string sub : {"frames", "records"}) {
    DYNAMIC_SECTION(sub) {
      test::TempDir dir("shared_sub");
      make_job(dir.path(), 3);
      const auto inputs = test::folder_bytes(dir / "in");
      fs::create_directories(dir / "elsewhere");
      write_text(dir / "elsewhere/keep.txt", "keep\n");
      const std::string keep_hash = sha256_file(dir / "elsewhere/keep.txt");
      fs::create_directories(dir / "out");
      fs::create_symlink(dir / "elsewhere", dir / "out" / sub);
      const test::CliRun r = test::run_cli(dir.path(), "-q job.json");
      CHECK(r.code == 4);
      CHECK_THAT(r.err, Contains("I/O error: refusing to write into '") &&
                            Contains("out/" + sub + "': it is a symbolic link"));
      CHECK(test::names_of(test::folder_bytes(dir / "elsewhere")) ==
            std::vector<std::string>{"keep.txt"});
      CHECK(sha256_file(dir / "elsewhere/keep.txt") == keep_hash);
      CHECK(test::folder_bytes(dir / "in") == inputs);
      CHECK(leftovers(dir / "out").empty());
      CHECK(leftovers(dir / "elsewhere").empty());
    }
  }
}

TEST_CASE("a symlinked or hard-linked lock file is refused and its target left unchanged",
          "[cli][trust][shared][lock]") {
  for (const bool hard : {false, true}) {
    DYNAMIC_SECTION((hard ? "hard link" : "symbolic link")) {
      test::TempDir dir("shared_lock");
      make_job(dir.path(), 3);
      const fs::path victim = dir / "victim.txt";
      write_text(victim, "the lock must not be this file\n");
      const std::string victim_hash = sha256_file(victim);
      fs::create_directories(dir / "out");
      if (hard)
        fs::create_hard_link(victim, dir / "out/.seqmassage.lock");
      else
        fs::create_symlink(victim, dir / "out/.seqmassage.lock");
      const test::CliRun r = test::run_cli(dir.path(), "-q job.json");
      CHECK(r.code == 4);
      CHECK_THAT(r.err, Contains("I/O error: ") && Contains("out/.seqmassage.lock'"));
      CHECK_THAT(r.err, Contains(hard ? "has 2 links" : "symbolic link"));
      CHECK(sha256_file(victim) == victim_hash);
      // Nothing but the planted lock in the folder.
      std::vector<std::string> names;
      for (const auto& e : fs::directory_iterator(dir / "out"))
        names.push_back(e.path().filename().string());
      CHECK(names == std::vector<std::string>{".seqmassage.lock"});
    }
  }
}

namespace {

// Two shards of a 4-frame job run in dir/out; the frame names in order.
std::vector<std::string> run_shards(const fs::path& dir) {
  make_job(dir, 4);
  for (const char* shard : {"0/2", "1/2"})
    REQUIRE(test::run_cli(dir, std::string("-q --shard ") + shard + " job.json").code == 0);
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir / "out/frames"))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// What merge must leave as it was when it refuses: every file with its bytes, and no whole-run
// outputs.
void check_refused_merge(const fs::path& dir, const std::map<std::string, std::string>& before,
                         const test::CliRun& r) {
  INFO(r.err);
  CHECK(r.code == 3);
  CHECK(test::folder_bytes(dir / "out") == before);
  CHECK(!fs::exists(dir / "out/summary.csv"));
  CHECK(!fs::exists(dir / "out/report.json"));
  CHECK(leftovers(dir / "out").empty());
}

}  // namespace

TEST_CASE("merge refuses an output whose content is not its record's, naming shard, frame, file",
          "[cli][trust][merge]") {
  test::TempDir dir("shared_merge_sha");
  const std::vector<std::string> names = run_shards(dir.path());
  REQUIRE(names.size() == 4);
  // Frame 3 is in shard 1/2; one byte of it changed, the size kept.
  const fs::path frame = dir / "out/frames" / names[3];
  std::string bytes = read_file(frame);
  const size_t at = bytes.find('.', bytes.find("\nv "));
  REQUIRE(at != std::string::npos);
  bytes[at + 1] = bytes[at + 1] == '1' ? '2' : '1';
  write_text(frame, bytes);
  const auto before = test::folder_bytes(dir / "out");
  const test::CliRun r = test::run_cli(dir.path(), "merge out");
  check_refused_merge(dir.path(), before, r);
  CHECK_THAT(r.err, Contains("report.shard-1-of-2.json: frame 3 (" + names[3] +
                             "): refusing to publish frames/" + names[3] +
                             " changed since it was written (SHA-256 differs)"));
}

TEST_CASE("merge reads no output through a symbolic link", "[cli][trust][merge]") {
  test::TempDir dir("shared_merge_link");
  const std::vector<std::string> names = run_shards(dir.path());
  // The same bytes outside, and the frame a link to them: size and SHA-256 would both match.
  const fs::path frame = dir / "out/frames" / names[0];
  fs::copy_file(frame, dir / "outside.obj");
  fs::remove(frame);
  fs::create_symlink(dir / "outside.obj", frame);
  const std::string outside_hash = sha256_file(dir / "outside.obj");
  const auto before = test::folder_bytes(dir / "out");
  const test::CliRun r = test::run_cli(dir.path(), "merge out");
  check_refused_merge(dir.path(), before, r);
  CHECK_THAT(r.err, Contains("report.shard-0-of-2.json: frame 0 (" + names[0] + ")") &&
                        Contains("frames/" + names[0] + " is a symbolic link"));
  CHECK(sha256_file(dir / "outside.obj") == outside_hash);
}

TEST_CASE("merge recomputes each shard report's config hash from its config",
          "[cli][trust][merge]") {
  test::TempDir dir("shared_merge_hash");
  run_shards(dir.path());
  // Shard 0's report: the config edited, its hash kept; shard 1 edited the same way, so the
  // shards still agree with each other.
  for (const char* file : {"report.shard-0-of-2.json", "report.shard-1-of-2.json"}) {
    json report = json::parse(read_file(dir / "out" / file));
    report["config"]["massage"]["iterations"] = 7;
    write_text(dir / "out" / file, report.dump(2) + "\n");
  }
  const auto before = test::folder_bytes(dir / "out");
  const test::CliRun r = test::run_cli(dir.path(), "merge out");
  check_refused_merge(dir.path(), before, r);
  CHECK_THAT(r.err, Contains("report.shard-0-of-2.json: its hashes.config is not the hash of its "
                             "config") &&
                        Contains("report.shard-1-of-2.json: its hashes.config"));
}

TEST_CASE("an untouched sharded job still merges", "[cli][trust][merge]") {
  test::TempDir dir("shared_merge_ok");
  run_shards(dir.path());
  const test::CliRun r = test::run_cli(dir.path(), "merge -q out");
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK(fs::is_regular_file(dir / "out/summary.csv"));
  CHECK(leftovers(dir / "out").empty());
}

TEST_CASE("--resume does not trust a record naming a file outside the output folder",
          "[cli][trust][resume]") {
  test::TempDir dir("shared_resume");
  make_job(dir.path(), 3);
  REQUIRE(test::run_cli(dir.path(), "-q job.json").code == 0);
  const fs::path victim = dir / "victim.txt";
  write_text(victim, "outside\n");
  const std::string victim_hash = sha256_file(victim);
  // Frame 1's record: its output path now names ../victim.txt, with that file's size and hash.
  std::vector<fs::path> records;
  for (const auto& e : fs::directory_iterator(dir / "out/records")) records.push_back(e.path());
  std::sort(records.begin(), records.end());
  json record = json::parse(read_file(records[1]));
  record["outputs"][0] = {{"path", "../victim.txt"},
                          {"size", fs::file_size(victim)},
                          {"sha256", victim_hash}};
  write_text(records[1], record.dump(1) + "\n");
  const test::CliRun r = test::run_cli(dir.path(), "--resume job.json");
  INFO(r.err);
  CHECK(r.code == 0);
  CHECK_THAT(r.err, Contains("2 frames kept from earlier runs, 1 processed (1 an output is "
                             "missing or changed)"));
  CHECK(sha256_file(victim) == victim_hash);
  const json rewritten = json::parse(read_file(records[1]));
  for (const json& o : rewritten["outputs"])
    CHECK(o["path"].get<std::string>().find("..") == std::string::npos);
  CHECK(leftovers(dir / "out").empty());
}

TEST_CASE("an input inside the output folder is never overwritten, by identity",
          "[cli][trust][inputs]") {
  SECTION("weights saved as the summary") {
    test::TempDir dir("shared_in_weights");
    make_job(dir.path(), 3, R"(, "template": {"frame": 0})");
    const int vertices = make_synthetic_sequence(test::small_tube(3)).rest.num_vertices();
    fs::create_directories(dir / "out");
    std::string weights;
    for (int i = 0; i < vertices; ++i) weights += "1\n";
    write_text(dir / "out/summary.csv", weights);
    json config = json::parse(read_file(dir / "job.json"));
    config["massage"]["vertex_weights"] = "out/summary.csv";
    write_text(dir / "job.json", config.dump());
    const std::string hash = sha256_file(dir / "out/summary.csv");
    for (const char* args : {"job.json", "--dry-run job.json"}) {
      const test::CliRun r = test::run_cli(dir.path(), args);
      CHECK(r.code == 2);
      CHECK_THAT(r.err, Contains("output.dir: writing ") && Contains("out/summary.csv") &&
                            Contains("would overwrite an input file, massage.vertex_weights '"));
      CHECK(sha256_file(dir / "out/summary.csv") == hash);
    }
    CHECK(leftovers(dir / "out").empty());
  }
  SECTION("the config saved as the report, and hard-linked as the summary") {
    test::TempDir dir("shared_in_config");
    make_job(dir.path(), 3);
    json config = json::parse(read_file(dir / "job.json"));
    config["input"]["frames"] = "../in";
    config["output"]["dir"] = ".";
    fs::create_directories(dir / "out");
    write_text(dir / "out/report.json", config.dump());
    const std::string hash = sha256_file(dir / "out/report.json");
    for (const char* args : {"out/report.json", "--dry-run out/report.json"}) {
      const test::CliRun r = test::run_cli(dir.path(), args);
      CHECK(r.code == 2);
      CHECK_THAT(r.err, Contains("report.json would overwrite an input file, the config '"));
      CHECK(sha256_file(dir / "out/report.json") == hash);
    }
    // Another name for the same file: refused by identity.
    fs::rename(dir / "out/report.json", dir / "job2.json");
    config["output"]["dir"] = "out";
    config["input"]["frames"] = "in";
    write_text(dir / "job2.json", config.dump());
    fs::create_hard_link(dir / "job2.json", dir / "out/summary.csv");
    const std::string hash2 = sha256_file(dir / "job2.json");
    const test::CliRun r = test::run_cli(dir.path(), "job2.json");
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("summary.csv would overwrite an input file, the config '") &&
                          Contains("job2.json"));
    CHECK(sha256_file(dir / "job2.json") == hash2);
    CHECK(leftovers(dir / "out").empty());
  }
}

TEST_CASE("a config path that is missing or a folder: one message and exit code everywhere",
          "[cli][config]") {
  test::TempDir dir("shared_config_path");
  fs::create_directories(dir / "folder.json");
  for (const auto& [file, why] : {std::pair<std::string, std::string>{"missing.json", "does not exist"},
                                  {"folder.json", "is not a file"}}) {
    const test::CliRun run = test::run_cli(dir.path(), file);
    const test::CliRun complete = test::run_cli(dir.path(), "config --complete " + file);
    CHECK(run.code == 2);
    CHECK(complete.code == 2);
    CHECK_THAT(run.err, Contains("config file '" + file + "' " + why));
    CHECK(complete.err == run.err);
  }
}
