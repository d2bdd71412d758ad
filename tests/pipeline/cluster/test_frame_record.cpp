// Frame records: every summary field round-trips exactly (non-finite values too), the hashes
// cover what they should, recorded outputs are checked by size and content.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "io/atomic_file.hpp"
#include "io/sha256.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"
#include "pipeline/cluster/frame_record.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
namespace fs = std::filesystem;

namespace {

FrameSummary example() {
  FrameSummary s;
  s.frame = 12;
  s.file = "take,12.obj";
  s.time = 0.1 + 0.2;
  s.vertices = 100;
  s.triangles = 196;
  s.shear_before = {std::numeric_limits<double>::infinity(), 1.0 / 3.0, 0.7, 2};
  s.shear_after = {0.5, 0.1, 0.2, 0};
  s.out_to_in = {1e-300, 2.5e-7, 3.0, 4.0, 5.0, 6.0, 12345};
  s.in_to_out.max = std::nan("");
  s.iterations = 15;
  s.seconds = 1.25;
  s.status = FrameStatus::Failed;
  s.failure = "folded triangles: 3 ...";
  s.folded_triangles = 3;
  s.ground_truth = GroundTruthError{0.1, 0.2, 0.3, 0.4, {}, {}};
  s.warnings = {"one", "two"};
  return s;
}

}  // namespace

TEST_CASE("a frame summary round-trips through JSON exactly") {
  const FrameSummary s = example();
  const nlohmann::json j = to_json(s);
  const FrameSummary t = frame_summary_from_json(nlohmann::json::parse(j.dump()));
  CHECK(to_json(t).dump() == j.dump());
  CHECK(t.time == s.time);  // exact doubles
  CHECK(t.shear_before.max == std::numeric_limits<double>::infinity());
  CHECK(std::isnan(t.in_to_out.max));
  CHECK(t.out_to_in.max == 1e-300);
  CHECK(t.status == FrameStatus::Failed);
  CHECK(t.ground_truth->max_after == 0.4);
  CHECK(t.warnings == s.warnings);
  CHECK_FALSE(t.resumed);

  FrameSummary plain;
  plain.file = "a.obj";
  const FrameSummary u = frame_summary_from_json(to_json(plain));
  CHECK_FALSE(u.time);
  CHECK_FALSE(u.ground_truth);
}

TEST_CASE("a broken record names what is wrong") {
  nlohmann::json j = to_json(example());
  j.erase("status");
  CHECK_THROWS_WITH(frame_summary_from_json(j), "frame record: summary.status: missing");
  j = to_json(example());
  j["status"] = "great";
  CHECK_THROWS_WITH(frame_summary_from_json(j),
                    "frame record: summary.status: unknown status \"great\"");
  CHECK_THROWS_AS(frame_record_from_json(nlohmann::json::object()), InputError);
}

TEST_CASE("records are read back, their outputs checked by size and SHA-256") {
  test::TempDir dir("frame_record");
  FrameRecord r;
  r.config_hash = "c";
  r.template_hash = "t";
  r.input_hash = "i";
  r.summary = example();
  write_file_atomic(dir / "frames/a.obj", "v 1 2 3\n");
  r.outputs.push_back({"frames/a.obj", 8, sha256_hex("v 1 2 3\n")});
  const fs::path file = record_file(dir.path(), "a.obj");
  CHECK(file == dir / "records/a.json");
  std::string problem;
  CHECK_FALSE(read_frame_record(file, &problem));
  CHECK(problem == "no record");
  write_file_atomic(file, to_json(r).dump(1));
  const std::optional<FrameRecord> back = read_frame_record(file);
  REQUIRE(back);
  CHECK(to_json(*back) == to_json(r));
  CHECK(check_recorded_outputs(r, dir.path(), true).empty());

  write_file_atomic(dir / "frames/a.obj", "v 1 2 4\n");  // same size, other bytes
  CHECK(check_recorded_outputs(r, dir.path(), false).empty());
  CHECK(check_recorded_outputs(r, dir.path(), true) ==
        "frames/a.obj changed since it was written (SHA-256 differs)");
  write_file_atomic(dir / "frames/a.obj", "v 1 2\n");
  CHECK(check_recorded_outputs(r, dir.path(), false) ==
        "frames/a.obj has 6 bytes, the record says 8");
  fs::remove(dir / "frames/a.obj");
  CHECK(check_recorded_outputs(r, dir.path(), false) == "frames/a.obj is missing");

  write_file_atomic(file, "{\"format\": 1");
  CHECK_FALSE(read_frame_record(file, &problem));
  CHECK(problem.rfind("unreadable record a.json: ", 0) == 0);
}

TEST_CASE("the config hash ignores what does not change a frame's output") {
  SequenceJobOptions c;
  c.input.frames = "/in";
  c.output.dir = "/out";
  const std::string base = frame_config_hash(c);
  CHECK(base.size() == 64);
  SequenceJobOptions d = c;
  d.threads = 7;
  d.frames_in_flight = 3;
  d.input.range = {2, 9, 3};
  d.output.timings = false;
  d.output.dir = "/elsewhere";
  d.shard = {1, 4};
  d.resume = true;
  CHECK(frame_config_hash(d) == base);
  d = c;
  d.massage.iterations = 14;
  CHECK(frame_config_hash(d) != base);
  d = c;
  d.checks.max_folded_triangles = 2;
  CHECK(frame_config_hash(d) != base);
  d = c;
  d.output.on_failure = OnFailure::Skip;
  CHECK(frame_config_hash(d) != base);

  const TriMesh a = make_icosphere(1, 1.0);
  TriMesh b = a;
  CHECK(template_hash(a) == template_hash(b));
  b.V(3, 1) = std::nextafter(b.V(3, 1), 2.0);
  CHECK(template_hash(a) != template_hash(b));
}
