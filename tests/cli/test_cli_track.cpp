// The seqmassage command line for "job": "track", run as a subprocess on an untracked sequence
// generated in code: outputs and results line, a lost frame's exit status and messages, bad
// input and arguments with their exit codes.
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <fstream>

#include "io/atomic_file.hpp"
#include "io/mesh_file.hpp"
#include "support/cli_process.hpp"
#include "support/temp_dir.hpp"
#include "support/untracked_sequence.hpp"

using namespace sm;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

// Frames 0..4 of a slowly bending limb, each its own triangulation; `glitch` throws frame 2's
// vertices about.
void write_frames(const fs::path& dir, bool glitch) {
  fs::create_directories(dir);
  const test::Surface s = test::bending_limb(0.5, 0.02);
  for (int k = 0; k < 5; ++k) {
    TriMesh m = test::sample_surface(s, k, 0.3, 100u + unsigned(k)).mesh;
    if (glitch && k == 2)
      for (int i = 0; i < m.num_vertices(); ++i) m.V(i, (i % 3)) += (i % 2 ? 6.0 : -6.0);
    write_mesh(dir / ("f_" + std::to_string(k) + (k % 2 ? ".ply" : ".obj")), m);
  }
}

}  // namespace

TEST_CASE("seqmassage runs a track config: frames, summary, exit 0; a lost frame exits 5") {
  test::TempDir dir("cli_track");
  write_frames(dir / "raw", false);
  write_file_atomic(dir / "track.json", R"({ "job": "track", "input": { "frames": "raw" },
    "output": { "dir": "out", "html": false } })");
  const test::CliRun r = test::run_cli(dir.path(), "track.json");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Contains("tracked 5 frames (0 lost, 0 recovered)"));
  CHECK_THAT(r.out, Contains("results: out/ (frames/, summary.csv, report.json)"));
  for (int k = 0; k < 5; ++k) CHECK(fs::exists(dir / ("out/frames/f_" + std::to_string(k) + ".obj")));
  CHECK_THAT(read_file(dir / "out/summary.csv"), Contains("frame,file,status,recovery,"));

  const test::CliRun dry = test::run_cli(dir.path(), "--dry-run track.json");
  CHECK(dry.code == 0);
  CHECK_THAT(dry.out, Contains("job: track\n"));
  CHECK_THAT(dry.out, Contains("dry run: nothing written"));

  write_frames(dir / "glitched", true);
  write_file_atomic(dir / "glitched.json", R"({ "job": "track", "input": { "frames": "glitched" },
    "output": { "dir": "out_glitched", "html": true } })");
  const test::CliRun lost = test::run_cli(dir.path(), "glitched.json");
  CHECK(lost.code == 5);
  CHECK_THAT(lost.err, Contains("frame 2 (f_2.obj) lost: "));
  CHECK_THAT(lost.err, Contains("1 of 5 frames lost (written as their best attempt"));
  CHECK(fs::exists(dir / "out_glitched/frames/f_2.obj"));
  CHECK_THAT(lost.out, Contains("results: out_glitched/ (frames/, report_data/, report.html, "
                                "summary.csv, report.json)"));
  CHECK(fs::exists(dir / "out_glitched/report.html"));
}

TEST_CASE("seqmassage tracks shards of a track config and merges them, naming the seams") {
  test::TempDir dir("cli_track_shards");
  write_frames(dir / "raw", false);
  write_file_atomic(dir / "track.json", R"({ "job": "track", "input": { "frames": "raw" },
    "output": { "dir": "out", "format": "pc2", "html": false } })");
  for (const char* shard : {"0/2", "1/2"}) {
    const test::CliRun r =
        test::run_cli(dir.path(), std::string("--shard ") + shard + " --resume track.json");
    INFO(r.err);
    REQUIRE(r.code == 0);
    CHECK_THAT(r.err, Contains("--resume: a track job keeps no per-frame records"));
    CHECK_THAT(r.out, Contains("when every shard is done: seqmassage merge out"));
  }
  CHECK(fs::exists(dir / "out/summary.shard-1-of-2.csv"));
  CHECK_FALSE(fs::exists(dir / "out/sequence.pc2"));
  const test::CliRun merged = test::run_cli(dir.path(), "merge out");
  INFO(merged.err);
  REQUIRE(merged.code == 0);
  CHECK_THAT(merged.err, Contains("merged 2 shards, 5 frames (0 lost, 0 recovered)"));
  CHECK_THAT(merged.err, Contains("seams (tracked from the template, not the frame before): "
                                  "frames 2\n"));
  CHECK(fs::exists(dir / "out/sequence.pc2"));
  CHECK(fs::exists(dir / "out/summary.csv"));
}

TEST_CASE("seqmassage refuses bad track input with the key, folder or frame") {
  test::TempDir dir("cli_track_bad");
  write_frames(dir / "raw", false);
  write_file_atomic(dir / "missing.json", R"({ "job": "track", "input": { "frames": "nowhere" },
    "output": { "dir": "out" } })");
  const test::CliRun missing = test::run_cli(dir.path(), "missing.json");
  CHECK(missing.code == 4);
  CHECK_THAT(missing.err, Contains("input.frames: the folder '" + (dir / "nowhere").string() +
                                   "' does not exist"));
  write_file_atomic(dir / "range.json", R"({ "job": "track", "input": { "frames": "raw" },
    "template": { "frame": 5 }, "output": { "dir": "out" } })");
  const test::CliRun range = test::run_cli(dir.path(), "range.json");
  CHECK(range.code == 2);
  CHECK_THAT(range.err, Contains("template.frame: 5 is out of range (the folder has 5 frames"));
  const test::CliRun shard = test::run_cli(dir.path(), "--shard 2/2 range.json");
  CHECK(shard.code == 2);
  CHECK_THAT(shard.err, Contains("--shard: "));
  std::ofstream(dir / "raw/f_3.ply") << "ply\nformat ascii 1.0\nelement vertex 3\n";
  write_file_atomic(dir / "bad.json", R"({ "job": "track", "input": { "frames": "raw" },
    "output": { "dir": "out" } })");
  const test::CliRun bad = test::run_cli(dir.path(), "bad.json");
  CHECK(bad.code == 3);
  CHECK_THAT(bad.err, Contains("input error: frame 3 ('" + (dir / "raw/f_3.ply").string() + "')"));
}
