// The input side of the trust boundary end to end: seqmassage run as a subprocess on hostile
// inputs. Every case checks the exit code, the words of the message, that the inputs are unchanged
// and that no output (nor temporary file) is left.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <map>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "pipeline/sequence/synthetic.hpp"
#include "support/cli_process.hpp"
#include "support/gltf_models.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"
#include "support/text_files.hpp"

using namespace sm;
using test::write_text;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// Every regular file under `dir` with its bytes (FIFOs and devices are left alone).
std::map<fs::path, std::string> snapshot(const fs::path& dir) {
  std::map<fs::path, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().filename().string().rfind("cli_std", 0) != 0)
      files[fs::relative(entry.path(), dir)] = read_file(entry.path());
  return files;
}

// The skinned strip as takes/strip.gltf whose buffer file is named `bin` with uri `uri`.
void write_strip(const test::TempDir& dir, const std::string& uri, const std::string& bin) {
  fs::create_directories(dir / "takes");
  test::skinned_strip().save(dir / "takes/strip.gltf", false);
  json doc = json::parse(read_file(dir / "takes/strip.gltf"));
  doc["buffers"][0]["uri"] = uri;
  write_text(dir / "takes/strip.gltf", doc.dump());
  fs::rename(dir / "takes/strip.bin", dir / bin);
  write_text(dir / "job.json", R"({"job": "sequence",
    "input": {"gltf": "takes/strip.gltf", "fps": 4},
    "output": {"dir": "out", "timings": false}, "massage": {"iterations": 3},
    "checks": {"max_folded_fraction": null}})");
}

}  // namespace

TEST_CASE("a glTF buffer outside the model's folder: exit 3 in dry-run and run, nothing written",
          "[cli][trust]") {
  test::TempDir dir("cli_trust_escape");
  write_strip(dir, "../secret.bin", "secret.bin");
  const auto before = snapshot(dir.path());
  for (const std::string args : {"--dry-run job.json", "job.json"}) {
    const test::CliRun r = test::run_cli(dir.path(), args);
    CHECK(r.code == 3);
    CHECK_THAT(r.err, Catch::Contains("seqmassage: input error: '") &&
                          Catch::Contains("takes/strip.gltf': buffers[0].uri '../secret.bin': "
                                          "resolves outside the model's folder"));
    CHECK_FALSE(fs::exists(dir / "out"));
  }
  CHECK(snapshot(dir.path()) == before);
}

TEST_CASE("a percent-encoded buffer name runs exactly as it dry-runs, hashing the file it reads",
          "[cli][trust]") {
  test::TempDir dir("cli_trust_percent");
  write_strip(dir, "my%20strip.bin", "takes/my strip.bin");
  test::CliRun r = test::run_cli(dir.path(), "--dry-run job.json");
  CHECK(r.code == 0);
  CHECK_FALSE(fs::exists(dir / "out"));
  r = test::run_cli(dir.path(), "job.json");
  REQUIRE(r.code == 0);
  const auto input_hash = [&] {
    return json::parse(read_file(dir / "out/records/frame_0000.json")).at("input_hash");
  };
  const json first = input_hash();
  // Other bytes in the same buffer file change the input hash: it is the file that was read.
  std::string bin = read_file(dir / "takes/my strip.bin");
  bin.back() = char(bin.back() ^ 1);
  write_text(dir / "takes/my strip.bin", bin);
  r = test::run_cli(dir.path(), "--resume job.json");
  CHECK(r.code == 0);
  CHECK(input_hash() != first);
  CHECK_THAT(r.out + r.err, Catch::Contains("the input changed"));
}

TEST_CASE("a FIFO or a device as an input mesh: exit 3 at once, naming it, nothing written",
          "[cli][trust]") {
  test::TempDir dir("cli_trust_fifo");
  const SyntheticSequence tube = make_synthetic_sequence(test::small_tube(3));
  write_synthetic_sequence(tube, dir / "in", dir / "gt");
  REQUIRE(::mkfifo((dir / "rest.obj").c_str(), 0600) == 0);  // no writer: open() would block
  fs::create_symlink("/dev/zero", dir / "zero.obj");
  const auto before = snapshot(dir.path());
  const std::string not_regular = "': not a regular file (a FIFO); only regular files are read";
  write_text(dir / "job.json", R"({"job": "sequence", "input": {"frames": "in"},
    "template": {"mesh": "rest.obj"}, "output": {"dir": "out"}})");
  for (const std::string args : {"--dry-run job.json", "job.json"}) {
    const test::CliRun r = test::run_cli(dir.path(), args);
    CHECK(r.code == 3);
    CHECK_THAT(r.err, Catch::Contains("rest.obj" + not_regular));
    CHECK_FALSE(fs::exists(dir / "out"));
  }
  write_text(dir / "job.json", R"({"job": "sequence", "input": {"gltf": "rest.gltf"},
    "output": {"dir": "out"}})");
  REQUIRE(::mkfifo((dir / "rest.gltf").c_str(), 0600) == 0);
  test::CliRun r = test::run_cli(dir.path(), "job.json");
  CHECK(r.code == 3);
  CHECK_THAT(r.err, Catch::Contains("rest.gltf" + not_regular));
  write_text(dir / "job.json", R"({"job": "smooth", "input": {"mesh": "rest.obj"},
    "output": {"dir": "out"}})");
  r = test::run_cli(dir.path(), "job.json");
  CHECK(r.code == 3);
  CHECK_THAT(r.err, Catch::Contains("rest.obj" + not_regular));
  r = test::run_cli(dir.path(), "measure zero.obj rest.obj");
  CHECK(r.code == 3);
  CHECK_THAT(r.err, Catch::Contains("zero.obj': not a regular file (a character device)"));
  r = test::run_cli(dir.path(), "measure in/" + synthetic_frame_name(tube, 0) + " rest.obj");
  CHECK(r.code == 3);
  CHECK_THAT(r.err, Catch::Contains("rest.obj" + not_regular));
  CHECK_FALSE(fs::exists(dir / "out"));
  fs::remove(dir / "job.json");
  fs::remove(dir / "rest.gltf");
  CHECK(snapshot(dir.path()) == before);
}
