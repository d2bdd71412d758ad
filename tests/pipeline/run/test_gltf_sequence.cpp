// The sequence job on glTF animations built in code: GLB and OBJ outputs, round trips of the
// written GLB against the OBJ frames and summary.csv, seams that stay closed, determinism across
// thread counts, frame selection, bad files refused before anything is written; and, when
// ../shared/data/gltf is present, every real model through the whole job.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "io/atomic_file.hpp"
#include "io/gltf/gltf_file.hpp"
#include "io/obj.hpp"
#include "core/errors.hpp"
#include "mesh/topology.hpp"
#include "pipeline/report/report.hpp"
#include "pipeline/run/sequence_job.hpp"
#include "support/error_of.hpp"
#include "support/gltf_models.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
using Catch::Contains;
using test::error_of;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// A job on `gltf` writing to `out`, without timings (so runs compare byte for byte).
SequenceJobOptions gltf_job(const fs::path& gltf, const fs::path& out, OutputFormat format,
                            std::optional<double> fps = std::nullopt) {
  SequenceJobOptions c;
  c.input.gltf = GltfInputOptions{gltf, "", "", fps};
  c.output.dir = out;
  c.output.format = format;
  c.output.per_triangle_csv = true;
  c.output.timings = false;
  c.output.html = false;  // report.html has its own tests (test_html_report.cpp)
  c.massage.iterations = 6;
  c.threads = 2;
  // The skin creases the 8-triangle strip so sharply (shear 13 at the seam) that one triangle
  // folds in its most bent frames: counted, not failed, so that every frame is compared.
  c.checks.max_folded_fraction.reset();
  return c;
}

// Every regular file under `dir`, as paths relative to it.
std::vector<fs::path> files_under(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) files.push_back(fs::relative(entry.path(), dir));
  std::sort(files.begin(), files.end());
  return files;
}

// Every split copy of a welded vertex has exactly the same position in every frame of `glb`,
// whose glTF vertices are those of `source` (the writer keeps the source's vertex order).
void require_closed_seams(const GltfSequence& source, const GltfSequence& glb) {
  REQUIRE(glb.gltf_vertices == source.gltf_vertices);
  for (int k = 0; k < glb.num_frames(); ++k) {
    const Positions P = evaluate_gltf_vertices(glb, glb.times[size_t(k)]);
    std::vector<int> first(size_t(source.rest.num_vertices()), -1);
    int copies = 0;
    for (size_t v = 0; v < source.weld_map.size(); ++v) {
      const int w = source.weld_map[v];
      if (w < 0) continue;
      if (first[size_t(w)] < 0) {
        first[size_t(w)] = int(v);
        continue;
      }
      INFO("frame " << k << ", glTF vertex " << v << ", copy of " << first[size_t(w)]);
      REQUIRE(P.row(Eigen::Index(v)) == P.row(first[size_t(w)]));
      ++copies;
    }
    CHECK(copies == source.welded_vertices);
  }
}

}  // namespace

TEST_CASE("a skinned glTF runs to sequence.glb and to OBJ frames with the same results") {
  test::TempDir dir("gltf_job");
  test::skinned_strip().save(dir / "strip.glb", true);
  const GltfSequence source = load_gltf_sequence({dir / "strip.glb", "", "", 20.0});
  REQUIRE(source.num_frames() == 21);

  const SequenceJobOptions c = gltf_job(dir / "strip.glb", dir / "glb", OutputFormat::Gltf, 20.0);
  const SequencePlan plan = plan_sequence_job(c);
  CHECK_FALSE(fs::exists(dir / "glb"));  // planning writes nothing
  const std::string description = describe_plan(plan);
  CHECK_THAT(description, Contains("input: glTF strip.glb, mesh 0 'strip' (node 3), animation 0 "
                                   "'take', "
                                   "21 frames at 20 fps (0 to 1 s); 12 glTF vertices welded to "
                                   "10 (2 split copies merged)"));
  CHECK_THAT(description, Contains("template: frame 0 (frame_0000.obj, t = 0 s), 10 vertices"));
  CHECK_THAT(description, Contains("sequence.glb (21 frames, one morph target each, over 1 mesh"));
  const SequenceResult r = run_sequence_job(plan);
  REQUIRE(r.frames.size() == 21);
  CHECK(r.failed == 0);
  // distortion/*.csv, positions/*.bin, records/*.json, summary, report, GLB
  CHECK(files_under(dir / "glb").size() == 3 * 21 + 3);
  CHECK_FALSE(fs::exists(dir / "glb/frames"));
  test::require_valid_gltf(dir / "glb/sequence.glb");

  const json report = json::parse(read_file(dir / "glb/report.json"));
  CHECK(report["input"]["kind"] == "gltf");
  CHECK(report["input"]["gltf_vertices"] == 12);
  CHECK(report["input"]["vertices"] == 10);
  CHECK(report["input"]["welded_vertices"] == 2);
  CHECK(report["input"]["fps"] == 20.0);
  CHECK(report["outputs"]["gltf"] == "sequence.glb");
  CHECK(report["config"]["input"]["gltf"] == (dir / "strip.glb").string());

  // The same job with OBJ output: the same summary, and frames the GLB plays back.
  SequenceJobOptions obj = c;
  obj.output.dir = dir / "obj";
  obj.output.format = OutputFormat::Obj;
  run_sequence_job(plan_sequence_job(obj));
  CHECK(read_file(dir / "obj/summary.csv") == read_file(dir / "glb/summary.csv"));
  CHECK(read_file(dir / "obj/distortion/frame_0013.csv") ==
        read_file(dir / "glb/distortion/frame_0013.csv"));

  const GltfSequence glb = load_gltf_sequence({dir / "glb/sequence.glb", "", "", std::nullopt});
  REQUIRE(glb.num_frames() == 21);
  CHECK(glb.rest.F == source.rest.F);
  int moved = 0;
  for (int k = 0; k < 21; ++k) {
    INFO("frame " << k);
    const FrameSummary& s = r.frames[size_t(k)];
    CHECK(s.frame == k);
    CHECK(s.file == "frame_00" + std::string(k < 10 ? "0" : "") + std::to_string(k) + ".obj");
    REQUIRE(s.time);
    CHECK(*s.time == source.times[size_t(k)]);
    CHECK(float(glb.times[size_t(k)]) == float(*s.time));
    CHECK(s.vertices == 10);
    CHECK(s.triangles == 8);
    const ObjFile frame = read_obj(dir / "obj/frames" / s.file);
    CHECK(frame.mesh.F == source.rest.F);
    CHECK(frame.texcoords.rows() == 12);  // one vt per glTF vertex: the UV seam is kept
    test::require_close(evaluate_gltf_frame(glb, k).V, frame.mesh.V);
    const Positions input = evaluate_gltf_frame(source, k).V;
    if (k == 0) {
      CHECK(s.status == FrameStatus::Template);
      CHECK(frame.mesh.V == input);  // written unchanged
    } else {
      CHECK(s.status == FrameStatus::Optimized);
      moved += (frame.mesh.V - input).cwiseAbs().maxCoeff() > 1e-9;
    }
  }
  CHECK(moved > 0);
  require_closed_seams(source, glb);

  // The GLB keeps the source's material and texture.
  const GltfFile written = load_gltf_file(dir / "glb/sequence.glb");
  CHECK(written.json["materials"] == load_gltf_file(dir / "strip.glb").json["materials"]);
  CHECK(written.model.images.size() == 1);
}

TEST_CASE("glTF jobs write the same bytes with 1 and 2 threads") {
  test::TempDir dir("gltf_threads");
  test::skinned_strip(true).save(dir / "strip.gltf", false);  // .gltf + .bin, two weight sets
  for (const OutputFormat format : {OutputFormat::Gltf, OutputFormat::Obj}) {
    SequenceJobOptions c = gltf_job(dir / "strip.gltf", dir / "one", format, 15.0);
    c.threads = 1;
    run_sequence_job(plan_sequence_job(c));
    c.threads = 2;
    c.frames_in_flight = 3;
    c.output.dir = dir / "two";
    run_sequence_job(plan_sequence_job(c));
    const std::vector<fs::path> files = files_under(dir / "one");
    CHECK(files == files_under(dir / "two"));
    // frames/*.obj or positions/*.bin, distortion/*.csv, records/*.json, summary, report, GLB
    CHECK(int(files.size()) == 16 * 3 + 2 + (format == OutputFormat::Gltf ? 1 : 0));
    for (const fs::path& file : files) {
      if (file == "report.json") continue;  // holds the thread count
      INFO(file.string());
      CHECK(read_file(dir / "one" / file) == read_file(dir / "two" / file));
    }
    fs::remove_all(dir / "one");
    fs::remove_all(dir / "two");
  }
}

TEST_CASE("morph-target and node-animated glTF: OBJ frames, frame selection into the GLB") {
  test::TempDir dir("gltf_kinds");
  test::morph_quad().save(dir / "quad.glb", true);
  SequenceJobOptions c = gltf_job(dir / "quad.glb", dir / "quad", OutputFormat::Obj);
  SequenceResult r = run_sequence_job(plan_sequence_job(c));
  REQUIRE(r.frames.size() == 3);  // the keyframe times 0, 1, 2
  CHECK(r.frames[2].time == 2.0);
  const ObjFile quad = read_obj(dir / "quad/frames/frame_0002.obj");
  CHECK(quad.texcoords.rows() == 0);
  CHECK(quad.normals.rows() == 4);  // NORMAL kept as vn, recomputed for the new positions
  CHECK(quad.corners[0].vn >= 0);
  CHECK(quad.corners[0].vt < 0);

  test::node_animated_triangle().save(dir / "nodes.glb", true);
  c = gltf_job(dir / "nodes.glb", dir / "nodes", OutputFormat::Gltf, 10.0);
  c.input.range = {1, 21, 5};
  const SequencePlan plan = plan_sequence_job(c);
  CHECK(plan.selected == std::vector<int>{1, 6, 11, 16});
  r = run_sequence_job(plan);
  REQUIRE(r.frames.size() == 4);
  c.output.format = OutputFormat::Obj;
  c.output.dir = dir / "nodes-obj";
  run_sequence_job(plan_sequence_job(c));
  const GltfSequence all = load_gltf_sequence({dir / "nodes.glb", "", "", 10.0});
  const GltfSequence glb = load_gltf_sequence({dir / "nodes/sequence.glb", "", "", std::nullopt});
  REQUIRE(glb.num_frames() == 4);
  for (int k = 0; k < 4; ++k) {
    const int frame = plan.selected[size_t(k)];
    INFO("frame " << frame);
    CHECK(float(glb.times[size_t(k)]) == float(all.times[size_t(frame)]));
    const fs::path obj =
        dir / "nodes-obj/frames" / ("frame_00" + std::to_string(100 + frame).substr(1) + ".obj");
    test::require_close(evaluate_gltf_frame(glb, k).V, read_obj(obj).mesh.V);
  }
  test::require_valid_gltf(dir / "nodes/sequence.glb");
}

TEST_CASE("a cancelled glTF run writes no GLB and says so") {
  test::TempDir dir("gltf_cancel");
  test::morph_quad().save(dir / "quad.glb", true);
  std::atomic<bool> cancel{true};
  RunHooks hooks;
  hooks.cancel = &cancel;
  const SequenceResult r = run_sequence_job(
      plan_sequence_job(gltf_job(dir / "quad.glb", dir / "out", OutputFormat::Gltf)), hooks);
  CHECK(r.interrupted);
  CHECK_FALSE(fs::exists(dir / "out/sequence.glb"));
  CHECK(files_under(dir / "out") == std::vector<fs::path>{"report.json", "summary.csv"});
  REQUIRE_FALSE(r.warnings.empty());
  CHECK(r.warnings.back() == "no frame was processed, so sequence.glb was not written");
}

TEST_CASE("bad glTF inputs are refused before anything is written, naming file and element") {
  test::TempDir dir("gltf_bad");
  const fs::path out = dir / "out";
  const auto plan_error = [&](const fs::path& file, std::optional<double> fps = std::nullopt) {
    return error_of([&] { plan_sequence_job(gltf_job(file, out, OutputFormat::Gltf, fps)); });
  };

  test::skinned_strip().save(dir / "strip.glb", true);
  const std::string bytes = read_file(dir / "strip.glb");
  write_file_atomic(dir / "truncated.glb", bytes.substr(0, bytes.size() / 2));
  CHECK_THAT(plan_error(dir / "truncated.glb"), Contains("truncated.glb") && Contains("GLB"));
  CHECK_THROWS_AS(plan_sequence_job(gltf_job(dir / "truncated.glb", out, OutputFormat::Gltf)),
                  InputError);

  test::skinned_strip().save(dir / "lost.gltf", false);
  fs::remove(dir / "lost.bin");
  CHECK_THAT(plan_error(dir / "lost.gltf"),
             Contains("lost.gltf") && Contains("buffers[0]") && Contains("not found"));

  test::ModelBuilder still = test::skinned_strip();
  still.m.animations.clear();
  still.save(dir / "still.glb", true);
  CHECK_THAT(plan_error(dir / "still.glb"),
             Contains("still.glb") && Contains("animations") && Contains("no animation"));

  test::ModelBuilder lines = test::morph_quad();
  lines.m.meshes[0].primitives[0].mode = TINYGLTF_MODE_LINE;
  lines.save(dir / "lines.glb", true);
  CHECK_THAT(plan_error(dir / "lines.glb"), Contains("lines.glb") &&
                                                Contains("meshes[0].primitives[0]") &&
                                                Contains("not a triangle primitive"));

  SequenceJobOptions c = gltf_job(dir / "strip.glb", out, OutputFormat::Gltf);
  c.input.gltf->animation = "walk";
  CHECK_THAT(error_of([&] { plan_sequence_job(c); }),
             Contains("strip.glb") && Contains("animations") && Contains("'walk'"));
  c.input.gltf->animation_index = 1;
  CHECK_THAT(error_of([&] { plan_sequence_job(c); }),
             Contains("no animation numbered 1 (the file has 0 'take')"));
  c.input.gltf->animation_index = 0;  // the index wins over the name
  c.input.gltf->mesh = "strip";
  CHECK_NOTHROW(plan_sequence_job(c));

  CHECK_THAT(plan_error(dir / "strip.glb", 1e9), Contains("input.fps"));
  CHECK_THROWS_AS(plan_sequence_job(gltf_job(dir / "strip.glb", out, OutputFormat::Gltf, 1e9)),
                  ConfigError);
  CHECK_THROWS_AS(plan_sequence_job(gltf_job(dir / "missing.glb", out, OutputFormat::Gltf)),
                  IoError);
  CHECK_FALSE(fs::exists(out));

  // An output that would replace the input.
  fs::copy_file(dir / "strip.glb", dir / "sequence.glb");
  CHECK_THAT(error_of([&] {
               plan_sequence_job(gltf_job(dir / "sequence.glb", dir.path(), OutputFormat::Gltf));
             }),
             Contains("output.dir: writing ") && Contains("would overwrite an input file"));
}

// ---------------------------------------------------------------------------------------------
// Every real model of ../shared/data/gltf (data/README.md §2), when present.

TEST_CASE("every real glTF model runs through the job to a valid GLB", "[data]") {
  if (!test::have_shared_gltf()) return;
  test::TempDir dir("gltf_real_job");
  for (const test::SharedGltfModel& model : test::kSharedGltfModels) {
    INFO(model.file);
    SequenceJobOptions c =
        gltf_job(test::shared_gltf_dir() / model.file, dir / "out", OutputFormat::Gltf);
    c.massage.iterations = 4;
    c.output.per_triangle_csv = false;
    const int frames = load_gltf_sequence(*c.input.gltf).num_frames();
    c.input.range.step = std::max(1, frames / 12);  // about a dozen frames per model
    const SequencePlan plan = plan_sequence_job(c);
    CHECK(plan.templ.num_vertices() == model.welded_vertices);
    CHECK(plan.templ.num_triangles() == model.triangles);
    const Topology topo = build_topology(plan.templ);
    CHECK(topo.is_manifold());
    CHECK(int(topo.boundary_loops.size()) == model.boundary_loops);

    const SequenceResult r = run_sequence_job(plan);
    REQUIRE(r.frames.size() == plan.selected.size());
    CHECK(r.failed == 0);
    for (const FrameSummary& f : r.frames) {
      CHECK(std::isfinite(f.shear_after.mean));
      CHECK(f.vertices == plan.templ.num_vertices());
    }
    test::require_valid_gltf(dir / "out/sequence.glb");
    const GltfSequence source = load_gltf_sequence(*c.input.gltf);
    const GltfSequence glb = load_gltf_sequence({dir / "out/sequence.glb", "", "", std::nullopt});
    REQUIRE(glb.num_frames() == int(plan.selected.size()));
    CHECK(glb.rest.F == source.rest.F);
    require_closed_seams(source, glb);
    fs::remove_all(dir / "out");
  }
}

TEST_CASE("real glTF models with several primitives give one OBJ group per primitive", "[data]") {
  if (!test::have_shared_gltf()) return;
  test::TempDir dir("gltf_real_obj");
  SequenceJobOptions c =
      gltf_job(test::shared_gltf_dir() / "morph/MorphStressTest/glTF-Binary/MorphStressTest.glb",
               dir / "out", OutputFormat::Obj);
  c.massage.iterations = 2;
  c.input.range = {0, 2, 1};
  run_sequence_job(plan_sequence_job(c));
  const std::string text = read_file(dir / "out/frames/frame_0001.obj");
  CHECK_THAT(text, Contains("\ng primitive_0\n") && Contains("\ng primitive_1\n"));
  const ObjFile obj = parse_obj(text, "frame_0001.obj");
  CHECK(obj.mesh.num_vertices() == 1224);
  CHECK(obj.texcoords.rows() == 1528);
}

TEST_CASE("static real glTF models are a clear 'no animation' error, nothing written", "[data]") {
  if (!test::have_shared_gltf()) return;
  test::TempDir dir("gltf_real_static");
  for (const char* file : test::kStaticGltfModels) {
    INFO(file);
    const std::string message = error_of([&] {
      plan_sequence_job(gltf_job(test::shared_gltf_dir() / file, dir / "out", OutputFormat::Gltf));
    });
    CHECK_THAT(message, Contains(file) && Contains("no animation"));
    CHECK_FALSE(fs::exists(dir / "out"));
  }
}
