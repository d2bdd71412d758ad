// The output side of the trust boundary: frame folders whose entries would silently renumber or
// overwrite frames are refused at planning, naming the entries; one writer per output folder and
// shard (lock files); input errors of glTF output refused before anything is written.
#include <sys/stat.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <fstream>

#include "io/atomic_file.hpp"
#include "core/errors.hpp"
#include "pipeline/cluster/merge.hpp"
#include "pipeline/cluster/output_lock.hpp"
#include "pipeline/run/sequence_job.hpp"
#include "support/error_of.hpp"
#include "support/gltf_models.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

std::string host() {
  char buffer[256] = {};
  ::gethostname(buffer, sizeof buffer - 1);
  return buffer;
}

// Every path under `dir` (files, folders, links), relative; empty if `dir` does not exist.
std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    out.push_back(fs::relative(it->path(), dir).generic_string());
  std::sort(out.begin(), out.end());
  return out;
}

// The planning error of `c` (and that it wrote nothing: no output folder).
std::string planning_error(const SequenceJobOptions& c) {
  const std::string e = test::error_of<InputError>([&] { plan_sequence_job(c); });
  CHECK_FALSE(fs::exists(c.output.dir));
  return e;
}

}  // namespace

TEST_CASE("an entry named *.obj that is not a frame file is refused, naming it",
          "[pipeline][trust]") {
  test::TempDir dir("trust_entries");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(4));
  const auto before = test::folder_bytes(dir / "in");
  const std::string in = (dir / "in").string();

  SECTION("a dangling symbolic link") {
    fs::create_symlink("gone.obj", dir / "in/frame_0001b.obj");
    CHECK_THAT(planning_error(c), Contains("frame folder '" + in +
                                           "': 'frame_0001b.obj' is a dangling symbolic "
                                           "link (to 'gone.obj'), not a frame file"));
  }
  SECTION("a symbolic link loop") {
    fs::create_symlink("loop_b.obj", dir / "in/loop_a.obj");
    fs::create_symlink("loop_a.obj", dir / "in/loop_b.obj");
    CHECK_THAT(planning_error(c), Contains("'loop_a.obj' is a symbolic link loop"));
  }
  SECTION("a FIFO") {
    REQUIRE(::mkfifo((dir / "in/frame_0002b.obj").c_str(), 0644) == 0);
    CHECK_THAT(planning_error(c), Contains("'frame_0002b.obj' is a FIFO (named pipe)"));
  }
  SECTION("a folder, and a link to a device") {
    fs::create_directory(dir / "in/frame_0003b.obj");
    CHECK_THAT(planning_error(c), Contains("'frame_0003b.obj' is a folder"));
    fs::remove(dir / "in/frame_0003b.obj");
    fs::create_symlink("/dev/zero", dir / "in/zero.OBJ");
    CHECK_THAT(planning_error(c),
               Contains("'zero.OBJ' is a symbolic link to a character device, not a frame file; "
                        "every .obj entry must be a regular file (or a link to one)"));
  }
  // Hidden entries are still skipped, and a link to a frame file is a frame.
  std::error_code ec;
  for (const char* name :
       {"frame_0001b.obj", "loop_a.obj", "loop_b.obj", "frame_0002b.obj", "zero.OBJ"})
    fs::remove(dir / "in" / name, ec);
  fs::create_symlink("gone.obj", dir / "in/.hidden.obj");
  CHECK(test::folder_bytes(dir / "in") == before);
  CHECK(plan_sequence_job(c).source->size() == 4);
}

TEST_CASE("two frames whose outputs would collide are refused at planning, naming both",
          "[pipeline][trust]") {
  test::TempDir dir("trust_collide");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(4));
  SECTION("a.obj and a.OBJ: the same record and table") {
    fs::copy_file(dir / "in/frame_0002.obj", dir / "in/frame_0002.OBJ");
    const auto before = test::folder_bytes(dir / "in");
    const std::string e = planning_error(c);
    CHECK_THAT(e, Contains("frame_0002.OBJ") && Contains("frame_0002.obj"));
    CHECK_THAT(e, Contains("would both write records/frame_0002.json (their output names differ "
                           "only in letter case or extension)"));
    CHECK(test::folder_bytes(dir / "in") == before);
  }
  SECTION("A.obj and a.obj: the same files on a case-insensitive file system") {
    fs::copy_file(dir / "in/frame_0002.obj", dir / "in/FRAME_0002.obj");
    CHECK_THAT(planning_error(c), Contains("(FRAME_0002.obj) and ") &&
                                      Contains("would both write records/frame_0002.json"));
  }
  SECTION("outside the selection, no collision") {
    fs::copy_file(dir / "in/frame_0002.obj", dir / "in/frame_0002.OBJ");
    c.input.range.stop = 2;
    CHECK(plan_sequence_job(c).selected.size() == 2);
  }
}

TEST_CASE("one writer per output folder and shard", "[pipeline][trust][lock]") {
  test::TempDir dir("trust_lock");
  const fs::path out = dir / "out";
  const std::string pid = std::to_string(::getpid());
  {
    const OutputLock first = lock_output_folder(out);
    CHECK(first.warnings().empty());
    const std::string text = read_file(out / ".seqmassage.lock");
    CHECK_THAT(text, Contains("host " + host() + "\npid " + pid + "\nstarted 20"));
    const std::string e = test::error_of<IoError>([&] { lock_output_folder(out); });
    CHECK_THAT(e, Contains("output folder '" + out.string() + "' is in use: its lock file '" +
                           (out / ".seqmassage.lock").string() + "' is held by host " + host() +
                           ", pid " + pid + ", since "));
    CHECK_THAT(e, Contains("wait until that run ends, or stop it, then run again"));
    // A shard needs the folder's lock too (shared): refused while a whole run holds it.
    CHECK_THAT(test::error_of<IoError>([&] {
                 lock_output_folder(out, {1, 4});
               }),
               Contains(".seqmassage.lock' is held by host"));
  }
  CHECK(entries(out).empty());  // released: no lock file left

  {  // Shards of one job side by side; the same shard twice, a whole run, a merge: refused.
    const OutputLock s1 = lock_output_folder(out, {1, 4});
    const OutputLock s2 = lock_output_folder(out, {2, 4});
    CHECK_THAT(test::error_of<IoError>([&] {
                 lock_output_folder(out, {1, 4});
               }),
               Contains("its lock file '" + (out / ".seqmassage-shard-1-of-4.lock").string() +
                        "' is held by host " + host() + ", pid " + pid));
    const std::string whole = test::error_of<IoError>([&] { lock_output_folder(out); });
    CHECK_THAT(whole, Contains(".seqmassage.lock' is held by the shards running there: ") &&
                          Contains("shard 1/4 (host " + host() + ", pid " + pid) &&
                          Contains("shard 2/4 (host "));
    CHECK_THAT(test::error_of<IoError>([&] { merge_shards(out); }), Contains("is in use"));
  }
  CHECK(entries(out).empty());  // the last shard removed the folder's shared lock file too

  // A lock file left by a process that is gone (SIGKILL): taken over, with a warning.
  write_file_atomic(out / ".seqmassage-shard-0-of-2.lock",
                    "host " + host() + "\npid 999999999\nstarted 2026-01-01T00:00:00Z\n");
  {
    const OutputLock taken = lock_output_folder(out, {0, 2});
    REQUIRE(taken.warnings().size() == 1);
    CHECK(taken.warnings()[0] == "took over the lock file '" +
                                     (out / ".seqmassage-shard-0-of-2.lock").string() +
                                     "' left by host " + host() +
                                     ", pid 999999999, since 2026-01-01T00:00:00Z: that run ended "
                                     "without removing it (killed, or its host went down)");
    CHECK_THAT(read_file(out / ".seqmassage-shard-0-of-2.lock"), Contains("pid " + pid));
  }
  CHECK(entries(out).empty());

  // A lock file that is not a regular file is refused, not followed.
  fs::create_symlink("elsewhere", out / ".seqmassage.lock");
  CHECK_THAT(test::error_of<IoError>([&] { lock_output_folder(out); }),
             Contains("cannot create the lock file") && Contains("symbolic link"));
}

TEST_CASE("a run into a locked output folder is refused before it writes anything",
          "[pipeline][trust][lock]") {
  test::TempDir dir("trust_lock_run");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(3));
  const SequencePlan plan = plan_sequence_job(c);
  {
    const OutputLock other = lock_output_folder(c.output.dir);
    CHECK_THAT(test::error_of<IoError>([&] { run_sequence_job(plan); }),
               Contains("is in use: its lock file"));
    CHECK(entries(c.output.dir) == std::vector<std::string>{".seqmassage.lock"});
  }
  // Unlocked: the run, its lock gone at the end, the outputs of a run without locks.
  run_sequence_job(plan);
  const auto files = test::names_of(test::folder_bytes(c.output.dir));
  CHECK(std::none_of(files.begin(), files.end(),
                     [](const std::string& f) { return f.find("lock") != std::string::npos; }));
  CHECK(fs::exists(c.output.dir / "summary.csv"));
  // A shard runs beside another shard's lock.
  c.shard = {1, 2};
  const OutputLock shard0 = lock_output_folder(c.output.dir, {0, 2});
  CHECK(run_sequence_job(plan_sequence_job(c)).frames.size() == 2);
}

TEST_CASE("glTF output: an image of unknown format is refused at planning, before any output",
          "[pipeline][trust][gltf]") {
  test::TempDir dir("trust_gltf_image");
  test::skinned_strip().save(dir / "strip.gltf", false);
  // Its image an external file that is neither PNG nor JPEG (nor WebP, KTX2), without mimeType.
  nlohmann::json j = nlohmann::json::parse(read_file(dir / "strip.gltf"));
  j["images"][0] = {{"uri", "pixel.dat"}};
  write_file_atomic(dir / "strip.gltf", j.dump());
  write_file_atomic(dir / "pixel.dat", "GIF89a, not an image a GLB may carry");
  const auto before = test::folder_bytes(dir.path());
  SequenceJobOptions c;
  c.input.gltf = GltfInputOptions{dir / "strip.gltf", "", "", 12.0};
  c.output.dir = dir / "out";
  c.output.format = OutputFormat::Gltf;
  CHECK_THAT(planning_error(c),
             Contains("images[0]") && Contains("unknown image format (not PNG, JPEG, WebP or "
                                               "KTX2)"));
  c.shard = {0, 2};  // a shard writes no GLB, but merge would: refused as well
  CHECK_THAT(planning_error(c), Contains("unknown image format"));
  CHECK(test::folder_bytes(dir.path()) == before);
  // The same model as OBJ output: no GLB, no image written, accepted.
  c.output.format = OutputFormat::Obj;
  c.shard = {};
  CHECK_NOTHROW(plan_sequence_job(c));
}
