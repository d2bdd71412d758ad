// The seqmassage command line for the single-mesh jobs (remesh, crossparam, smooth) and the
// measure command, run as a subprocess on meshes generated in code: outputs, printed report, bad
// configs and arguments with their messages and exit codes.
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "io/mesh_file.hpp"
#include "mesh/primitives.hpp"
#include "support/cli_process.hpp"
#include "support/job_meshes.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

// A folder with a remesh pair (sphere), a box to smooth and a config per job.
struct Fixture {
  test::TempDir dir;
  explicit Fixture(const std::string& name) : dir(name) {
    const test::RemeshPair pair = test::sphere_remesh_pair();
    write_mesh(dir / "remesh.off", pair.remesh);
    write_mesh(dir / "source.off", pair.source);
    write_mesh(dir / "box.obj", test::jittered_box(test::Box{}, 6, 0.3, 2));
    write_file_atomic(dir / "remesh.json", R"({ "job": "remesh",
      "input": { "mesh": "remesh.off", "reference": "source.off" },
      "output": { "dir": "out_remesh", "timings": false } })");
    write_file_atomic(dir / "smooth.json", R"({ "job": "smooth", "input": { "mesh": "box.obj" },
      "output": { "dir": "out_smooth", "format": "ply" }, "massage": { "iterations": 10 } })");
  }
};

}  // namespace

TEST_CASE("seqmassage runs a remesh config: outputs, the printed report, exit 0") {
  Fixture f("cli_remesh");
  const test::CliRun r = test::run_cli(f.dir.path(), "remesh.json");
  INFO(r.err);
  REQUIRE(r.code == 0);
  for (const char* text :
       {"M = remesh.off (162 vertices, 320 triangles)", "N = source.off", "M -> N\n  before",
        "N -> M\n", "Hausdorff distance\n", "% vs before)", "radius ratio 2r/R of N",
        "results: out_remesh/ (remesh.off, measures.csv, report.json, report.html)"})
    CHECK_THAT(r.out, Contains(text));
  CHECK_THAT(r.err, Contains("seqmassage: remesh remesh.off (162 vertices), 15 iterations"));
  CHECK(fs::exists(f.dir / "out_remesh/remesh.off"));
  CHECK(fs::exists(f.dir / "out_remesh/measures.csv"));
  CHECK(fs::exists(f.dir / "out_remesh/report.json"));

  // -q prints nothing on success; --dry-run writes nothing.
  const test::CliRun quiet = test::run_cli(f.dir.path(), "-q remesh.json");
  CHECK(quiet.code == 0);
  CHECK(quiet.out.empty());
  CHECK(quiet.err.empty());
  fs::remove_all(f.dir / "out_remesh");
  const test::CliRun dry = test::run_cli(f.dir.path(), "--dry-run remesh.json");
  CHECK(dry.code == 0);
  CHECK_THAT(dry.out, Contains("job: remesh\nmesh (M): "));
  CHECK_THAT(dry.out, Contains("dry run: nothing written"));
  CHECK_FALSE(fs::exists(f.dir / "out_remesh"));
}

TEST_CASE("seqmassage runs a smooth config with another output format") {
  Fixture f("cli_smooth");
  const test::CliRun r = test::run_cli(f.dir.path(), "--threads 1 smooth.json");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(fs::exists(f.dir / "out_smooth/box.ply"));
  CHECK(read_mesh(f.dir / "out_smooth/box.ply").num_vertices() ==
        read_mesh(f.dir / "box.obj").num_vertices());
  CHECK_THAT(r.out, Contains("radius ratio 2r/R of M\n  before"));
  CHECK_THAT(r.out, Contains("feature edges of N (dihedral angle above 30 degrees): 72"));
}

TEST_CASE("bad single-mesh configs and options name the key, exit 2, write nothing") {
  Fixture f("cli_mesh_errors");
  auto config = [&](const std::string& text) {
    write_file_atomic(f.dir / "bad.json", text);
    return test::run_cli(f.dir.path(), "bad.json");
  };
  test::CliRun r =
      config(R"({"job": "remesh", "input": {"mesh": "remesh.off", "refrence": "source.off"},
                     "output": {"dir": "o"}})");
  CHECK(r.code == 2);
  CHECK(r.err ==
        "seqmassage: bad.json: input.refrence: unknown key (did you mean \"reference\"?)\n");
  r = config(R"({"job": "smooth", "input": {"mesh": "box.obj"}, "output": {"dir": "o"},
                 "massage": {"weights": "cotan"}})");
  CHECK(r.code == 2);
  CHECK_THAT(r.err,
             Contains("massage.weights: expected \"mean_value\" or \"uniform\", got \"cotan\""));
  r = config(R"({"job": "smooth", "input": {"mesh": "box.obj"}, "output": {"dir": "."}})");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("output.dir: writing"));
  CHECK_THAT(r.err, Contains("would overwrite an input file"));
  r = test::run_cli(f.dir.path(), "--frames 0:2 smooth.json");
  CHECK(r.code == 2);
  CHECK(r.err == "seqmassage: --frames: only for \"job\": \"sequence\" (this is a smooth job)\n");
  r = config(R"({"job": "smooth", "input": {"mesh": "missing.obj"}, "output": {"dir": "o"}})");
  CHECK(r.code == 4);
  CHECK_THAT(r.err, Contains("missing.obj"));
  write_file_atomic(f.dir / "bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\nx 1 0\n3 0 1 2\n");
  r = config(R"({"job": "smooth", "input": {"mesh": "bad.off"}, "output": {"dir": "o"}})");
  CHECK(r.code == 3);
  CHECK_THAT(r.err, Contains("bad.off"));
  CHECK_FALSE(fs::exists(f.dir / "o"));
}

TEST_CASE("seqmassage measure A B prints the report; --csv and --json write it") {
  Fixture f("cli_measure");
  const test::CliRun r =
      test::run_cli(f.dir.path(), "measure remesh.off source.off --csv m.csv --json m.json");
  INFO(r.err);
  REQUIRE(r.code == 0);
  for (const char* text :
       {"M = remesh.off (162 vertices, 320 triangles)",
        "N = source.off (2562 vertices, 5120 triangles)", "M -> N  ", "N -> M  ",
        "Hausdorff distance  ", "radius ratio 2r/R of M  ", "radius ratio 2r/R of N  ",
        "feature edges of N (dihedral angle above 30 degrees): 0"})
    CHECK_THAT(r.out, Contains(text));
  CHECK_THAT(r.out, !Contains("shear"));  // other connectivity, no --template
  const std::string csv = read_file(f.dir / "m.csv");
  CHECK(csv.rfind("stage,mesh,reference,vertices,triangles,dist_mesh_to_ref_max,", 0) == 0);
  CHECK_THAT(csv, Contains("\nmeasure,remesh.off,source.off,162,320,"));
  const nlohmann::json j = nlohmann::json::parse(read_file(f.dir / "m.json"));
  CHECK(j["measures"]["hausdorff"].get<double>() > 0.0);
  CHECK(j["template"].is_null());

  // Same connectivity: shear against the reference, dihedral changes.
  const test::CliRun same =
      test::run_cli(f.dir.path(), "measure box.obj box.obj --feature-angle 45");
  REQUIRE(same.code == 0);
  CHECK_THAT(same.out, Contains("T = N (it has M's connectivity)"));
  CHECK_THAT(same.out, Contains("shear against T (eq. 8)"));
  CHECK_THAT(same.out, Contains("dihedral change (degrees)"));
  CHECK_THAT(same.out, Contains("(dihedral angle above 45 degrees): 72"));
  const test::CliRun templ =
      test::run_cli(f.dir.path(), "measure remesh.off source.off --template box.obj");
  CHECK(templ.code == 3);
  CHECK_THAT(templ.err, Contains("--template needs the connectivity of remesh.off"));

  const test::CliRun help = test::run_cli(f.dir.path(), "measure --help");
  CHECK(help.code == 0);
  CHECK_THAT(help.out, Contains("Usage: seqmassage measure [options] MESH REFERENCE"));
  CHECK(test::run_cli(f.dir.path(), "measure remesh.off").code == 2);
  CHECK(test::run_cli(f.dir.path(), "measure a b c").code == 2);
  const test::CliRun bad_option =
      test::run_cli(f.dir.path(), "measure --spacing 0 remesh.off source.off");
  CHECK(bad_option.code == 2);
  CHECK_THAT(bad_option.err, Contains("--spacing: expected a number > 0, got \"0\""));
  const test::CliRun missing = test::run_cli(f.dir.path(), "measure remesh.off nothing.off");
  CHECK(missing.code == 4);
  CHECK_THAT(missing.err, Contains("nothing.off"));
  const test::CliRun overwrite =
      test::run_cli(f.dir.path(), "measure remesh.off source.off --csv source.off");
  CHECK(overwrite.code == 2);
  CHECK_THAT(overwrite.err, Contains("--csv: source.off is an input file"));
}

TEST_CASE("--help lists the jobs and the measure command") {
  test::TempDir dir("cli_mesh_help");
  const test::CliRun help = test::run_cli(dir.path(), "--help");
  CHECK(help.code == 0);
  for (const char* text : {"seqmassage measure [options] MESH REFERENCE", "remesh ", "crossparam ",
                           "smooth ", "measures.csv"})
    CHECK_THAT(help.out, Contains(text));
}
