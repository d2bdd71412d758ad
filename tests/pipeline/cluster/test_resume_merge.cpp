// Resume (issue 6.4) and shards with merge (issue 8) in one process: frame records decide which
// frames a resumed run skips, and merge rebuilds one run's summary and report from every shard's
// records, byte for byte.
#include <catch2/catch.hpp>

#include "io/atomic_file.hpp"
#include "core/errors.hpp"
#include "pipeline/cluster/frame_record.hpp"
#include "pipeline/cluster/merge.hpp"
#include "pipeline/run/sequence_job.hpp"
#include "pipeline/sequence/shard.hpp"
#include "support/gltf_models.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

SequenceResult run(const SequenceJobOptions& c, const RunHooks& hooks = {}) {
  return run_sequence_job(plan_sequence_job(c), hooks);
}

std::string merge_error(const fs::path& dir) {
  try {
    merge_shards(dir);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Runs `c` as `n` shards one after the other, then merges them.
MergeResult run_shards(SequenceJobOptions c, int n) {
  for (int i = 0; i < n; ++i) {
    c.shard = {i, n};
    const SequenceResult r = run(c);
    REQUIRE_FALSE(r.interrupted);
  }
  return merge_shards(c.output.dir);
}

}  // namespace

TEST_CASE("shards are contiguous blocks of the selection, named apart") {
  const std::vector<int> selected = {1, 3, 5, 7, 9, 11, 13};
  CHECK(shard_frames(selected, {0, 3}) == std::vector<int>{1, 3});
  CHECK(shard_frames(selected, {1, 3}) == std::vector<int>{5, 7});
  CHECK(shard_frames(selected, {2, 3}) == std::vector<int>{9, 11, 13});
  CHECK(shard_frames(selected, {0, 1}) == selected);
  CHECK(shard_frames({4}, {0, 2}).empty());
  CHECK(shard_frames({4}, {1, 2}) == std::vector<int>{4});
  CHECK(summary_file_name({1, 3}) == "summary.shard-1-of-3.csv");
  CHECK(report_file_name({1, 3}) == "report.shard-1-of-3.json");
  CHECK(summary_file_name({}) == "summary.csv");
  CHECK(report_file_name({}) == "report.json");
}

TEST_CASE("a resumed run skips current frames and redoes the others, with the same bytes") {
  test::TempDir dir("resume_lib");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube());
  run(c);
  const auto first = test::folder_bytes(dir / "out");
  CHECK(first.count("records/frame_0003.json"));

  c.resume = true;
  SequenceResult r = run(c);
  CHECK(r.resumed == 6);
  CHECK(r.redone.empty());
  for (const FrameSummary& f : r.frames) CHECK(f.resumed);
  CHECK(test::folder_bytes(dir / "out") == first);

  // Another input for frame 4, an output changed by hand, an output and a record removed.
  test::edit_obj_vertices(c.input.frames / "frame_0004.obj",
                          [](int v, double& x, double&, double&) { x += v == 5 ? 1e-3 : 0.0; });
  write_file_atomic(dir / "out/frames/frame_0001.obj",
                    read_file(dir / "out/frames/frame_0001.obj") + "# edited\n");
  fs::remove(dir / "out/distortion/frame_0002.csv");
  fs::remove(dir / "out/records/frame_0005.json");
  r = run(c);
  CHECK(r.resumed == 2);
  CHECK(r.redone == std::map<std::string, int>{{"the input changed", 1},
                                               {"an output is missing or changed", 2},
                                               {"no record", 1}});
  CHECK_FALSE(r.frames[4].resumed);
  auto now = test::folder_bytes(dir / "out");
  for (const char* same : {"frames/frame_0001.obj", "distortion/frame_0002.csv",
                           "records/frame_0005.json", "frames/frame_0003.obj"})
    CHECK(now[same] == first.at(same));
  CHECK(now["frames/frame_0004.obj"] != first.at("frames/frame_0004.obj"));

  // Another config: every frame again.
  c.massage.iterations = 7;
  r = run(c);
  CHECK(r.resumed == 0);
  CHECK(r.redone == std::map<std::string, int>{{"the config changed", 6}});
}

TEST_CASE("an interrupted run, resumed, ends with the bytes of an uninterrupted one") {
  test::TempDir dir("resume_interrupted");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(8));
  run(c);
  fs::rename(dir / "out", dir / "whole");  // the same path for both runs: report.json names it
  std::atomic<bool> cancel{false};
  RunHooks hooks;
  hooks.cancel = &cancel;
  hooks.progress = [&](const FrameSummary&, int done, int, double) {
    if (done == 3) cancel = true;
  };
  const SequenceResult stopped = run(c, hooks);
  CHECK(stopped.interrupted);
  CHECK(stopped.frames.size() < 8);
  CHECK(nlohmann::json::parse(read_file(dir / "out/report.json"))["interrupted"] == true);
  c.resume = true;
  const SequenceResult resumed = run(c);
  CHECK_FALSE(resumed.interrupted);
  CHECK(resumed.resumed == int(stopped.frames.size()));
  test::compare_folders(dir / "whole", dir / "out");
}

TEST_CASE("three shards, merged, write exactly what one run writes") {
  test::TempDir dir("shards_lib");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(8));
  c.input.range = {1, std::nullopt, 1};  // 7 frames: blocks of 2, 2, 3
  c.output.html = true;  // the merged report.html is the one run's, byte for byte
  run(c);
  fs::rename(dir / "out", dir / "single");
  const MergeResult m = run_shards(c, 3);
  CHECK(m.shards == 3);
  CHECK(m.frames.size() == 7);
  CHECK(m.written == std::vector<std::string>{"summary.csv", "report.json", "report.html"});
  test::compare_folders(dir / "single", dir / "out", ".shard-");
  // A shard's own report: its frames, complete, the plan's warnings.
  const nlohmann::json shard =
      nlohmann::json::parse(read_file(dir / "out/report.shard-2-of-3.json"))["shard"];
  CHECK(shard["complete"] == true);
  CHECK(shard["frames"].size() == 3);
  CHECK(shard["frames"][0]["file"] == "frame_0005.obj");
  CHECK(fs::exists(dir / "out/summary.shard-0-of-3.csv"));
}

TEST_CASE("merge names missing shards, missing frames and shards of another job") {
  test::TempDir dir("shards_missing");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(9));
  run_shards(c, 3);

  fs::remove(dir / "out/records/frame_0004.json");
  fs::remove(dir / "out/frames/frame_0005.obj");
  std::string e = merge_error(dir / "out");
  CHECK_THAT(e, Contains("cannot merge 3 shards:"));
  CHECK_THAT(e, Contains("missing or incomplete frames: frames 4 (frame_0004.obj) to 5 "
                         "(frame_0005.obj) (first: frame 4 (frame_0004.obj): no record); run "
                         "its shard again: seqmassage --shard 1/3 --resume CONFIG"));

  // A resumed shard repairs it.
  c.shard = {1, 3};
  c.resume = true;
  const SequenceResult r = run(c);
  CHECK(r.resumed == 1);
  CHECK(merge_error(dir / "out").empty());

  // A shard that never ran: named, with its frames.
  fs::remove(dir / "out/report.shard-2-of-3.json");
  e = merge_error(dir / "out");
  CHECK_THAT(e, Contains("shard 2/3: no report.shard-2-of-3.json; missing frames 6 "
                         "(frame_0006.obj) to 8 (frame_0008.obj); run it: seqmassage --shard 2/3 "
                         "--resume CONFIG"));

  // A shard of another config.
  c.shard = {2, 3};
  c.resume = false;
  c.massage.iterations = 5;
  run(c);
  e = merge_error(dir / "out");
  CHECK_THAT(e, Contains("report.shard-2-of-3.json ran another config: massage.iterations (8 vs "
                         "5) than report.shard-0-of-3.json"));

  // Shards of two splits.
  c.massage.iterations = 8;
  c.shard = {0, 2};
  run(c);
  CHECK_THAT(merge_error(dir / "out"), Contains("shard reports of different splits"));
  CHECK_THROWS_AS(merge_shards(dir / "nowhere"), IoError);
}

TEST_CASE("a sharded glTF job: merge assembles sequence.glb from the shards' positions") {
  test::TempDir dir("shards_gltf");
  test::skinned_strip().save(dir / "strip.glb", true);
  SequenceJobOptions c;
  c.input.gltf = GltfInputOptions{dir / "strip.glb", "", "", 12.0};
  c.output.dir = dir / "out";
  c.output.format = OutputFormat::Gltf;
  c.output.timings = false;
  c.output.html = false;
  c.massage.iterations = 4;
  c.checks.max_folded_fraction.reset();  // the strip folds at its sharpest bend (see gltf tests)
  run(c);
  REQUIRE(fs::exists(dir / "out/sequence.glb"));
  fs::rename(dir / "out", dir / "single");
  c.shard = {0, 2};
  run(c);
  CHECK_FALSE(fs::exists(dir / "out/sequence.glb"));  // a shard writes positions only
  CHECK(fs::exists(dir / "out/positions/frame_0000.bin"));
  c.shard = {1, 2};
  run(c);
  const MergeResult m = merge_shards(dir / "out");
  CHECK(m.written == std::vector<std::string>{"summary.csv", "report.json", "sequence.glb"});
  test::compare_folders(dir / "single", dir / "out", ".shard-");
}

TEST_CASE("visual outputs (colored, checker, iterations.csv) resume and merge like the frames") {
  test::TempDir dir("shards_extras");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(7));
  c.output.colored.enabled = true;
  c.output.checker.enabled = true;
  c.output.iterations.enabled = true;
  c.output.iterations.shear_frames = FrameSelection::none();
  c.output.iterations.shear_frames.list = {2, 5};
  run(c);
  REQUIRE(fs::exists(dir / "out/iterations.csv"));
  REQUIRE(fs::exists(dir / "out/colored/after/frame_0004.ply"));
  const auto record = read_frame_record(dir / "out/records/frame_0005.json");
  REQUIRE(record);
  CHECK(record->outputs.size() == 2 + 4);  // frame, table, colored and checker before/after
  CHECK_FALSE(record->record_rows.at("iterations_csv").empty());
  fs::rename(dir / "out", dir / "single");

  // Interrupted after 3 frames, then resumed: the same bytes, iterations.csv included.
  std::atomic<bool> cancel{false};
  RunHooks hooks;
  hooks.cancel = &cancel;
  hooks.progress = [&](const FrameSummary&, int done, int, double) {
    if (done == 3) cancel = true;
  };
  CHECK(run(c, hooks).interrupted);
  c.resume = true;
  CHECK(run(c).resumed >= 3);
  test::compare_folders(dir / "single", dir / "out");
  fs::remove_all(dir / "out");

  // As 3 shards, merged: iterations.csv is rebuilt from the records.
  c.resume = false;
  const MergeResult m = run_shards(c, 3);
  CHECK(m.written == std::vector<std::string>{"summary.csv", "report.json", "iterations.csv"});
  test::compare_folders(dir / "single", dir / "out", ".shard-");
  CHECK(fs::exists(dir / "out/iterations.shard-1-of-3.csv"));
}
