// The sequence job's visual outputs end to end: colored PLY files whose colours match the
// per-triangle CSV, checker OBJ + MTL + PNG with the template's texture coordinates in every
// frame, iterations.csv (with shear after every iteration for chosen frames), frame selections,
// glTF input, a rest-mesh template, and the same bytes with 1 or 2 threads.
#include <catch2/catch.hpp>

#include <sstream>

#include "io/atomic_file.hpp"
#include "io/mesh_file.hpp"
#include "io/obj.hpp"
#include "io/ply.hpp"
#include "io/png.hpp"
#include "massage/reference.hpp"
#include "pipeline/outputs/checker.hpp"
#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/sequence/iteration_log.hpp"
#include "pipeline/run/sequence_job.hpp"
#include "pipeline/outputs/shear_ply.hpp"
#include "pipeline/sequence/synthetic.hpp"
#include "support/gltf_models.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"
#include "support/text_files.hpp"

using namespace sm;
using test::read_csv;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// A folder of drifted frames under `dir`/in, a job on it writing to `dir`/out with every visual
// output on.
SequenceJobOptions visual_job(const fs::path& dir, int frames = 5) {
  SyntheticOptions s = test::small_tube(frames);
  s.drift = 0.8;
  SequenceJobOptions c = test::tube_job(dir, s);
  c.output.colored.enabled = true;
  c.output.colored.max = 0.05;
  c.output.checker.enabled = true;
  c.output.iterations.enabled = true;
  c.output.iterations.shear_frames = FrameSelection{FrameSelection::Kind::List, {3}, 0, {}, 1};
  c.massage.iterations = 6;
  return c;
}

size_t column(const std::vector<std::vector<std::string>>& rows, const std::string& name) {
  const auto& h = rows.at(0);
  const auto it = std::find(h.begin(), h.end(), name);
  REQUIRE(it != h.end());
  return size_t(it - h.begin());
}

}  // namespace

TEST_CASE("colored PLY files carry the per-triangle CSV's shear as colours, before and after") {
  test::TempDir dir("extras_colored");
  const SequenceJobOptions c = visual_job(dir.path());
  const SequencePlan plan = plan_sequence_job(c);
  const std::string described = describe_plan(plan);
  CHECK(described.find("colored/{before,after}/<name>.ply (5 frames: shear 0 blue to 0.05") !=
        std::string::npos);
  CHECK(described.find("checker/{before,after}/<name>.obj") != std::string::npos);
  CHECK(described.find("iterations.csv (the optimized frames among 5 frames; shear after every "
                       "iteration for 1 frame") != std::string::npos);
  run_sequence_job(plan);
  for (int frame : {0, 2, 4}) {
    const std::string name = "frame_000" + std::to_string(frame);
    const auto csv = read_csv(dir / ("out/distortion/" + name + ".csv"));
    for (const char* side : {"before", "after"}) {
      INFO(name << " " << side);
      PlyColors colors;
      const TriMesh ply =
          read_ply(dir / ("out/colored/" + std::string(side) + "/" + name + ".ply"), &colors);
      const ObjFile source =
          read_obj(dir / (std::string(side) == "before" ? "in/" : "out/frames/") / (name + ".obj"));
      const Eigen::Index m = source.mesh.num_triangles();
      REQUIRE(ply.num_triangles() == m);
      REQUIRE(ply.num_vertices() == 3 * m);
      REQUIRE(csv.size() == size_t(m) + 1);
      const size_t col = column(csv, std::string("shear_") + side);
      int red = 0, blue = 0;
      for (Eigen::Index t = 0; t < m; t += 7) {  // a sample of the triangles
        const double shear = std::stod(csv[size_t(t) + 1][col]);
        const std::array<uint8_t, 3> expected = shear_color(shear, 0.05);
        CHECK(colors.face[size_t(t)] == expected);
        CHECK(colors.vertex[size_t(3 * t)] == expected);
        red += expected == std::array<uint8_t, 3>{255, 0, 0};
        blue += expected == std::array<uint8_t, 3>{0, 0, 255};
        for (int k = 0; k < 3; ++k)
          CHECK(ply.V.row(3 * t + k) == source.mesh.V.row(source.mesh.F(t, k)));
      }
      if (frame == 0) CHECK(red == 0);  // the template against itself: all blue
      if (frame == 0) CHECK(blue > 0);
    }
  }
}

TEST_CASE("checker frames share the template's texture coordinates; texture and material") {
  test::TempDir dir("extras_checker");
  const SequenceJobOptions c = visual_job(dir.path());
  const SequenceResult r = run_sequence_job(plan_sequence_job(c));
  const ObjFile templ = read_obj(dir / "in/frame_0000.obj");
  const CornerUv own = *input_uv(templ, templ.mesh.F);
  for (const char* side : {"before", "after"}) {
    const fs::path folder = dir / "out/checker" / side;
    CHECK(read_file(folder / "checker.png") == encode_png(checker_texture(8)));
    CHECK(read_file(folder / "checker.mtl").find("map_Kd checker.png") != std::string::npos);
    for (int frame = 0; frame < 5; ++frame) {
      const std::string name = "frame_000" + std::to_string(frame) + ".obj";
      const std::string text = read_file(folder / name);
      CHECK(text.find("mtllib checker.mtl\n") != std::string::npos);
      const ObjFile obj = parse_obj(text, name);
      CHECK(obj.texcoords == own.uv);  // the synthetic frames' own vt, from the template
      for (Eigen::Index t = 0; t < obj.mesh.num_triangles(); ++t)
        for (int k = 0; k < 3; ++k) CHECK(obj.corners[size_t(3 * t + k)].vt == own.faces(t, k));
      const ObjFile source =
          read_obj(dir / (std::string(side) == "before" ? "in/" : "out/frames/") / name);
      CHECK(obj.mesh.V == source.mesh.V);
      CHECK(obj.mesh.F == source.mesh.F);
    }
  }
  for (const std::string& w : r.warnings) CHECK(w.find("folded") != std::string::npos);
  const json report = json::parse(read_file(dir / "out/report.json"));
  CHECK(report["outputs"]["checker"]["uv"] == "input");
  CHECK(report["outputs"]["colored"]["shear_red"] == 0.05);
  CHECK(report["outputs"]["iterations"] == "iterations.csv");
  CHECK(report["config"]["output"]["checker"]["cells"] == 8);
}

TEST_CASE(
    "iterations.csv: the engine's figures per iteration, shear after each for chosen frames") {
  test::TempDir dir("extras_iterations");
  SequenceJobOptions c = visual_job(dir.path());
  c.massage.tolerance = 0.0;  // run every iteration
  const SequenceResult r = run_sequence_job(plan_sequence_job(c));
  const auto rows = read_csv(dir / "out/iterations.csv");
  CHECK(rows[0] == iteration_columns());
  const size_t frame = column(rows, "frame"), it = column(rows, "iteration"),
               max = column(rows, "shear_max"), mean = column(rows, "shear_mean"),
               dist = column(rows, "max_dist_m_to_n"), energy = column(rows, "energy");
  // Frames 1..4 optimized (the template frame is not logged), 0..6 iterations each.
  REQUIRE(rows.size() == 1 + 4 * 7);
  for (int f = 1; f <= 4; ++f) {
    const FrameSummary& s = r.frames[size_t(f)];
    for (int k = 0; k <= 6; ++k) {
      const auto& row = rows[size_t(1 + (f - 1) * 7 + k)];
      INFO("frame " << f << " iteration " << k);
      CHECK(row[frame] == std::to_string(f));
      CHECK(row[it] == std::to_string(k));
      if (k == 0) {
        CHECK(std::stod(row[max]) == s.shear_before.max);
        CHECK(std::stod(row[dist]) == 0.0);
        CHECK(row[energy].empty());
      } else {
        CHECK(std::stod(row[energy]) > 0.0);
        CHECK(std::stod(row[dist]) > 0.0);
      }
      if (k == 6) CHECK(std::stod(row[mean]) == s.shear_after.mean);
      const bool measured = k == 0 || k == 6 || f == 3;
      CHECK(row[max].empty() == !measured);
    }
  }
  // Frame 3's shear falls over the iterations as the optimizer corrects it.
  CHECK(std::stod(rows[1 + 2 * 7 + 1][mean]) < std::stod(rows[1 + 2 * 7][mean]));
  CHECK(std::stod(rows[1 + 2 * 7 + 6][mean]) < std::stod(rows[1 + 2 * 7 + 1][mean]));
}

TEST_CASE("visual outputs of chosen frames only; listed frames not processed are warned about") {
  test::TempDir dir("extras_frames");
  SequenceJobOptions c = visual_job(dir.path(), 6);
  c.output.colored.frames = FrameSelection{FrameSelection::Kind::List, {1, 4, 9}, 0, {}, 1};
  c.output.checker.frames = FrameSelection{FrameSelection::Kind::Range, {}, 0, std::nullopt, 2};
  c.output.iterations.frames = FrameSelection::none();
  c.output.iterations.shear_frames = FrameSelection{FrameSelection::Kind::List, {5}, 0, {}, 1};
  c.input.range.stop = 5;
  const SequencePlan plan = plan_sequence_job(c);
  REQUIRE(plan.warnings.size() == 2);
  CHECK(plan.warnings[0] ==
        "output.colored.frames: frame 9 not processed by this run (see input.range and --frames)");
  CHECK(plan.warnings[1].rfind("output.iterations.shear_frames: frame 5 not processed", 0) == 0);
  run_sequence_job(plan);
  for (int f = 0; f < 6; ++f) {
    const std::string name = "frame_000" + std::to_string(f);
    CHECK(fs::exists(dir / ("out/colored/after/" + name + ".ply")) == (f == 1 || f == 4));
    CHECK(fs::exists(dir / ("out/checker/before/" + name + ".obj")) ==
          (f == 0 || f == 2 || f == 4));
  }
  CHECK(read_csv(dir / "out/iterations.csv").size() == 1);  // no frame logged: the header
}

TEST_CASE("visual outputs are the same bytes with 1 or 2 threads") {
  test::TempDir dir("extras_threads");
  SequenceJobOptions c = visual_job(dir.path(), 6);
  c.output.iterations.shear_frames = FrameSelection{};  // all
  c.output.checker.uv = CheckerUvSource::Charts;
  c.output.colored.colors = ShearColorMode::Vertices;
  c.threads = 1;
  c.output.dir = dir / "one";
  run_sequence_job(plan_sequence_job(c));
  c.threads = 2;
  c.frames_in_flight = 3;
  c.output.dir = dir / "two";
  run_sequence_job(plan_sequence_job(c));
  // report.json names its own output folder and thread count.
  CHECK(test::compare_folders(dir / "one", dir / "two", "report.json").size() > 6 * 6);
}

TEST_CASE("checker charts on a rest mesh without texture coordinates; glTF input") {
  test::TempDir dir("extras_rest");
  SECTION("a rest mesh (OFF, no texture coordinates) as the template: charts") {
    SequenceJobOptions c = visual_job(dir.path(), 3);
    SyntheticOptions s;
    s.segments = 12;
    s.rings = 10;
    const SyntheticSequence seq = make_synthetic_sequence(s);
    write_mesh(dir / "rest.off", TriMesh{synthetic_frame(seq, 0).clean, seq.F});
    c.templ.mesh = dir / "rest.off";
    run_sequence_job(plan_sequence_job(c));
    const ObjFile a = read_obj(dir / "out/checker/after/frame_0001.obj");
    const ObjFile b = read_obj(dir / "out/checker/before/frame_0002.obj");
    CHECK(a.texcoords.rows() > a.mesh.num_vertices());  // split at chart borders
    CHECK(a.texcoords == b.texcoords);
    const json report = json::parse(read_file(dir / "out/report.json"));
    CHECK(report["outputs"]["checker"]["uv"] == "charts");
    CHECK(report["outputs"]["checker"]["uv_template"] == "rest.off");
  }
  SECTION("glTF input: welded vertices coloured, TEXCOORD_0 for the checker") {
    test::skinned_strip().save(dir / "strip.glb", true);
    SequenceJobOptions c;
    c.input.gltf = GltfInputOptions{dir / "strip.glb", "", "", 4.0};
    c.output.dir = dir / "out";
    c.output.timings = false;
    c.output.per_triangle_csv = true;
    c.output.colored.enabled = true;
    c.output.checker.enabled = true;
    c.massage.iterations = 3;
    const SequencePlan plan = plan_sequence_job(c);
    run_sequence_job(plan);
    const int m = plan.templ.num_triangles();
    for (int f = 0; f < plan.source->size(); ++f) {
      const std::string name = numbered_frame_name(f, plan.source->size());
      PlyColors colors;
      const TriMesh ply =
          read_ply(dir / "out/colored/after" / fs::path(name).replace_extension(".ply"), &colors);
      CHECK(ply.num_triangles() == m);
      const ObjFile obj = read_obj(dir / "out/checker/after" / name);
      CHECK(obj.mesh.num_vertices() == plan.templ.num_vertices());
      CHECK(obj.texcoords == plan.source->decode(0, "").obj->texcoords);
    }
    const json report = json::parse(read_file(dir / "out/report.json"));
    CHECK(report["outputs"]["checker"]["uv"] == "input");
  }
}

TEST_CASE("shear per iteration is measured on the iterates of the frame's one run") {
  SyntheticOptions s;
  s.frames = 4;
  s.segments = 10;
  s.rings = 8;
  const SyntheticSequence seq = make_synthetic_sequence(s);
  const TriMesh templ{synthetic_frame(seq, 0).drifted, seq.F};
  const TriMesh frame{synthetic_frame(seq, 3).drifted, seq.F};
  MassageOptions options;
  options.iterations = 5;
  options.tolerance = 0.0;
  const Massager massager(templ, options);
  const Reference reference(frame, options.samples, "frame 3", massager.shared_topology());
  std::vector<std::optional<DistortionSummary>> shear;
  const MassageResult full = massager.run(frame.V, reference, shear_observer(templ, shear));
  REQUIRE(full.ok);
  REQUIRE(full.iterations.size() == 5);
  REQUIRE(shear.size() == 5);
  // Each entry is the shear of the j-th iterate: the result of a run limited to j iterations.
  for (int j = 1; j <= 5; ++j) {
    MassageOptions limited = options;
    limited.iterations = j;
    const MassageResult run = Massager(templ, limited).run(frame.V, reference);
    REQUIRE(shear[size_t(j - 1)]);
    CHECK(shear[size_t(j - 1)]->mean ==
          summarize_distortion(shear_distortion(templ.V, run.V, templ.F)).mean);
    CHECK(shear[size_t(j - 1)]->max ==
          summarize_distortion(shear_distortion(templ.V, run.V, templ.F)).max);
  }
  const auto rows =
      iteration_rows(full, summarize_distortion(shear_distortion(templ.V, frame.V, templ.F)),
                     summarize_distortion(shear_distortion(templ.V, full.V, templ.F)), shear);
  REQUIRE(rows.size() == 6);
  CHECK(rows[0].iteration == 0);
  CHECK_FALSE(rows[0].stats);
  for (size_t k = 1; k < rows.size(); ++k) {
    CHECK(rows[k].iteration == int(k));
    CHECK(rows[k].shear.has_value());
  }
  CHECK(rows[3].shear->mean < rows[1].shear->mean);
}

TEST_CASE("displacement CSVs hold every vertex's output minus its input") {
  test::TempDir dir("extras_displacement");
  SequenceJobOptions c = visual_job(dir.path(), 4);
  c.output.displacement_csv = true;
  const SequencePlan plan = plan_sequence_job(c);
  CHECK(describe_plan(plan).find("displacement/<name>.csv (4 files)") != std::string::npos);
  CHECK(outputs_help().find("displacement/<frame>.csv") != std::string::npos);
  run_sequence_job(plan);
  for (int frame = 0; frame < 4; ++frame) {
    const std::string name = "frame_000" + std::to_string(frame);
    INFO(name);
    const auto csv = read_csv(dir / ("out/displacement/" + name + ".csv"));
    const TriMesh in = read_obj(dir / ("in/" + name + ".obj")).mesh;
    const TriMesh out = read_obj(dir / ("out/frames/" + name + ".obj")).mesh;
    REQUIRE(csv.size() == size_t(in.num_vertices()) + 1);
    CHECK(csv[0] == std::vector<std::string>{"vertex", "dx", "dy", "dz"});
    double moved = 0.0;
    for (Eigen::Index v = 0; v < in.num_vertices(); ++v) {
      const auto& row = csv[size_t(v) + 1];
      REQUIRE(std::stol(row[0]) == v);
      for (int k = 0; k < 3; ++k) {
        const double d = std::stod(row[size_t(k) + 1]);
        CHECK(in.V(v, k) + d == Approx(out.V(v, k)).margin(1e-12));
        moved += std::abs(d);
      }
    }
    if (frame == 0) CHECK(moved == 0.0);  // the template frame is written as it is
    if (frame > 0) CHECK(moved > 0.0);
  }
  const json record = json::parse(read_file(dir / "out/records/frame_0002.json"));
  CHECK(record.dump().find("displacement/frame_0002.csv") != std::string::npos);
}
