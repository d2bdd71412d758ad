// A sequence job whose writes fail: the error reaches the caller with its type and message, the
// frames in flight are dropped (not leaked: the ASan build checks), nothing partial is left.
#include <catch2/catch.hpp>
#include <fstream>

#include "io/atomic_file.hpp"
#include "core/errors.hpp"
#include "pipeline/run/sequence_job.hpp"
#include "pipeline/sequence/synthetic.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
namespace fs = std::filesystem;

TEST_CASE("a write that fails mid-run throws its IoError after the pipeline drained",
          "[pipeline][errors]") {
  test::TempDir dir("job_write_fails");
  SequenceJobOptions c = test::tube_job(dir.path(), test::small_tube(6));
  c.massage.iterations = 3;
  c.frames_in_flight = 4;
  const SequencePlan plan = plan_sequence_job(c);
  // distortion/ is a file: the first per-triangle table cannot be written, after frames/ was.
  fs::create_directories(dir / "out");
  std::ofstream(dir / "out/distortion") << "in the way\n";
  std::string message;
  try {
    run_sequence_job(plan);
  } catch (const IoError& e) {
    message = e.what();
  }
  CHECK(message ==
        "cannot create folder '" + (dir / "out/distortion").string() + "': Not a directory");
  CHECK(fs::exists(dir / "out/frames/frame_0000.obj"));
  // Frames write their own files in the parallel stage: a frame finished at the same time as the
  // failing one may have written its OBJ too (complete), but no frame is recorded as done, and
  // the frames still in flight after the failure are dropped unwritten.
  CHECK_FALSE(fs::exists(dir / "out/frames/frame_0005.obj"));
  for (int k = 0; k < 6; ++k)
    CHECK_FALSE(fs::exists(dir / ("out/records/frame_000" + std::to_string(k) + ".json")));
  CHECK_FALSE(fs::exists(dir / "out/summary.csv"));
  for (const auto& entry : fs::recursive_directory_iterator(dir / "out"))
    CHECK(entry.path().string().find(".seqmassage-tmp") == std::string::npos);
}
