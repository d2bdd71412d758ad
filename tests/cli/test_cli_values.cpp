// Values the readers now bound, end to end (issue 24.4 and 24.6): a sampling spacing beyond the
// budget (exit 2 before any work, in --dry-run too, naming measures.spacing and the count), a
// point cache with a coordinate beyond 1e18 or a sample rate of 0 (exit 3 naming the file).
// Nothing is written, no input is changed.
#include <catch2/catch.hpp>
#include <cstring>

#include "io/atomic_file.hpp"
#include "io/obj.hpp"
#include "io/point_cache.hpp"
#include "pipeline/sequence/synthetic.hpp"
#include "support/cli_process.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"
#include "support/text_files.hpp"

using namespace sm;
using Catch::Matchers::Contains;
using test::write_text;
namespace fs = std::filesystem;

namespace {

// Four frames of a 12×10 tube in `in/`.
SyntheticSequence write_frames(const fs::path& dir) {
  SyntheticSequence s = make_synthetic_sequence(test::small_tube(4));
  write_synthetic_sequence(s, dir / "in", dir / "gt");
  return s;
}

}  // namespace

TEST_CASE("a spacing beyond the sample budget: exit 2 before any work", "[cli][values]") {
  test::TempDir dir("cli_spacing_budget");
  const SyntheticSequence s = write_frames(dir.path());
  write_text(dir / "job.json", R"({"job": "sequence", "input": {"frames": "in"},
    "output": {"dir": "out"}, "measures": {"spacing": 1e-9}})");
  for (const char* args : {"job.json", "--dry-run job.json"}) {
    const test::CliRun run = test::run_cli(dir.path(), args);
    CHECK(run.code == 2);
    CHECK_THAT(run.err, Contains("job.json: measures.spacing: 1e-09 would take up to ") &&
                            Contains(" samples on the template, ") &&
                            Contains("more than the budget of 50000000 (50 million, or 100 per "
                                     "triangle); choose a larger spacing"));
    CHECK_FALSE(fs::exists(dir / "out"));
  }
  // The sequence's default spacing (0.125, adaptive) and a fine one within the budget run.
  write_text(dir / "job.json", R"({"job": "sequence", "input": {"frames": "in"},
    "output": {"dir": "out"}, "massage": {"iterations": 2}, "measures": {"spacing": 0.01}})");
  CHECK(test::run_cli(dir.path(), "-q job.json").code == 0);

  // seqmassage measure: both meshes are sampled.
  const fs::path a = dir / ("in/" + synthetic_frame_name(s, 0)),
                 b = dir / ("in/" + synthetic_frame_name(s, 1));
  const test::CliRun measure = test::run_cli(
      dir.path(), "measure --spacing 1e-9 " + test::shell_quote(a.string()) + " " +
                      test::shell_quote(b.string()));
  CHECK(measure.code == 2);
  CHECK_THAT(measure.err, Contains("measures.spacing: 1e-09 would take ") &&
                              Contains(" samples on the measured mesh (240 triangles)"));
}

TEST_CASE("a PC2 coordinate beyond 1e18 or a sample rate of 0: exit 3 naming the file",
          "[cli][values]") {
  test::TempDir dir("cli_pc2_values");
  const SyntheticSequence s = write_frames(dir.path());
  const fs::path rest = dir / ("in/" + synthetic_frame_name(s, 0));
  const int n = read_obj(rest).mesh.num_vertices();
  write_point_cache(dir / "take.pc2", PointCacheFormat::Pc2, n, 4, {}, [&](int f) {
    return read_obj(dir / ("in/" + synthetic_frame_name(s, f))).mesh.V;
  });
  const std::string good = read_file(dir / "take.pc2");
  write_text(dir / "job.json", R"({"job": "sequence", "input": {"pc2": "take.pc2", "mesh": ")" +
                                   rest.string() + R"("}, "output": {"dir": "out", "format": "pc2"}})");
  const auto run_with = [&](size_t at, float value) {
    std::string bytes = good;
    std::memcpy(&bytes[at], &value, 4);
    write_file_atomic(dir / "take.pc2", bytes);
    const test::CliRun run = test::run_cli(dir.path(), "job.json");
    CHECK(read_file(dir / "take.pc2") == bytes);
    CHECK_FALSE(fs::exists(dir / "out"));
    return run;
  };
  const test::CliRun far = run_with(32 + 12 * size_t(n) * 3 + 4, -1e30f);  // frame 3, vertex 0, y
  CHECK(far.code == 3);
  CHECK_THAT(far.err, Contains("take.pc2': frame 3, vertex 0: coordinate y -1.00000002e+30 is too "
                               "large (more than 1e18 in magnitude: the geometry would overflow)"));
  const test::CliRun zero = run_with(24, 0.0f);
  CHECK(zero.code == 3);
  CHECK_THAT(zero.err, Contains("take.pc2': the header's sample rate 0 is not positive"));
}
