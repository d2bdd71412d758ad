// Atomic writes leave no temporary behind; a later run removes the temporaries of killed writers
// of this host, and only those (a live writer's, e.g. another shard's, and other hosts' stay).
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <functional>

#include "io/atomic_file.hpp"
#include "core/errors.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
namespace fs = std::filesystem;

namespace {

int count_files(const fs::path& dir) {
  int n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) n += entry.is_regular_file();
  return n;
}

void touch(const fs::path& file) {
  std::ofstream(file) << "partial";
}

}  // namespace

TEST_CASE("write_file_atomic leaves the file and no temporary") {
  test::TempDir dir;
  write_file_atomic(dir / "sub/a.txt", "hello");
  CHECK(read_file(dir / "sub/a.txt") == "hello");
  CHECK(count_files(dir / "sub") == 1);
  CHECK(temporary_owner().find('-') != std::string::npos);
  CHECK(temporary_owner().rfind(std::to_string(::getpid())) ==
        temporary_owner().size() - std::to_string(::getpid()).size());
}

TEST_CASE("remove_stale_temporaries removes a dead writer's temporaries only") {
  test::TempDir dir;
  // A process that has ended: its pid is not running any more (it was reaped).
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  const std::string own = temporary_owner();
  const std::string host = own.substr(0, own.rfind('-'));
  const std::string dead = host + "-" + std::to_string(child);
  const std::string suffix(kTempSuffix);
  touch(dir / ("frame.obj." + dead + ".3" + suffix));                   // killed writer, this host
  touch(dir / ("frame.obj." + std::to_string(child) + ".0" + suffix));  // older name, no host
  touch(dir / ("frame.obj." + own + ".1" + suffix));                    // this process (live)
  touch(dir / ("frame.obj." + host + "-1.2" + suffix));                 // pid 1 runs: live
  touch(dir / ("frame.obj.otherhost-" + std::to_string(child) + ".4" + suffix));  // elsewhere
  touch(dir / "frame.obj");
  CHECK(remove_stale_temporaries(dir.path()) == 2);
  CHECK_FALSE(fs::exists(dir / ("frame.obj." + dead + ".3" + suffix)));
  CHECK(fs::exists(dir / ("frame.obj." + own + ".1" + suffix)));
  CHECK(fs::exists(dir / ("frame.obj." + host + "-1.2" + suffix)));
  CHECK(fs::exists(dir / ("frame.obj.otherhost-" + std::to_string(child) + ".4" + suffix)));
  CHECK(fs::exists(dir / "frame.obj"));
  CHECK(remove_stale_temporaries(dir / "missing") == 0);
}

TEST_CASE("temporaries have unpredictable names, created exclusively beside the destination",
          "[io][trust]") {
  test::TempDir dir;
  std::vector<std::string> names;
  {
    AtomicFileWriter a(dir / "a.txt"), b(dir / "a.txt");
    for (const auto& entry : fs::directory_iterator(dir.path()))
      names.push_back(entry.path().filename().string());
  }
  REQUIRE(names.size() == 2);
  CHECK(names[0] != names[1]);
  const std::string stem = "a.txt." + temporary_owner() + ".";
  for (const std::string& name : names) {
    INFO(name);
    REQUIRE(name.size() == stem.size() + 16 + kTempSuffix.size());
    CHECK(name.compare(0, stem.size(), stem) == 0);
    CHECK(name.substr(stem.size(), 16).find_first_not_of("0123456789abcdef") == std::string::npos);
  }
  CHECK(count_files(dir.path()) == 0);  // both abandoned: removed
  // A dead writer's temporary of this form is cleaned like the older ones.
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  const std::string own = temporary_owner();
  const std::string dead = own.substr(0, own.rfind('-')) + "-" + std::to_string(child);
  touch(dir / ("a.txt." + dead + ".0123456789abcdef" + std::string(kTempSuffix)));
  CHECK(remove_stale_temporaries(dir.path()) == 1);
}

TEST_CASE("below an output folder no write or removal follows a link", "[io][trust]") {
  test::TempDir dir;
  fs::create_directories(dir / "elsewhere");
  touch(dir / "elsewhere/victim.txt");
  const OutputFolder out(dir / "out");
  fs::create_symlink(dir / "elsewhere", dir / "out/frames");
  const auto refused = [&](const std::function<void()>& f) {
    try {
      f();
    } catch (const IoError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string link_message = "refusing to write into '" +
                                   fs::absolute(dir / "out/frames").lexically_normal().string() +
                                   "': it is a symbolic link";
  CHECK(refused([&] { write_file_atomic(dir / "out/frames/a.obj", "x"); })
            .rfind(link_message, 0) == 0);
  CHECK(refused([&] { remove_output_file(dir / "out/frames/victim.txt"); })
            .rfind(link_message, 0) == 0);
  CHECK(remove_stale_temporaries(dir / "out/frames") == 0);
  CHECK(fs::exists(dir / "elsewhere/victim.txt"));
  CHECK(!fs::exists(dir / "elsewhere/a.obj"));
  // Real sub-folders are created on the way; a link at the file's own name is replaced.
  write_file_atomic(dir / "out/records/deep/r.json", "{}");
  CHECK(read_file(dir / "out/records/deep/r.json") == "{}");
  fs::create_symlink(dir / "elsewhere/victim.txt", dir / "out/summary.csv");
  write_file_atomic(dir / "out/summary.csv", "frame\n");
  CHECK(!fs::is_symlink(dir / "out/summary.csv"));
  CHECK(read_file(dir / "elsewhere/victim.txt") == "partial");
  fs::create_symlink(dir / "elsewhere/victim.txt", dir / "out/report.json");
  remove_output_file(dir / "out/report.json");
  CHECK(!fs::exists(fs::symlink_status(dir / "out/report.json")));
  CHECK(fs::exists(dir / "elsewhere/victim.txt"));
}
