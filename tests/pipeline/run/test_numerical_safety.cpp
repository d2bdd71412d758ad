// Numerical safety of the sequence job (issue 6.5): each kind of per-frame failure — the
// optimizer fails, positions are not finite, triangles fold over — is detected, reported in
// summary.csv and report.json with its reason, and the frame is written unchanged or not at all
// (output.on_failure); the other frames are complete.
#include <catch2/catch.hpp>
#include <cmath>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/obj.hpp"
#include "pipeline/cluster/frame_record.hpp"
#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/report/report.hpp"
#include "pipeline/run/sequence_job.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

// A source that passes every frame on, except that frame `bad` gets a NaN coordinate: what a
// frame source that does not check its frames (a plug-in, a future reader) could deliver. The
// library's readers refuse NaN, so this is the honest way in.
class NanSource : public FrameSource {
 public:
  NanSource(std::shared_ptr<const FrameSource> inner, int bad, int huge = -1)
      : inner_(std::move(inner)), bad_(bad), huge_(huge) {}
  int size() const override { return inner_->size(); }
  std::string name(int i) const override { return inner_->name(i); }
  std::string describe() const override { return inner_->describe(); }
  nlohmann::json report() const override { return inner_->report(); }
  std::vector<fs::path> files(const std::vector<int>& frames) const override {
    return inner_->files(frames);
  }
  std::string fetch(int i) const override { return inner_->fetch(i); }
  SourceFrame decode(int i, std::string bytes) const override {
    SourceFrame f = inner_->decode(i, std::move(bytes));
    if (i == bad_) f.mesh.V(7, 1) = std::nan("");
    if (i == huge_) {  // the readers refuse coordinates beyond 1e18: this is the way in
      f.mesh.V(0, 0) = 1.7e308;
      f.mesh.V(1, 1) = -1.7e308;
    }
    return f;
  }

 private:
  std::shared_ptr<const FrameSource> inner_;
  int bad_;
  int huge_;
};

// Frames 2, 3 and 4 of a 6-frame tube made to fail, each in its own way.
SequencePlan failing_plan(const SequenceJobOptions& c) {
  // Frame 2: a tracking glitch, one vertex flung 5 units (10 radii) off the tube: the optimizer
  // pulls it back into the template's shape and folds triangles over.
  test::edit_obj_vertices(c.input.frames / "frame_0002.obj",
                          [](int v, double& x, double&, double&) {
                            if (v == 40) x += 5.0;
                          });
  SequenceJobOptions no_repair = c;  // the fold must fail its frame, not be repaired
  no_repair.checks.repair_folds = false;
  SequencePlan plan = plan_sequence_job(no_repair);
  // Frame 4: a NaN from the source; frame 3: finite coordinates at the end of the double range,
  // which overflow the system: the sparse LU fails.
  plan.source = std::make_shared<NanSource>(plan.source, 4, 3);
  plan.outputs = make_frame_outputs({plan.config, plan.source, {}});
  return plan;
}

}  // namespace

TEST_CASE("each failure kind fails its frame, which is written unchanged by default") {
  test::TempDir dir("safety_copy");
  const SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube());
  const SequencePlan plan = failing_plan(c);
  const SequenceResult r = run_sequence_job(plan);
  REQUIRE(r.frames.size() == 6);
  CHECK(r.failed == 3);
  for (int t : {0, 1, 5}) CHECK(r.frames[size_t(t)].status != FrameStatus::Failed);

  const FrameSummary& fold = r.frames[2];
  CHECK(fold.status == FrameStatus::Failed);
  CHECK(fold.folded_triangles > 1);  // more than 0.5% of 240 triangles
  CHECK_THAT(fold.failure, StartsWith("folded triangles: " + std::to_string(fold.folded_triangles) +
                                      " output triangles are folded over") &&
                               Contains("checks.max_folded_fraction = 0.005 of 240 triangles"));
  CHECK(r.frames[3].failure == "optimizer failed: iteration 1: sparse LU solve failed");
  CHECK(r.frames[4].failure ==
        "non-finite positions: input vertex 7 has a non-finite coordinate (" +
            format_number(read_obj(c.input.frames / "frame_0004.obj").mesh.V(7, 0)) + ", nan, " +
            format_number(read_obj(c.input.frames / "frame_0004.obj").mesh.V(7, 2)) + ")");

  // Written unchanged, byte for byte (OBJ input), with a table whose "after" is the input's.
  for (int t : {2, 3, 4}) {
    const std::string name = "frame_000" + std::to_string(t);
    CHECK(read_file(dir / ("out/frames/" + name + ".obj")) ==
          read_file(dir / ("in/" + name + ".obj")));
    CHECK(fs::exists(dir / ("out/distortion/" + name + ".csv")));
    CHECK(r.frames[size_t(t)].shear_after.mean == r.frames[size_t(t)].shear_before.mean);
  }
  // summary.csv: status and reason; report.json: failures and warnings.
  const std::string summary = read_file(dir / "out/summary.csv");
  CHECK_THAT(summary,
             Contains(",failed,optimizer failed: iteration 1: sparse LU solve failed,,0\n"));
  CHECK_THAT(summary, Contains(",failed,\"folded triangles: "));
  const nlohmann::json report = nlohmann::json::parse(read_file(dir / "out/report.json"));
  CHECK(report["totals"]["failed"] == 3);
  REQUIRE(report["failures"].size() == 3);
  CHECK(report["failures"][1]["frame"] == 3);
  CHECK(report["failures"][1]["reason"] == r.frames[3].failure);
  CHECK_THAT(report["warnings"].dump(),
             Contains("frame 3 (frame_0003.obj) failed, written unchanged: "
                      "optimizer failed"));
}

TEST_CASE("with on_failure \"skip\", a failed frame is not written, and stale outputs go") {
  test::TempDir dir("safety_skip");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube());
  // A first run writes every frame (nothing fails before the inputs are spoiled).
  run_sequence_job(plan_sequence_job(c));
  REQUIRE(fs::exists(dir / "out/frames/frame_0002.obj"));
  c.output.on_failure = OnFailure::Skip;
  const SequenceResult r = run_sequence_job(failing_plan(c));
  CHECK(r.failed == 3);
  for (int t = 0; t < 6; ++t) {
    const std::string name = "frame_000" + std::to_string(t);
    const bool failed = t >= 2 && t <= 4;
    INFO(name);
    CHECK(fs::exists(dir / ("out/frames/" + name + ".obj")) == !failed);
    CHECK(fs::exists(dir / ("out/distortion/" + name + ".csv")) == !failed);
    const auto record = read_frame_record(dir / ("out/records/" + name + ".json"));
    REQUIRE(record);
    CHECK(record->outputs.empty() == failed);
  }
  CHECK_THAT(read_file(dir / "out/summary.csv"), Contains("3,frame_0003.obj,"));
  CHECK_THAT(nlohmann::json::parse(read_file(dir / "out/report.json"))["warnings"].dump(),
             Contains("frame 3 (frame_0003.obj) failed, not written: optimizer failed"));
}

TEST_CASE("folds below the limit are counted, reported, and do not fail the frame") {
  test::TempDir dir("safety_count");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(4));
  test::edit_obj_vertices(c.input.frames / "frame_0002.obj",
                          [](int v, double& x, double&, double&) {
                            if (v == 40) x += 5.0;
                          });
  c.checks.max_folded_fraction.reset();
  c.checks.max_folded_triangles = 1000;
  const SequenceResult r = run_sequence_job(plan_sequence_job(c));
  CHECK(r.failed == 0);
  CHECK(r.frames[2].status == FrameStatus::Optimized);
  CHECK(r.frames[2].folded_triangles > 1);
  CHECK(r.frames[1].folded_triangles == 0);
  CHECK_THAT(nlohmann::json::parse(read_file(dir / "out/report.json"))["warnings"].dump(),
             Contains("frame 2 (frame_0002.obj): " + std::to_string(r.frames[2].folded_triangles) +
                      " triangles folded over"));
  // An absolute limit below the count fails it (without the fold repair, which would mend it).
  c.checks.max_folded_triangles = 1;
  c.checks.repair_folds = false;
  const SequenceResult strict = run_sequence_job(plan_sequence_job(c));
  CHECK(strict.failed == 1);
  CHECK_THAT(strict.frames[2].failure, Contains("more than checks.max_folded_triangles = 1"));
}
