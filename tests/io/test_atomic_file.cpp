// Atomic writes leave no temporary behind; a later run removes the temporaries of killed writers
// of this host, and only those (a live writer's, e.g. another shard's, and other hosts' stay).
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <fstream>

#include "io/atomic_file.hpp"
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
