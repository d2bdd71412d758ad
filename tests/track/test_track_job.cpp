// The track job end to end on untracked sequences generated in code (tests/support/
// untracked_sequence.hpp): a folder of raw frames (OBJ, PLY, OFF), each frame a new random
// triangulation of an analytic deforming surface; the truth of a template vertex is the surface
// point of its parameters. Errors are in mean edge lengths of the template.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

#include "config/config.hpp"
#include "io/atomic_file.hpp"
#include "io/gltf/gltf_file.hpp"
#include "io/gltf/gltf_load.hpp"
#include "io/mesh_file.hpp"
#include "io/obj.hpp"
#include "core/errors.hpp"
#include "pipeline/track/track_job.hpp"
#include "pipeline/track/track_merge.hpp"
#include "support/error_of.hpp"
#include "support/temp_dir.hpp"
#include "support/untracked_sequence.hpp"

using namespace sm;
using namespace sm::test;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr double kCell = 0.3;

std::string frame_name(int k, const char* ext) {
  char name[32];
  std::snprintf(name, sizeof name, "take_%04d.%s", k, ext);
  return name;
}

// The template frame as an OBJ with texture coordinates (the surface parameters, scaled) and a
// material: what the outputs must keep.
void write_textured_obj(const fs::path& file, const SampledFrame& f, const Surface& s) {
  std::ostringstream out;
  out << "mtllib skin.mtl\no subject\n";
  for (int i = 0; i < f.mesh.num_vertices(); ++i)
    out << "v " << f.mesh.V(i, 0) << " " << f.mesh.V(i, 1) << " " << f.mesh.V(i, 2) << "\n";
  for (const Eigen::Vector2d& p : f.params)
    out << "vt " << p[0] / s.u_length << " " << p[1] / s.v_length << "\n";
  out << "usemtl skin\n";
  for (int t = 0; t < f.mesh.num_triangles(); ++t) {
    out << "f";
    for (int c = 0; c < 3; ++c) out << " " << f.mesh.F(t, c) + 1 << "/" << f.mesh.F(t, c) + 1;
    out << "\n";
  }
  std::ofstream(file) << out.str();
}

struct Capture {
  Surface surface;
  SampledFrame templ;  // frame 0 as captured
  int frames = 0;
};

// Frames 0..frames-1 of `s` into `dir`: frame 0 a textured OBJ, the others OBJ, PLY and OFF in
// turn, each its own triangulation; `change` may alter a frame's raw mesh.
Capture write_capture(const fs::path& dir, const Surface& s, int frames, unsigned seed,
                      const std::function<void(int, TriMesh&)>& change = {}) {
  fs::create_directories(dir);
  Capture c{s, sample_surface(s, 0.0, kCell, seed), frames};
  write_textured_obj(dir / frame_name(0, "obj"), c.templ, s);
  const char* ext[] = {"obj", "ply", "off"};
  for (int k = 1; k < frames; ++k) {
    SampledFrame raw = sample_surface(s, k, kCell * 0.93, seed * 7919u + k);
    if (change) change(k, raw.mesh);
    write_mesh(dir / frame_name(k, ext[k % 3]), raw.mesh);
  }
  return c;
}

TrackJobOptions job(const fs::path& frames, const fs::path& out, const std::string& extra = "") {
  const std::string text = R"({"job": "track", "input": {"frames": ")" + frames.string() +
                           R"("}, "output": {"dir": ")" + out.string() +
                           R"(", "timings": false, "html": false})" + extra + "}";
  return parse_track_config(json::parse(text), frames);
}

// Mean distance of the output frame's vertices to their truth.
double truth_error(const Positions& V, const Capture& c, int k, double h) {
  double total = 0;
  for (int i = 0; i < V.rows(); ++i)
    total += (V.row(i).transpose() -
              c.surface.at(c.templ.params[size_t(i)][0], c.templ.params[size_t(i)][1], k))
                 .norm();
  return total / V.rows() / h;
}

// summary.csv's rows as column → text.
std::vector<std::map<std::string, std::string>> read_summary(const fs::path& file) {
  std::istringstream in(read_file(file));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> columns;
  std::stringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');) columns.push_back(cell);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::map<std::string, std::string> row;
    std::stringstream cells(line);
    size_t k = 0;
    for (std::string cell; std::getline(cells, cell, ',') && k < columns.size(); ++k)
      row[columns[k]] = cell;
    rows.push_back(row);
  }
  return rows;
}

std::map<std::string, std::string> files_below(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out[fs::relative(e.path(), dir).string()] = read_file(e.path());
  return out;
}

}  // namespace

TEST_CASE("track job: the template's connectivity and texture on every frame, near the truth",
          "[track][job]") {
  TempDir dir("track_job");
  const Capture c = write_capture(dir / "raw", bending_limb(/*speed=*/0.5, /*turn=*/0.02), 8, 5);
  const TrackPlan plan = plan_track_job(job(dir / "raw", dir / "out"));
  CHECK(plan.selected.size() == 8);
  CHECK(plan.template_frame == 0);
  const TrackResult result = run_track_job(plan);
  REQUIRE(result.frames.size() == 8);
  CHECK(result.lost == 0);

  const ObjFile templ = read_obj(dir / "raw" / frame_name(0, "obj"));
  const double h = mean_edge_length(templ.mesh);
  const auto rows = read_summary(dir / "out/summary.csv");
  REQUIRE(rows.size() == 8);
  for (int k = 0; k < 8; ++k) {
    INFO("frame " << k);
    const ObjFile out = read_obj(dir / "out/frames" / frame_name(k, "obj"));
    // The template's connectivity, texture coordinates and statements.
    CHECK(out.mesh.F == templ.mesh.F);
    CHECK(out.texcoords == templ.texcoords);
    REQUIRE(out.corners.size() == templ.corners.size());
    for (size_t i = 0; i < out.corners.size(); ++i) CHECK(out.corners[i].vt == templ.corners[i].vt);
    CHECK(out.text.find("usemtl skin") != std::string::npos);
    // Near the truth (the bound: the tracker's tests measure about 0.2 on this limb).
    const double e = truth_error(out.mesh.V, c, k, h);
    CHECK(e < 0.35);
    // summary.csv: the status and the figures both ways, small on the captured surface.
    CHECK(rows[size_t(k)].at("frame") == std::to_string(k));
    CHECK(rows[size_t(k)].at("status") == "ok");
    CHECK(std::stod(rows[size_t(k)].at("to_raw_mean")) < 0.06);
    CHECK(std::stod(rows[size_t(k)].at("from_raw_mean")) < 0.2);
    CHECK(std::stod(rows[size_t(k)].at("shear_mean")) >= 0.0);
  }
  // Frame 0 is the template itself: tracked onto its own surface, it barely moves.
  CHECK(truth_error(read_obj(dir / "out/frames" / frame_name(0, "obj")).mesh.V, c, 0, h) < 0.05);
  const json report = json::parse(read_file(dir / "out/report.json"));
  CHECK(report["job"] == "track");
  CHECK(report["lost"].empty());
  CHECK(report["tolerances"]["lost_distance"] == 0.2);
}

TEST_CASE("track job: a glitched frame is lost and listed, a jump is recovered",
          "[track][job]") {
  TempDir dir("track_job_lost");
  // Frame 3 is a capture glitch (every vertex thrown 6 units at random); from frame 5 on the
  // subject is 25 units away (a cut in the footage).
  const Surface limb = bending_limb(0.5, 0.02);
  Surface s = limb;
  s.at = [limb](double u, double v, double time) {
    const Vec3 p = limb.at(u, v, time);
    return time < 5 ? p : Vec3(p + Vec3(3.0, 25.0, -4.0));
  };
  std::mt19937 random(9);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Capture c = write_capture(dir / "raw", s, 8, 11, [&](int k, TriMesh& raw) {
    if (k == 3)
      for (int i = 0; i < raw.num_vertices(); ++i)
        raw.V.row(i) += 6.0 * Vec3(unit(random), unit(random), unit(random)).transpose();
  });
  const TrackResult result = run_track_job(plan_track_job(job(dir / "raw", dir / "out")));
  REQUIRE(result.frames.size() == 8);
  const auto rows = read_summary(dir / "out/summary.csv");
  CHECK(rows[3].at("status") == "lost");
  CHECK(rows[3].at("beyond").find("lost_distance") != std::string::npos);
  CHECK(rows[4].at("status") != "lost");      // back from the last good frame
  CHECK(rows[5].at("status") == "recovered");  // the jump
  CHECK(rows[7].at("status") == "ok");
  CHECK(result.lost == 1);
  const json report = json::parse(read_file(dir / "out/report.json"));
  REQUIRE(report["lost"].size() == 1);
  CHECK(report["lost"][0]["frame"] == 3);
  // The lost frame is written (its best attempt), the frames after it follow the truth.
  CHECK(fs::exists(dir / "out/frames" / frame_name(3, "obj")));
  const double h = mean_edge_length(c.templ.mesh);
  for (int k : {4, 5, 6, 7})
    CHECK(truth_error(read_obj(dir / "out/frames" / frame_name(k, "obj")).mesh.V, c, k, h) < 0.6);
}

TEST_CASE("track job: same bytes with 1 and 2 threads; a clean template mesh; PC2 output",
          "[track][job]") {
  TempDir dir("track_job_threads");
  const Surface s = rolling_sheet(/*speed=*/1.0, /*turn=*/0.03);
  write_capture(dir / "raw", s, 5, 7);
  // A clean template: another triangulation of frame 0's surface, as a PLY.
  write_mesh(dir / "clean.ply", sample_surface(s, 0.0, kCell * 1.1, 4242).mesh);
  std::map<std::string, std::string> outputs[2];
  for (int threads : {1, 2}) {
    const fs::path out = dir / ("out" + std::to_string(threads));
    TrackJobOptions c = job(dir / "raw", out,
                            R"(, "template": {"mesh": ")" + (dir / "clean.ply").string() +
                                R"("}, "threads": )" + std::to_string(threads));
    c.output.format = OutputFormat::Pc2;
    const TrackResult r = run_track_job(plan_track_job(c));
    CHECK(r.lost == 0);
    outputs[threads - 1] = files_below(out);
  }
  CHECK(outputs[0].count("sequence.pc2") == 1);
  CHECK(outputs[0].count("rest.obj") == 1);
  CHECK(outputs[0].count("summary.csv") == 1);
  REQUIRE(outputs[0].size() == outputs[1].size());
  for (const auto& [name, bytes] : outputs[0]) {
    INFO(name);
    if (name == "report.json") continue;  // holds the thread count and output folder
    CHECK(outputs[1].at(name) == bytes);
  }
  // The cache has the clean mesh's vertex count: 5 frames of it, float32 triples.
  const TriMesh clean = read_mesh(dir / "clean.ply");
  CHECK(outputs[0]["sequence.pc2"].size() == 32 + size_t(5) * clean.num_vertices() * 12);
}

TEST_CASE("track job: a template split along seams keeps its split vertices together",
          "[track][job]") {
  TempDir dir("track_job_seams");
  const Capture c = write_capture(dir / "raw", bending_limb(0.5, 0.02), 4, 13);
  // Frame 0's mesh written non-indexed (every triangle its own three vertices), as capture
  // software splits vertices along texture seams.
  const TriMesh& t = c.templ.mesh;
  TriMesh split{Positions(3 * t.num_triangles(), 3), Triangles(t.num_triangles(), 3)};
  std::vector<int> original(size_t(3 * t.num_triangles()));
  for (int f = 0; f < t.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      split.V.row(3 * f + k) = t.V.row(t.F(f, k));
      split.F(f, k) = 3 * f + k;
      original[size_t(3 * f + k)] = t.F(f, k);
    }
  write_mesh(dir / "split.ply", split);
  const TrackResult r = run_track_job(plan_track_job(
      job(dir / "raw", dir / "out", R"(, "template": {"mesh": ")" + (dir / "split.ply").string() +
                                        R"("})")));
  CHECK(r.lost == 0);
  const double h = mean_edge_length(t);
  for (int k = 0; k < 4; ++k) {
    INFO("frame " << k);
    const TriMesh out = read_mesh(dir / "out/frames" / frame_name(k, "obj"));
    REQUIRE(out.num_vertices() == split.num_vertices());
    CHECK(out.F == split.F);
    // Every copy of a vertex at the position of the vertex's first copy, near the truth.
    Positions welded(t.num_vertices(), 3);
    for (int i = 0; i < out.num_vertices(); ++i) welded.row(original[size_t(i)]) = out.V.row(i);
    for (int i = 0; i < out.num_vertices(); ++i)
      CHECK(out.V.row(i) == welded.row(original[size_t(i)]));
    CHECK(truth_error(welded, c, k, h) < 0.35);
  }
}

TEST_CASE("track job: bad input is refused with the file, frame and key", "[track][job]") {
  TempDir dir("track_job_errors");
  CHECK(error_of<IoError>([&] { plan_track_job(job(dir / "missing", dir / "out")); }) ==
        "input.frames: the folder '" + (dir / "missing").string() + "' does not exist");
  fs::create_directories(dir / "empty");
  std::ofstream(dir / "empty/notes.txt") << "not a frame\n";
  CHECK(error_of<InputError>([&] { plan_track_job(job(dir / "empty", dir / "out")); }) ==
        "input.frames: the folder '" + (dir / "empty").string() +
            "' holds no frame (no .obj, .ply or .off file)");

  write_capture(dir / "raw", bending_limb(0.5, 0.02), 3, 5);
  CHECK(error_of<ConfigError>([&] {
          plan_track_job(job(dir / "raw", dir / "out", R"(, "template": {"frame": 3})"));
        }) == "template.frame: 3 is out of range (the folder has 3 frames, 0 to 2)");
  CHECK(error_of<ConfigError>([&] {
          job(dir / "raw", dir / "out", R"(, "template": {"frame": 0, "mesh": "a.obj"})");
        }) == "template: give \"frame\" or \"mesh\", not both");
  CHECK(error_of<ConfigError>([&] { job(dir / "raw", dir / "out", R"(, "track": {"stages": 0})"); })
            .find("track.stages") == 0);
  CHECK(error_of<ConfigError>([&] {
          job(dir / "raw", dir / "out", R"(, "massage": {"iterations": 3})");
        }).find("massage.iterations: ") == 0);

  // A frame that cannot be parsed: named by its index and file when the run reaches it.
  const fs::path bad = dir / "raw" / frame_name(2, "off");
  std::ofstream(bad) << "OFF\n3 1 0\n0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n";
  const std::string message =
      error_of<InputError>([&] { run_track_job(plan_track_job(job(dir / "raw", dir / "out"))); });
  CHECK(message.find("frame 2 ('" + bad.string() + "')") == 0);
}

TEST_CASE("track job: GLB output, a morph target per frame on the template's vertices",
          "[track][job]") {
  TempDir dir("track_job_glb");
  write_capture(dir / "raw", bending_limb(0.5, 0.02), 4, 17);
  const TrackResult obj_run = run_track_job(plan_track_job(job(dir / "raw", dir / "obj")));
  TrackJobOptions glb_job = job(dir / "raw", dir / "glb");
  glb_job.output.format = OutputFormat::Gltf;
  glb_job.output.gltf.fps = 30;
  const TrackResult glb_run = run_track_job(plan_track_job(glb_job));
  CHECK(glb_run.lost == obj_run.lost);
  REQUIRE(fs::exists(dir / "glb/sequence.glb"));
  CHECK_FALSE(fs::exists(dir / "glb/frames"));

  GltfInputOptions input;
  input.file = dir / "glb/sequence.glb";
  const GltfSequence glb = load_gltf_sequence(input);
  REQUIRE(glb.num_frames() == 4);
  for (int k = 0; k < 4; ++k) CHECK(glb.times[size_t(k)] == Approx(k / 30.0));
  // The template's texture coordinates travel (one glTF vertex per v/vt pair), and its rest
  // pose is the template's: each glTF vertex is found among the template's vertices.
  const TriMesh t = read_mesh(dir / "raw" / frame_name(0, "obj"));
  CHECK(glb.gltf_vertices == t.num_vertices());
  CHECK(glb.rest.num_triangles() == t.num_triangles());
  const double h = mean_edge_length(t);
  std::vector<int> template_vertex(size_t(glb.gltf_vertices), -1);
  for (int g = 0; g < glb.gltf_vertices; ++g) {
    const Eigen::RowVector3d p = glb.rest.V.row(glb.weld_map[size_t(g)]);
    for (int i = 0; i < t.num_vertices(); ++i)
      if ((t.V.row(i) - p).norm() < 1e-4 * h) template_vertex[size_t(g)] = i;
    REQUIRE(template_vertex[size_t(g)] >= 0);
  }
  const GltfFile file = load_gltf_file(dir / "glb/sequence.glb");
  const auto& attributes = file.model.meshes.at(0).primitives.at(0).attributes;
  CHECK(attributes.count("TEXCOORD_0") == 1);
  CHECK(attributes.count("NORMAL") == 1);
  CHECK(file.model.meshes.at(0).primitives.at(0).targets.size() == 4);
  // Every frame plays the tracked positions the OBJ output writes (float32 precision).
  for (int k = 0; k < 4; ++k) {
    INFO("frame " << k);
    const TriMesh tracked = read_mesh(dir / "obj/frames" / frame_name(k, "obj"));
    const Positions played = evaluate_gltf_vertices(glb, glb.times[size_t(k)]);
    double worst = 0;
    for (int g = 0; g < glb.gltf_vertices; ++g)
      worst = std::max(worst, (played.row(g) - tracked.V.row(template_vertex[size_t(g)])).norm());
    CHECK(worst < 1e-4 * h);
  }
  // The frame rate is the track job's: a glTF input keeps its own times.
  CHECK(error_of<ConfigError>([&] {
          parse_config(json::parse(R"({"job": "sequence", "input": {"gltf": "a.glb"},
                                       "output": {"dir": "out", "format": "gltf",
                                                  "gltf": {"fps": 30}}})"),
                       dir.path());
        }).find("output.gltf.fps: ") == 0);
}

TEST_CASE("track job: shards tracked apart and merged, seams reported", "[track][job]") {
  TempDir dir("track_job_shards");
  write_capture(dir / "raw", rolling_sheet(/*speed=*/0.5, /*turn=*/0.02), 7, 29);
  const auto config = [&](const fs::path& out) {
    TrackJobOptions c = job(dir / "raw", out);
    c.output.format = OutputFormat::Pc2;
    return c;
  };
  const TrackResult whole = run_track_job(plan_track_job(config(dir / "whole")));
  REQUIRE(whole.frames.size() == 7);

  // Blocks of 7 frames in 3 shards: 0-1, 2-3, 4-6; the template frame 0 is in the first.
  for (int i = 0; i < 3; ++i) {
    TrackJobOptions c = config(dir / "sharded");
    c.shard = {i, 3};
    const TrackPlan plan = plan_track_job(c);
    CHECK(plan.block.front() == std::vector<int>{0, 2, 4}[size_t(i)]);
    CHECK(plan.order.front() == plan.block.front());  // forward from the block's first frame
    const TrackResult r = run_track_job(plan);
    CHECK(r.lost == 0);
    CHECK(fs::exists(dir / "sharded" / summary_file_name(c.shard)));
  }
  CHECK_FALSE(fs::exists(dir / "sharded/sequence.pc2"));
  CHECK_FALSE(fs::exists(dir / "sharded/summary.csv"));

  const TrackMergeResult merged = merge_track_shards(dir / "sharded");
  CHECK(merged.shards == 3);
  REQUIRE(merged.frames.size() == 7);
  REQUIRE(merged.seams.size() == 2);
  CHECK(merged.seams[0].frame == 2);
  CHECK(merged.seams[1].frame == 4);
  CHECK(merged.lost == 0);
  // The first block is tracked as the whole run tracks it: the same rows and positions.
  const auto rows = read_summary(dir / "sharded/summary.csv");
  const auto whole_rows = read_summary(dir / "whole/summary.csv");
  REQUIRE(rows.size() == 7);
  for (int k = 0; k < 2; ++k) CHECK(rows[size_t(k)] == whole_rows[size_t(k)]);
  const std::string cache = read_file(dir / "sharded/sequence.pc2");
  const std::string whole_cache = read_file(dir / "whole/sequence.pc2");
  REQUIRE(cache.size() == whole_cache.size());
  const size_t frame_bytes = (cache.size() - 32) / 7;
  CHECK(cache.substr(0, 32 + 2 * frame_bytes) == whole_cache.substr(0, 32 + 2 * frame_bytes));
  const json report = json::parse(read_file(dir / "sharded/report.json"));
  CHECK(report.at("merged").at("seams").size() == 2);
  CHECK(report.at("frames").size() == 7);

  // A shard missing, or run with another config: named, with the command that redoes it.
  fs::remove(dir / "sharded/report.shard-1-of-3.json");
  const std::string missing = error_of<InputError>([&] { merge_track_shards(dir / "sharded"); });
  INFO(missing);
  CHECK(missing.find("shard 1/3: no report.shard-1-of-3.json; missing frames 2 (take_0002.obj) to 3") !=
        std::string::npos);
  CHECK(missing.find("seqmassage --shard 1/3 CONFIG") != std::string::npos);
  TrackJobOptions odd = config(dir / "sharded");
  odd.shard = {1, 3};
  odd.track.lost_distance = 0.5;
  run_track_job(plan_track_job(odd));
  const std::string other = error_of<InputError>([&] { merge_track_shards(dir / "sharded"); });
  CHECK(other.find("report.shard-1-of-3.json ran another config: track.lost_distance") !=
        std::string::npos);
}
