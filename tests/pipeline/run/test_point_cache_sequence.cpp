// Point caches in a sequence job (issue 16.1): PC2 and MDD inputs on a mesh, PC2 and MDD outputs
// (sequence.pc2 / sequence.mdd and rest.obj) assembled from the frames' positions files, with
// round trips against the OBJ-folder run, shards + merge and resume giving the same bytes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/frame_folder.hpp"
#include "io/obj.hpp"
#include "io/point_cache.hpp"
#include "core/errors.hpp"
#include "pipeline/cluster/merge.hpp"
#include "pipeline/run/sequence_job.hpp"
#include "support/error_of.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using sm::test::error_of;

namespace {

SequenceResult run(const SequenceJobOptions& c, const RunHooks& hooks = {}) {
  return run_sequence_job(plan_sequence_job(c), hooks);
}

// A tube job whose OBJ frames hold float32 values only, so that a point cache of them holds the
// very same positions.
SequenceJobOptions float_tube_job(const fs::path& dir, int frames = 6) {
  SequenceJobOptions c = test::tube_job(dir, test::small_tube(frames));
  for (const fs::path& file : list_frames(c.input.frames))
    test::edit_obj_vertices(file, [](int, double& x, double& y, double& z) {
      x = float(x), y = float(y), z = float(z);
    });
  return c;
}

// The OBJ folder as a point cache, dir/take.<pc2|mdd>, and its first frame as the mesh.
PointCacheInput cache_of_folder(const fs::path& folder, const fs::path& dir,
                                PointCacheFormat format) {
  const std::vector<fs::path> files = list_frames(folder);
  const fs::path cache = dir / (format == PointCacheFormat::Pc2 ? "take.pc2" : "take.mdd");
  PointCacheTiming timing;
  for (size_t f = 0; f < files.size(); ++f) timing.times.push_back(float(f) / 24.0f);
  const int n = read_obj(files[0]).mesh.num_vertices();
  write_point_cache(cache, format, n, int(files.size()), timing,
                    [&](int f) { return read_obj(files[size_t(f)]).mesh.V; });
  fs::copy_file(files[0], dir / "rest.obj", fs::copy_options::overwrite_existing);
  return {format, cache, dir / "rest.obj"};
}

void use_cache(SequenceJobOptions& c, const PointCacheInput& cache) {
  c.input.frames.clear();
  if (cache.format == PointCacheFormat::Pc2)
    c.input.pc2 = Pc2InputOptions{cache.file, cache.mesh};
  else
    c.input.mdd = MddInputOptions{cache.file, cache.mesh};
}

// Every frame of a cache file.
std::vector<Positions> read_cache(const fs::path& file, PointCacheFormat format) {
  const PointCacheHeader h = read_point_cache_header(file, format);
  std::vector<Positions> frames;
  for (int f = 0; f < h.frames; ++f)
    frames.push_back(
        decode_point_cache_frame(read_point_cache_frame_bytes(file, h, f), h, f, file.string()));
  return frames;
}

// OBJ folder run -> cache of its input -> cache run: each output frame is the OBJ run's, rounded
// to float32. Returns the largest difference.
double round_trip(PointCacheFormat format, const std::string& name) {
  test::TempDir dir(name);
  SequenceJobOptions c = float_tube_job(dir.path());
  run(c);  // OBJ frames in, OBJ frames out
  const std::vector<fs::path> corrected = list_frames(dir / "out/frames");

  SequenceJobOptions p = c;
  use_cache(p, cache_of_folder(c.input.frames, dir.path(), format));
  p.output.dir = dir / "cache_out";
  p.output.format = format == PointCacheFormat::Pc2 ? OutputFormat::Pc2 : OutputFormat::Mdd;
  const SequenceResult r = run(p);
  CHECK(r.failed == 0);
  const fs::path out = p.output.dir / (format == PointCacheFormat::Pc2 ? "sequence.pc2"
                                                                        : "sequence.mdd");
  const std::vector<Positions> frames = read_cache(out, format);
  REQUIRE(frames.size() == corrected.size());
  double max_difference = 0;
  for (size_t f = 0; f < frames.size(); ++f) {
    const Positions V = read_obj(corrected[f]).mesh.V;
    const Positions rounded = V.cast<float>().cast<double>();
    CHECK(frames[f] == rounded);  // the same optimization, then float32 rounding
    max_difference = std::max(max_difference, (frames[f] - V).cwiseAbs().maxCoeff());
  }
  // rest.obj: the template (frame 0, unchanged), with the input's statements.
  CHECK(read_file(p.output.dir / "rest.obj") == read_file(list_frames(c.input.frames)[0]));
  return max_difference;
}

}  // namespace

TEST_CASE("OBJ folder -> PC2 -> seqmassage -> PC2 equals the OBJ run to float32 rounding") {
  const double d = round_trip(PointCacheFormat::Pc2, "pc2_trip");
  WARN("PC2 round trip: max |PC2 - OBJ run| = " << d);
  CHECK(d < 1e-6);  // positions of magnitude ~4: half a float32 ulp is 2.4e-7
}

TEST_CASE("OBJ folder -> MDD -> seqmassage -> MDD equals the OBJ run to float32 rounding") {
  const double d = round_trip(PointCacheFormat::Mdd, "mdd_trip");
  WARN("MDD round trip: max |MDD - OBJ run| = " << d);
  CHECK(d < 1e-6);
}

TEST_CASE("a PC2 input gives the OBJ frames the OBJ folder gives, and its report says so") {
  test::TempDir dir("pc2_obj_out");
  SequenceJobOptions c = float_tube_job(dir.path(), 4);
  run(c);
  SequenceJobOptions p = c;
  use_cache(p, cache_of_folder(c.input.frames, dir.path(), PointCacheFormat::Pc2));
  p.output.dir = dir / "pc2_out";
  const SequencePlan plan = plan_sequence_job(p);
  CHECK_THAT(describe_plan(plan), Contains("input: PC2 cache ") &&
                                      Contains("4 frames of 132 points (start frame 0, sample "
                                               "rate 1), on the triangles of "));
  run_sequence_job(plan);
  // The same positions, and rest.obj's statements (texture coordinates, faces) in every frame.
  const std::vector<fs::path> a = list_frames(dir / "out/frames"),
                              b = list_frames(dir / "pc2_out/frames");
  REQUIRE(a.size() == b.size());
  const ObjFile rest = read_obj(dir / "rest.obj");
  for (size_t f = 0; f < a.size(); ++f) {
    const ObjFile x = read_obj(a[f]), y = read_obj(b[f]);
    CHECK(x.mesh.V == y.mesh.V);
    CHECK(y.texcoords == rest.texcoords);
    CHECK(y.mesh.F == rest.mesh.F);
  }
  CHECK(read_file(b[0]) == read_file(dir / "rest.obj"));  // the template frame, unchanged
  const auto report = nlohmann::json::parse(read_file(dir / "pc2_out/report.json"));
  CHECK(report["input"]["kind"] == "pc2");
  CHECK(report["input"]["vertices"] == 132);
}

TEST_CASE("a PC2 job in shards, merged, writes the bytes of one run; so does a resumed one") {
  test::TempDir dir("pc2_shards");
  SequenceJobOptions c = float_tube_job(dir.path(), 7);
  c.frames_in_flight = 1;  // so that the interruption below stops after one frame
  use_cache(c, cache_of_folder(c.input.frames, dir.path(), PointCacheFormat::Pc2));
  c.templ.mesh = c.input.pc2->mesh;  // what a config gives by default: every frame optimized
  c.output.format = OutputFormat::Pc2;
  c.input.range = {1, std::nullopt, 2};  // frames 1, 3, 5: start frame 1, sample rate 2
  run(c);
  const fs::path cache = dir / "out/sequence.pc2";
  const PointCacheHeader h = read_point_cache_header(cache, PointCacheFormat::Pc2);
  CHECK(h.frames == 3);
  CHECK(h.start == 1.0f);
  CHECK(h.sample_rate == 2.0f);
  fs::rename(dir / "out", dir / "single");

  for (int i = 0; i < 3; ++i) {
    c.shard = {i, 3};
    run(c);
    CHECK_FALSE(fs::exists(cache));  // a shard writes positions only
  }
  const MergeResult m = merge_shards(c.output.dir);
  CHECK(m.written ==
        std::vector<std::string>{"summary.csv", "report.json", "sequence.pc2", "rest.obj"});
  const auto single = test::compare_folders(dir / "single", dir / "out", ".shard-");
  CHECK(single.count("sequence.pc2"));
  CHECK(single.count("rest.obj"));
  CHECK(single.at("rest.obj") == read_file(c.input.pc2->mesh));

  // Interrupted after a frame, then resumed: the same bytes again.
  fs::remove_all(dir / "out");
  c.shard = {};
  std::atomic<bool> cancel{false};
  RunHooks hooks;
  hooks.cancel = &cancel;
  hooks.progress = [&](const FrameSummary&, int done, int, double) { cancel = done >= 1; };
  const SequenceResult stopped = run(c, hooks);
  REQUIRE(stopped.interrupted);
  CHECK(read_point_cache_header(cache, PointCacheFormat::Pc2).frames ==
        int(stopped.frames.size()));  // the frames done, as for the GLB
  c.resume = true;
  const SequenceResult resumed = run(c);
  CHECK(resumed.resumed == int(stopped.frames.size()));
  test::compare_folders(dir / "single", dir / "out");
}

TEST_CASE("an MDD output keeps an MDD input's frame times; a failed frame is its input") {
  test::TempDir dir("mdd_times");
  SequenceJobOptions c = float_tube_job(dir.path(), 4);
  const fs::path frames_dir = c.input.frames;
  use_cache(c, cache_of_folder(c.input.frames, dir.path(), PointCacheFormat::Mdd));
  c.output.format = OutputFormat::Mdd;
  c.input.range = {1, std::nullopt, 1};
  c.massage.iterations = 1;
  // Below any count of folded triangles (the config's range starts at 0; built in code, it makes
  // every optimized frame fail): each is written as its input.
  c.checks.max_folded_triangles = -1;
  const SequenceResult r = run(c);
  CHECK(r.failed == 3);
  const PointCacheHeader h =
      read_point_cache_header(dir / "out/sequence.mdd", PointCacheFormat::Mdd);
  CHECK(h.times == std::vector<float>{1.0f / 24, 2.0f / 24, 3.0f / 24});
  const std::vector<Positions> frames =
      read_cache(dir / "out/sequence.mdd", PointCacheFormat::Mdd);
  const std::vector<fs::path> inputs = list_frames(frames_dir);
  for (int f = 0; f < 3; ++f) CHECK(frames[size_t(f)] == read_obj(inputs[size_t(f) + 1]).mesh.V);

  // An OBJ folder has no times: frame numbers / output.point_cache.fps.
  SequenceJobOptions o = float_tube_job(dir / "folder", 3);
  o.output.format = OutputFormat::Mdd;
  o.output.point_cache.fps = 10;
  run(o);
  CHECK(read_point_cache_header(o.output.dir / "sequence.mdd", PointCacheFormat::Mdd).times ==
        std::vector<float>{0.0f, 0.1f, 0.2f});
}

TEST_CASE("a point cache input is checked: vertex counts, non-finite positions") {
  test::TempDir dir("pc2_bad_input");
  SequenceJobOptions c = float_tube_job(dir.path(), 3);
  const PointCacheInput cache = cache_of_folder(c.input.frames, dir.path(), PointCacheFormat::Pc2);
  use_cache(c, cache);

  // A mesh with another vertex count: both files and counts named.
  write_file_atomic(dir / "small.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  SequenceJobOptions wrong = c;
  wrong.input.pc2->mesh = dir / "small.obj";
  CHECK(error_of<InputError>([&] { plan_sequence_job(wrong); }) ==
        "'" + cache.file.string() + "' has 132 points per frame, but its mesh '" +
            (dir / "small.obj").string() + "' has 3 vertices; the cache must be of that mesh");

  // A NaN in frame 2, vertex 7: refused when the job is planned, before anything is written.
  std::string bytes = read_file(cache.file);
  const float nan = std::nanf("");
  std::memcpy(&bytes[32 + 2 * 132 * 12 + 7 * 12], &nan, 4);
  write_file_atomic(cache.file, bytes);
  CHECK_THAT(error_of<InputError>([&] { plan_sequence_job(c); }),
             Contains("take.pc2': frame 2, vertex 7: non-finite position (nan, "));
  CHECK_FALSE(fs::exists(c.output.dir));
}

// Issue 24.4: the values of a point cache under the limits of every other reader.

namespace {

// Column `name` of every row of a CSV file without quoted fields.
std::vector<std::string> csv_column(const fs::path& file, const std::string& name) {
  std::istringstream in(read_file(file));
  std::string line;
  const auto split = [](const std::string& text) {
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream row(text);
    while (std::getline(row, cell, ',')) cells.push_back(cell);
    if (!text.empty() && text.back() == ',') cells.push_back("");
    return cells;
  };
  std::getline(in, line);
  const std::vector<std::string> header = split(line);
  const size_t at = size_t(std::find(header.begin(), header.end(), name) - header.begin());
  REQUIRE(at < header.size());
  std::vector<std::string> out;
  while (std::getline(in, line)) out.push_back(split(line).at(at));
  return out;
}

}  // namespace

TEST_CASE("a PC2 input beyond the readers' limits is refused at planning, nothing written") {
  test::TempDir dir("pc2_limits");
  SequenceJobOptions c = float_tube_job(dir.path(), 3);
  const PointCacheInput cache = cache_of_folder(c.input.frames, dir.path(), PointCacheFormat::Pc2);
  use_cache(c, cache);
  c.output.format = OutputFormat::Pc2;
  const std::string good = read_file(cache.file);
  const std::string name = "'" + cache.file.string() + "'";
  const auto refused = [&](size_t at, float value) {
    std::string bytes = good;
    std::memcpy(&bytes[at], &value, 4);
    write_file_atomic(cache.file, bytes);
    const std::string message = error_of<InputError>([&] { plan_sequence_job(c); });
    CHECK_FALSE(fs::exists(c.output.dir));
    return message;
  };
  // A coordinate of 1e30 (frame 1, vertex 5, z): the OBJ, PLY, OFF and glTF readers' limit.
  CHECK(refused(32 + 132 * 12 + 5 * 12 + 8, 1e30f) ==
        name + ": frame 1, vertex 5: coordinate z 1.00000002e+30 is too large (more than 1e18 in "
               "magnitude: the geometry would overflow)");
  // A start frame or sample rate of 3e38: finite, but the output's start + rate would not be.
  CHECK(refused(20, 3e38f) == name + ": the header's frames run from 3.00000001e+38 to "
                                     "3.00000001e+38 (start frame + (samples - 1) x sample "
                                     "rate), beyond 1e18 in magnitude");
  CHECK(refused(24, 3e38f) == name + ": the header's frames run from 0 to 6.00000001e+38 (start "
                                     "frame + (samples - 1) x sample rate), beyond 1e18 in "
                                     "magnitude");
  CHECK(refused(24, 0.0f) == name + ": the header's sample rate 0 is not positive (it is the "
                                    "number of frames from one sample to the next)");
  CHECK(refused(24, -2.0f) == name + ": the header's sample rate -2 is not positive (it is the "
                                     "number of frames from one sample to the next)");

  // At the limits the job runs, and its output reads back: frames 0 and 2 of start -1e18, rate
  // 1e18 are frames -1e18 and 1e18 (as float32 values), written as start -1e18, rate 2e18.
  std::string edge = good;
  const float start = -1e18f, rate = 1e18f;
  std::memcpy(&edge[20], &start, 4);
  std::memcpy(&edge[24], &rate, 4);
  write_file_atomic(cache.file, edge);
  c.input.range = {0, std::nullopt, 2};
  c.massage.iterations = 1;
  run(c);
  const PointCacheHeader h =
      read_point_cache_header(c.output.dir / "sequence.pc2", PointCacheFormat::Pc2);
  CHECK(h.frames == 2);
  CHECK(h.start == start);
  CHECK(h.sample_rate == float(2.0 * double(rate)));
}

TEST_CASE("an MDD's frame times are part of what --resume compares") {
  test::TempDir dir("mdd_resume_times");
  SequenceJobOptions c = float_tube_job(dir.path(), 3);
  const PointCacheInput cache = cache_of_folder(c.input.frames, dir.path(), PointCacheFormat::Mdd);
  use_cache(c, cache);
  c.output.format = OutputFormat::Mdd;
  c.massage.iterations = 1;
  run(c);
  const fs::path out = c.output.dir / "sequence.mdd";
  CHECK(read_point_cache_header(out, PointCacheFormat::Mdd).times ==
        std::vector<float>{0.0f, 1.0f / 24, 2.0f / 24});
  c.resume = true;
  CHECK(run(c).resumed == 3);  // nothing changed: every frame kept

  // Only the times change (big-endian float32 after the two counts): 0.25, 0.5, 1 s.
  std::string bytes = read_file(cache.file);
  const float times[3] = {0.25f, 0.5f, 1.0f};
  for (int f = 0; f < 3; ++f) {
    uint32_t u;
    std::memcpy(&u, &times[f], 4);
    for (int i = 0; i < 4; ++i) bytes[size_t(8 + 4 * f + i)] = char((u >> (24 - 8 * i)) & 0xff);
  }
  write_file_atomic(cache.file, bytes);
  const SequenceResult r = run(c);
  CHECK(r.resumed == 0);  // every frame redone: its record's time is not the input's
  CHECK(read_point_cache_header(out, PointCacheFormat::Mdd).times ==
        std::vector<float>{0.25f, 0.5f, 1.0f});
  CHECK(csv_column(c.output.dir / "summary.csv", "time") ==
        std::vector<std::string>{"0.25", "0.5", "1"});
}
