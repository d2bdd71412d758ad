// The single-mesh jobs end to end on meshes generated in code: remesh (Hausdorff distance to the
// source), smooth (triangle quality, surface and sharp edges kept), crossparam (shear against the
// template), pinning, outputs and formats, determinism, and the checks before anything is written.
#include <catch2/catch.hpp>
#include <fstream>

#include "io/atomic_file.hpp"
#include "io/mesh_file.hpp"
#include "io/obj.hpp"
#include "io/off.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"
#include "pipeline/mesh_jobs/mesh_job.hpp"
#include "pipeline/mesh_jobs/mesh_report.hpp"
#include "support/html_player.hpp"
#include "support/error_of.hpp"
#include "support/job_meshes.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
using test::error_of;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

MeshJobOptions job_config(JobKind job, const fs::path& dir, const std::string& mesh_file) {
  MeshJobOptions c;
  c.job = job;
  c.massage = default_massage_options(job);
  c.input.mesh = dir / mesh_file;
  c.output.dir = dir / "out";
  c.output.timings = false;
  c.threads = 2;
  return c;
}

// Runs a remesh of `pair` and returns the result.
MeshJobResult remesh(const test::RemeshPair& pair, const fs::path& dir, SampleKind samples) {
  write_mesh(dir / "remesh.off", pair.remesh);
  write_mesh(dir / "source.off", pair.source);
  MeshJobOptions c = job_config(JobKind::Remesh, dir, "remesh.off");
  c.input.reference = dir / "source.off";
  c.massage.samples = samples;
  return run_mesh_job(plan_mesh_job(c));
}

}  // namespace

// The sphere with the default samples (N's vertices). The coarse torus needs samples on N's edges
// too: its saddle-shaped inner side puts M's chords on both sides of N, and with vertex samples
// the Hausdorff distance drops by 35% only.
TEST_CASE("remesh: a sphere's and a torus's remesh lose at least 40% of their Hausdorff distance") {
  for (const auto& [name, pair, samples] :
       {std::tuple{"sphere", test::sphere_remesh_pair(), SampleKind::Vertices},
        std::tuple{"torus", test::torus_remesh_pair(), SampleKind::Edges}}) {
    INFO(name);
    test::TempDir dir(std::string("remesh_") + name);
    const MeshJobResult r = remesh(pair, dir.path(), samples);
    REQUIRE(r.ok());
    REQUIRE(r.after);
    // Vertices on the source: M -> N is small at the vertices, N -> M large (the chords).
    CHECK(r.before.from_reference.max > r.before.to_reference.max);
    CHECK(r.before.hausdorff > 0.0);
    CHECK(r.after->hausdorff <= 0.6 * r.before.hausdorff);
    CHECK(r.massage.folded_triangles == 0);
    // The output is what measures.csv describes.
    const TriMesh out = read_mesh(dir / "out/remesh.off");
    CHECK(out.F == pair.remesh.F);
    CHECK((out.V - r.V).cwiseAbs().maxCoeff() == 0.0);
  }
}

TEST_CASE("smooth: a box's irregular triangles even out, its faces and sharp edges stay") {
  const test::Box box;
  const TriMesh mesh = test::jittered_box(box, 8, 0.3, 7);
  test::TempDir dir("smooth_box");
  write_mesh(dir / "box.obj", mesh);
  const MeshJobOptions c = job_config(JobKind::Smooth, dir.path(), "box.obj");
  const MeshJobResult r = run_mesh_job(plan_mesh_job(c));
  REQUIRE(r.ok());
  REQUIRE(r.after);
  CHECK(r.after->radius_ratio.min > r.before.radius_ratio.min);
  CHECK(r.after->radius_ratio.mean > r.before.radius_ratio.mean);
  // Every vertex stays within 1% of the box's diagonal of its faces.
  double worst = 0.0;
  for (int i = 0; i < r.V.rows(); ++i)
    worst = std::max(worst, box.distance(r.V.row(i).transpose()));
  CHECK(worst <= 0.01 * box.diagonal());
  // The box's 12 edges (8 segments each) stay sharp and in place.
  CHECK(r.before.features.edges == 96);
  CHECK(r.after->features.distance.max <= 0.01 * box.diagonal());
  REQUIRE(r.after->features.flattened);
  CHECK(*r.after->features.flattened == 0);
}

TEST_CASE("pinned vertices do not move: a list, and the boundary of an open mesh") {
  // An open, bumpy grid with jittered vertices: smoothing moves every free vertex.
  TriMesh grid = make_grid(12, 10, 1.2, 1.0);
  test::Jitter jitter(3);
  for (int i = 0; i < grid.num_vertices(); ++i) {
    grid.V(i, 0) += 0.03 * jitter();
    grid.V(i, 1) += 0.03 * jitter();
    grid.V(i, 2) = 0.1 * std::sin(3 * grid.V(i, 0)) * std::cos(2 * grid.V(i, 1));
  }
  test::TempDir dir("pinned");
  write_mesh(dir / "grid.obj", grid);
  for (JobKind job : {JobKind::Smooth, JobKind::Crossparam, JobKind::Remesh}) {
    INFO(job_name(job));
    MeshJobOptions c = job_config(job, dir.path(), "grid.obj");
    if (job == JobKind::Crossparam) {
      TriMesh templ = make_grid(12, 10, 1.2, 1.0);
      write_mesh(dir / "template.obj", templ);
      c.templ.mesh = dir / "template.obj";
    }
    if (job == JobKind::Remesh) {
      write_mesh(dir / "source.off", make_grid(30, 25, 1.2, 1.0));
      c.input.reference = dir / "source.off";
    }
    c.massage.pinned = {20, 33, 47};
    c.massage.pin_boundary = true;
    const MeshJobPlan plan = plan_mesh_job(c);
    const Topology& topo = plan.massager->topology();
    int boundary = 0;
    for (uint8_t b : topo.is_boundary_vertex) boundary += b;
    CHECK(plan.pinned_vertices == boundary + 3);
    const MeshJobResult r = run_mesh_job(plan);
    REQUIRE(r.ok());
    const TriMesh written = read_obj(dir / "out/grid.obj").mesh;
    int moved = 0;
    for (int i = 0; i < grid.num_vertices(); ++i) {
      const bool pinned = topo.is_boundary_vertex[i] || i == 20 || i == 33 || i == 47;
      if (pinned) {
        CHECK(r.V.row(i) == grid.V.row(i));  // bit for bit
        CHECK(written.V.row(i) == grid.V.row(i));
      } else {
        moved += (r.V.row(i) - grid.V.row(i)).norm() > 1e-6;
      }
    }
    CHECK(moved > grid.num_vertices() / 3);
  }
}

TEST_CASE("crossparam: the target takes the template's triangle shapes on its own surface") {
  const test::CrossparamPair pair = test::crossparam_pair();
  test::TempDir dir("crossparam");
  write_mesh(dir / "target.obj", pair.target);
  write_mesh(dir / "template.obj", pair.templ);
  MeshJobOptions c = job_config(JobKind::Crossparam, dir.path(), "target.obj");
  c.templ.mesh = dir / "template.obj";
  c.output.per_triangle_csv = true;
  const MeshJobResult r = run_mesh_job(plan_mesh_job(c));
  REQUIRE(r.ok());
  REQUIRE(r.before.shear);
  REQUIRE(r.after->shear);
  CHECK(r.after->shear->summary.mean < 0.8 * r.before.shear->summary.mean);
  CHECK(r.after->shear->summary.max < r.before.shear->summary.max);
  CHECK(r.after->hausdorff_rel < 0.01);  // still on the target's surface
  // The histogram moves towards small values (the paper's Figure 7).
  int low_before = 0, low_after = 0;
  for (int i = 0; i < 4; ++i) {
    low_before += r.before.shear->counts[i];
    low_after += r.after->shear->counts[i];
  }
  CHECK(low_after > low_before);
  const std::string triangles = read_file(dir / "out/triangles.csv");
  CHECK(triangles.rfind(
            "triangle,radius_ratio_before,radius_ratio_after,shear_before,shear_after\n", 0) == 0);
}

TEST_CASE("outputs: the input's name and format, measures.csv and report.json") {
  test::TempDir dir("mesh_job_outputs");
  const test::Box box;
  const TriMesh mesh = test::jittered_box(box, 4, 0.3, 1);
  // An OBJ with texture coordinates, a group and a comment: all kept, only v lines change.
  std::string obj = "# a box\no box\n";
  for (int i = 0; i < mesh.num_vertices(); ++i)
    obj += "v " + std::to_string(mesh.V(i, 0)) + " " + std::to_string(mesh.V(i, 1)) + " " +
           std::to_string(mesh.V(i, 2)) + "\n";
  for (int i = 0; i < mesh.num_vertices(); ++i) obj += "vt 0.5 0.25\n";
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    obj += "f";
    for (int k = 0; k < 3; ++k)
      obj += " " + std::to_string(mesh.F(t, k) + 1) + "/" + std::to_string(mesh.F(t, k) + 1);
    obj += "\n";
  }
  write_file_atomic(dir / "box.obj", obj);
  MeshJobOptions c = job_config(JobKind::Smooth, dir.path(), "box.obj");
  c.massage.iterations = 5;
  const MeshJobPlan plan = plan_mesh_job(c);
  CHECK(plan.output_mesh == dir / "out/box.obj");
  CHECK_THAT(describe_mesh_plan(plan), Contains("job: smooth"));
  CHECK_THAT(describe_mesh_plan(plan), Contains("uniform weights, 5 iterations"));
  CHECK_FALSE(fs::exists(dir / "out"));  // planning writes nothing
  const MeshJobResult r = run_mesh_job(plan);
  REQUIRE(r.ok());
  const std::string written = read_file(dir / "out/box.obj");
  CHECK(written.rfind("# a box\no box\n", 0) == 0);
  CHECK_THAT(written, Contains("vt 0.5 0.25\n"));
  CHECK_THAT(written, Contains("f 1/1 "));
  const ObjFile back = parse_obj(written, "box.obj");
  CHECK((back.mesh.V - r.V).cwiseAbs().maxCoeff() == 0.0);

  const std::string csv = read_file(dir / "out/measures.csv");
  std::string header = csv.substr(0, csv.find('\n'));
  std::string expected;
  for (const std::string& col : measure_columns(c.measures))
    expected += (expected.empty() ? "" : ",") + col;
  CHECK(header == expected);
  CHECK_THAT(csv, Contains("\nbefore,box.obj,box.obj as loaded,"));
  CHECK_THAT(csv, Contains("\nafter,box.obj,box.obj as loaded,"));

  const nlohmann::json report = nlohmann::json::parse(read_file(dir / "out/report.json"));
  CHECK(report["config"]["job"] == "smooth");
  CHECK(report["inputs"]["mesh"]["vertices"] == mesh.num_vertices());
  CHECK(report["massage"]["ok"] == true);
  CHECK(report["massage"]["iterations"].size() == 5);
  CHECK(report["measures"]["after"]["radius_ratio"]["min"].get<double>() ==
        r.after->radius_ratio.min);
  CHECK(report["outputs"]["mesh"] == "box.obj");
  CHECK_FALSE(report.contains("run"));  // timings off
  CHECK(report.contains("versions"));

  // Other formats on request: OFF and PLY from an OBJ, OBJ from an OFF.
  for (auto [format, name] :
       {std::pair{MeshOutputFormat::Off, "box.off"}, std::pair{MeshOutputFormat::Ply, "box.ply"}}) {
    MeshJobOptions other = c;
    other.output.format = format;
    other.output.dir = dir / "out_other";
    const MeshJobResult o = run_mesh_job(plan_mesh_job(other));
    const TriMesh back_other = read_mesh(dir / "out_other" / name);
    CHECK(back_other.F == mesh.F);
    CHECK((back_other.V - o.V).cwiseAbs().maxCoeff() == 0.0);
  }
  write_mesh(dir / "plain.off", mesh);
  MeshJobOptions from_off = job_config(JobKind::Smooth, dir.path(), "plain.off");
  from_off.output.format = MeshOutputFormat::Obj;
  from_off.massage.iterations = 3;
  CHECK(plan_mesh_job(from_off).output_mesh == dir / "out/plain.obj");
  from_off.output.format = MeshOutputFormat::Same;
  CHECK(plan_mesh_job(from_off).output_mesh == dir / "out/plain.off");
}

TEST_CASE("the same job gives the same bytes with 1 or 2 threads") {
  const test::RemeshPair pair = test::sphere_remesh_pair();
  test::TempDir dir("mesh_job_threads");
  write_mesh(dir / "remesh.off", pair.remesh);
  write_mesh(dir / "source.off", pair.source);
  std::string bytes[2][3];
  for (int threads : {1, 2}) {
    MeshJobOptions c = job_config(JobKind::Remesh, dir.path(), "remesh.off");
    c.input.reference = dir / "source.off";
    c.threads = threads;
    c.output.dir = dir / ("out" + std::to_string(threads));
    run_mesh_job(plan_mesh_job(c));
    bytes[threads - 1][0] = read_file(c.output.dir / "remesh.off");
    bytes[threads - 1][1] = read_file(c.output.dir / "measures.csv");
    bytes[threads - 1][2] = read_file(c.output.dir / "report.json");
  }
  CHECK(bytes[0][0] == bytes[1][0]);
  CHECK(bytes[0][1] == bytes[1][1]);
  // report.json differs only in the resolved config's "threads" and output folder.
  nlohmann::json a = nlohmann::json::parse(bytes[0][2]), b = nlohmann::json::parse(bytes[1][2]);
  for (nlohmann::json* j : {&a, &b}) {
    j->erase("config");
    (*j)["outputs"].erase("dir");
  }
  CHECK(a == b);
}

TEST_CASE("bad inputs are refused before anything is written, naming the file") {
  test::TempDir dir("mesh_job_errors");
  const TriMesh sphere = make_icosphere(2, 1.0);
  write_mesh(dir / "target.obj", sphere);
  write_mesh(dir / "other.obj", make_icosphere(1, 1.0));
  MeshJobOptions c = job_config(JobKind::Crossparam, dir.path(), "target.obj");
  c.templ.mesh = dir / "other.obj";
  CHECK(error_of([&] { plan_mesh_job(c); }) ==
        "template (other.obj): 42 vertices, but the mesh (target.obj) has 162 (crossparam needs "
        "the same connectivity)");
  TriMesh flipped = sphere;
  flipped.F.row(5) = Eigen::RowVector3i(sphere.F(5, 1), sphere.F(5, 0), sphere.F(5, 2));
  write_mesh(dir / "flipped.obj", flipped);
  c.templ.mesh = dir / "flipped.obj";
  CHECK_THAT(error_of([&] { plan_mesh_job(c); }),
             Contains("template (flipped.obj): triangle 6 has vertices"));

  MeshJobOptions s = job_config(JobKind::Smooth, dir.path(), "target.obj");
  s.massage.pinned = {500};
  CHECK(error_of([&] { plan_mesh_job(s); }) ==
        "massage.pinned: vertex 500 is out of range (the mesh has 162 vertices)");
  s.massage.pinned.clear();
  s.output.dir = dir.path();  // out/target.obj would be the input itself
  CHECK_THAT(error_of([&] { plan_mesh_job(s); }), Contains("would overwrite an input file"));

  MeshJobOptions missing = job_config(JobKind::Smooth, dir.path(), "nothing.obj");
  CHECK_THROWS_AS(plan_mesh_job(missing), IoError);
  write_file_atomic(dir / "broken.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n");
  MeshJobOptions broken = job_config(JobKind::Smooth, dir.path(), "broken.off");
  CHECK_THAT(error_of([&] { plan_mesh_job(broken); }), Contains("broken.off"));
  MeshJobOptions stl = job_config(JobKind::Smooth, dir.path(), "mesh.stl");
  write_file_atomic(dir / "mesh.stl", "solid x\n");
  CHECK_THAT(error_of([&] { plan_mesh_job(stl); }), Contains("unknown mesh file extension"));

  MeshJobOptions far = job_config(JobKind::Remesh, dir.path(), "target.obj");
  TriMesh moved = sphere;
  moved.V.col(0).array() += 5.0;
  write_mesh(dir / "moved.obj", moved);
  far.input.reference = dir / "moved.obj";
  const MeshJobPlan plan = plan_mesh_job(far);
  REQUIRE(plan.warnings.size() == 1);
  CHECK_THAT(plan.warnings[0], Contains("the closest-point correspondences assume"));
  CHECK_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("a mesh job writes report.html with its mesh before and after") {
  const test::Box box;
  const TriMesh mesh = test::jittered_box(box, 4, 0.3, 7);
  test::TempDir dir("mesh_html");
  write_mesh(dir / "box.obj", mesh);
  MeshJobOptions c = job_config(JobKind::Smooth, dir.path(), "box.obj");
  const MeshJobResult r = run_mesh_job(plan_mesh_job(c));
  REQUIRE(r.ok());
  const std::string page = read_file(dir / "out/report.html");
  const std::string open = "id=\"sm-data\">";
  const size_t at = page.find(open) + open.size();
  const nlohmann::json data = nlohmann::json::parse(page.substr(at, page.find("</script>", at) - at));
  CHECK(data["kind"] == "mesh");
  CHECK(data["summary_csv"] == read_file(dir / "out/measures.csv"));
  if (!test::player_in_build(data)) return;
  REQUIRE(data["player"].is_object());
  CHECK(data["player"]["vertices"] == mesh.num_vertices());
  CHECK(data["player"]["triangles"] == mesh.num_triangles());
  CHECK(data["player"]["colour"] == "shear");
  // The histogram counts every triangle once per side.
  const std::vector<long long> before = data["histogram"]["before"];
  long long total = 0;
  for (long long n : before) total += n;
  CHECK(total == mesh.num_triangles());

  c.output.html = false;
  c.output.dir = dir / "off";
  run_mesh_job(plan_mesh_job(c));
  CHECK_FALSE(fs::exists(dir / "off/report.html"));
}
