// The sequence job end to end on small generated sequences: outputs, determinism across thread
// counts, the template frame, checks of the inputs before anything is written, cancellation.
#include <catch2/catch.hpp>
#include <fstream>

#include "io/atomic_file.hpp"
#include "io/obj.hpp"
#include "core/errors.hpp"
#include "pipeline/report/report.hpp"
#include "pipeline/run/sequence_job.hpp"
#include "pipeline/sequence/synthetic.hpp"
#include "support/error_of.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
using test::error_of;
namespace fs = std::filesystem;

namespace {}  // namespace

TEST_CASE("a sequence job writes every documented output") {
  test::TempDir dir("job_outputs");
  const SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(5));
  const SequencePlan plan = plan_sequence_job(c);
  CHECK(plan.selected == std::vector<int>{0, 1, 2, 3, 4});
  CHECK(plan.template_frame == 0);
  std::vector<int> done;
  RunHooks hooks;
  hooks.progress = [&](const FrameSummary& f, int n, int total, double) {
    CHECK(total == 5);
    CHECK(f.frame == n - 1);
    done.push_back(n);
  };
  const SequenceResult r = run_sequence_job(plan, hooks);
  CHECK(done == std::vector<int>{1, 2, 3, 4, 5});
  REQUIRE(r.frames.size() == 5);
  CHECK(r.failed == 0);
  CHECK_FALSE(r.interrupted);
  CHECK(r.frames[0].status == FrameStatus::Template);
  CHECK(r.frames[0].iterations == 0);
  double before = 0, after = 0;
  for (int t = 0; t < 5; ++t) {
    const std::string name = "frame_000" + std::to_string(t);
    CHECK(fs::exists(dir / ("out/frames/" + name + ".obj")));
    CHECK(fs::exists(dir / ("out/distortion/" + name + ".csv")));
    before += r.frames[t].shear_before.mean;
    after += r.frames[t].shear_after.mean;
    if (t > 0) {
      CHECK(r.frames[t].status == FrameStatus::Optimized);
      CHECK(r.frames[t].iterations > 0);
      // On a coarse tube (12 segments) the output's chords cut inside the input's facets.
      CHECK(r.frames[t].out_to_in.max < 0.2 * mean_edge_length(plan.templ));
      CHECK(r.frames[t].in_to_out.max < 0.2 * mean_edge_length(plan.templ));
    }
  }
  CHECK(after < before);
  // The template frame is copied byte for byte; the others keep their texture coordinates.
  CHECK(read_file(dir / "out/frames/frame_0000.obj") == read_file(dir / "in/frame_0000.obj"));
  const ObjFile out = read_obj(dir / "out/frames/frame_0003.obj");
  const ObjFile in = read_obj(dir / "in/frame_0003.obj");
  CHECK(out.texcoords == in.texcoords);
  CHECK(out.mesh.F == in.mesh.F);
  CHECK(out.mesh.V != in.mesh.V);
  CHECK(read_file(dir / "out/summary.csv") == format_summary_csv(r.frames, false));
  const nlohmann::json report = nlohmann::json::parse(read_file(dir / "out/report.json"));
  CHECK(report["totals"]["frames_written"] == 5);
  CHECK(report["totals"]["template_unchanged"] == 1);
  CHECK(report["config"]["input"]["frames"] == (dir / "in").string());
  CHECK(report["interrupted"] == false);
  CHECK_FALSE(report.contains("run"));  // no timings
  CHECK(report["versions"].contains("seqmassage"));
}

TEST_CASE("the output bytes do not depend on the number of threads") {
  test::TempDir dir("job_threads");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(6));
  c.threads = 1;
  c.output.dir = dir / "one";
  run_sequence_job(plan_sequence_job(c));
  c.threads = 2;
  c.frames_in_flight = 3;
  c.output.dir = dir / "two";
  run_sequence_job(plan_sequence_job(c));
  for (const char* file : {"summary.csv", "frames/frame_0002.obj", "frames/frame_0005.obj",
                           "distortion/frame_0004.csv"})
    CHECK(read_file(dir / "one" / file) == read_file(dir / "two" / file));
}

TEST_CASE("measures sets the sampling of summary.csv's distances, the same with 1 or 2 threads") {
  test::TempDir dir("job_measures");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(4));
  auto run = [&](const char* out, int threads) {
    c.threads = threads;
    c.output.dir = dir / out;
    return run_sequence_job(plan_sequence_job(c));
  };
  const SequenceResult fine = run("fine", 2);  // the default: adaptive
  run("fine1", 1);
  c.measures.adaptive = false;
  c.measures.spacing = 0.7;
  run("coarse1", 1);
  const SequenceResult coarse = run("coarse2", 2);
  c.measures.sample_edges = c.measures.sample_faces = false;
  const SequenceResult vertices = run("vertices", 2);
  for (const char* file : {"summary.csv", "frames/frame_0002.obj", "records/frame_0003.json"}) {
    CHECK(read_file(dir / "coarse1" / file) == read_file(dir / "coarse2" / file));
    CHECK(read_file(dir / "fine1" / file) == read_file(dir / "fine" / file));
  }
  // The corrected frames do not depend on how they are measured; the distances do.
  CHECK(read_file(dir / "fine/frames/frame_0003.obj") ==
        read_file(dir / "vertices/frames/frame_0003.obj"));
  REQUIRE(fine.frames.size() == 4);
  for (size_t k = 1; k < 4; ++k) {
    const DistanceStats& f = fine.frames[k].out_to_in;
    const DistanceStats& v = vertices.frames[k].out_to_in;
    CHECK(v.samples < coarse.frames[k].out_to_in.samples);
    CHECK(v.samples == fine.frames[k].vertices);
    CHECK(f.max > 0.0);
    CHECK(f.refined > 0);
    // The vertices are among the adaptive sampling's samples and the uniform one's.
    CHECK(v.max <= f.max * (1.0 + 1e-9));
    CHECK(v.max <= coarse.frames[k].out_to_in.max * (1.0 + 1e-9));
  }
}

TEST_CASE("the template frame can be optimized too, or come from a rest mesh") {
  test::TempDir dir("job_template");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(3));
  c.templ.optimize = true;
  c.input.range.stop = 1;
  SequenceResult r = run_sequence_job(plan_sequence_job(c));
  REQUIRE(r.frames.size() == 1);
  CHECK(r.frames[0].status == FrameStatus::Optimized);

  const SyntheticSequence seq = make_synthetic_sequence(test::small_tube(3));
  write_obj(dir / "rest.obj", seq.rest);
  c.templ = TemplateOptions{};
  c.templ.mesh = dir / "rest.obj";
  c.input.range = FrameRange{};
  const SequencePlan plan = plan_sequence_job(c);
  CHECK(plan.template_frame == -1);
  CHECK(plan.template_source == "rest.obj");
  r = run_sequence_job(plan);
  REQUIRE(r.frames.size() == 3);
  for (const FrameSummary& f : r.frames) CHECK(f.status == FrameStatus::Optimized);
}

TEST_CASE("frame ranges select the frames, the template is indexed in the full list") {
  test::TempDir dir("job_range");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(6));
  c.input.range = {1, 6, 2};
  const SequencePlan plan = plan_sequence_job(c);
  CHECK(plan.selected == std::vector<int>{1, 3, 5});
  const SequenceResult r = run_sequence_job(plan);
  REQUIRE(r.frames.size() == 3);
  CHECK(r.frames[1].frame == 3);
  CHECK(r.frames[1].file == "frame_0003.obj");
  CHECK_FALSE(fs::exists(dir / "out/frames/frame_0000.obj"));

  c.input.range = {7, std::nullopt, 1};
  CHECK(error_of([&] { plan_sequence_job(c); }) ==
        "input.range.start: 7 is beyond the last frame (the sequence has 6 frames, 0 to 5)");
  c.input.range = {};
  c.templ.frame = 9;
  CHECK(error_of([&] { plan_sequence_job(c); }) ==
        "template.frame: 9 is out of range (the sequence has 6 frames, 0 to 5)");
}

TEST_CASE("mismatched frames are refused before anything is written") {
  test::TempDir dir("job_mismatch");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(5));
  const SyntheticSequence other = make_synthetic_sequence(test::small_tube(5, 10));
  write_file_atomic(dir / "in/frame_0003.obj",
                    format_synthetic_obj(other, synthetic_frame(other, 3).drifted, "other"));
  CHECK(error_of([&] { plan_sequence_job(c); }) ==
        "frame 3 (frame_0003.obj): 110 vertices, but the template, frame 0 (frame_0000.obj), "
        "has 132");
  CHECK_THROWS_AS(plan_sequence_job(c), InputError);
  CHECK_FALSE(fs::exists(dir / "out"));

  // Same vertex count, one face changed.
  const SyntheticSequence seq = make_synthetic_sequence(test::small_tube(5));
  std::string text = format_synthetic_obj(seq, synthetic_frame(seq, 3).drifted, "frame 3");
  const size_t f = text.find("\nf ");
  const size_t end = text.find('\n', f + 1);
  text.replace(f, end - f, "\nf 1/1 3/3 2/2");
  write_file_atomic(dir / "in/frame_0003.obj", text);
  const std::string message = error_of([&] { plan_sequence_job(c); });
  CHECK(message.rfind("frame 3 (frame_0003.obj): faces differ from the template's, frame 0 "
                      "(frame_0000.obj): triangle 1 has vertices 1 3 2, the template's ",
                      0) == 0);
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("an output folder that would overwrite an input is refused") {
  test::TempDir dir("job_overwrite");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(5));
  fs::rename(dir / "in", dir / "frames");
  c.input.frames = dir / "frames";
  c.output.dir = dir.path();
  const std::string message = error_of([&] { plan_sequence_job(c); });
  CHECK(message.rfind("output.dir: writing ", 0) == 0);
  CHECK(message.find("would overwrite an input file") != std::string::npos);
  CHECK_THROWS_AS(plan_sequence_job(c), ConfigError);
  CHECK_FALSE(fs::exists(dir / "summary.csv"));
}

TEST_CASE("a cancelled run stops before the next frame and records it") {
  test::TempDir dir("job_cancel");
  const SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(5));
  std::atomic<bool> cancel{true};
  RunHooks hooks;
  hooks.cancel = &cancel;
  const SequenceResult r = run_sequence_job(plan_sequence_job(c), hooks);
  CHECK(r.interrupted);
  CHECK(r.frames.empty());
  CHECK(read_file(dir / "out/summary.csv") == format_summary_csv({}, false));
  CHECK(nlohmann::json::parse(read_file(dir / "out/report.json"))["interrupted"] == true);
}

TEST_CASE("a synthetic input is generated with its ground truth") {
  test::TempDir dir("job_synthetic");
  SequenceJobOptions c;
  c.input.synthetic = test::small_tube(4);
  c.output.dir = dir / "out";
  c.threads = 2;
  const SequencePlan plan = plan_sequence_job(c);
  CHECK_FALSE(fs::exists(dir / "out"));  // planning writes nothing
  const std::string description = describe_plan(plan);
  CHECK(description.find("input: synthetic bending tube, 4 frames of 132 vertices") !=
        std::string::npos);
  CHECK(description.find("template: frame 0 (frame_0000.obj), 132 vertices, 240 triangles; "
                         "written unchanged") != std::string::npos);
  const SequenceResult r = run_sequence_job(plan);
  CHECK(fs::exists(dir / "out/input/frame_0003.obj"));
  CHECK(fs::exists(dir / "out/ground_truth/frame_0003.obj"));
  REQUIRE(r.frames.size() == 4);
  REQUIRE(r.frames[3].ground_truth);
  CHECK(r.frames[3].ground_truth->mean_after < r.frames[3].ground_truth->mean_before);
  const nlohmann::json report = nlohmann::json::parse(read_file(dir / "out/report.json"));
  CHECK(report["ground_truth"]["mean_after"] < report["ground_truth"]["mean_before"]);
  CHECK(report["run"]["threads"] == 2);
}
