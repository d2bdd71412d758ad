// The bad-input catalogue end to end: seqmassage run as a subprocess on
// generated frame folders spoilt in one way each. Every case checks the exit code, the message
// (naming the file, frame, line or key) and that no input is touched and no partial or temporary
// file is left.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <map>
#include <optional>

#include "io/atomic_file.hpp"
#include "pipeline/sequence/synthetic.hpp"
#include "support/cli_process.hpp"
#include "support/sequence_fixture.hpp"
#include "support/temp_dir.hpp"
#include "support/text_files.hpp"

using namespace sm;
using test::write_text;
namespace fs = std::filesystem;

namespace {

// Every regular file under `dir` with its bytes.
std::map<fs::path, std::string> snapshot(const fs::path& dir) {
  std::map<fs::path, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) files[fs::relative(entry.path(), dir)] = read_file(entry.path());
  return files;
}

int temporaries_in(const fs::path& dir) {
  int n = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.path().filename().string().find(kTempSuffix) != std::string::npos) ++n;
  return n;
}

// Five frames of a 12×10 tube in `in/`, and job.json reading them into `out/`.
struct Job {
  test::TempDir dir;
  SyntheticSequence sequence;
  explicit Job(const std::string& name, const std::string& out = "out") : dir(name) {
    sequence = make_synthetic_sequence(test::small_tube(5));
    write_synthetic_sequence(sequence, dir / "in", dir / "gt");
    write_text(dir / "job.json", R"({"job": "sequence", "input": {"frames": "in"},
      "output": {"dir": ")" + out + R"(", "per_triangle_csv": true, "timings": false},
      "massage": {"iterations": 4}})");
  }
  // Frame `t` as text, changed by `edit` (e.g. one line replaced).
  std::string frame(int t) const {
    return read_file(dir / ("in/" + synthetic_frame_name(sequence, t)));
  }
  void set_frame(int t, const std::string& text) const {
    write_text(dir / ("in/" + synthetic_frame_name(sequence, t)), text);
  }
  fs::path path(const std::string& child) const { return dir / child; }
};

// `text` with its line number `line` (1-based) replaced by `replacement`.
std::string replace_line(const std::string& text, int line, const std::string& replacement) {
  size_t begin = 0;
  for (int k = 1; k < line; ++k) begin = text.find('\n', begin) + 1;
  const size_t end = text.find('\n', begin);
  return text.substr(0, begin) + replacement + text.substr(end);
}

// The 1-based number of the first line of `text` starting with `prefix`.
int line_of(const std::string& text, const std::string& prefix) {
  int line = 1;
  for (size_t at = 0; at < text.size(); at = text.find('\n', at) + 1, ++line)
    if (text.compare(at, prefix.size(), prefix) == 0) return line;
  return -1;
}

}  // namespace

TEST_CASE("a NaN, a bad index or a truncated frame: exit 3 naming the file and line",
          "[cli][errors]") {
  Job job("cli_bad_frame");
  const std::string frame2 = job.path("in/frame_0002.obj").string();
  struct Case {
    std::string text;
    std::string message;
  };
  const std::string f = job.frame(2);
  const int v = line_of(f, "v "), face = line_of(f, "f ");
  const std::vector<Case> cases = {
      {replace_line(f, v + 3, "v nan 0 0"),
       ":" + std::to_string(v + 3) + ": v: coordinate x 'nan' is not finite"},
      {replace_line(f, v + 3, "v 1e999 0 0"),
       ":" + std::to_string(v + 3) + ": v: coordinate x '1e999' is not finite"},
      {replace_line(f, face, "f 1/1 0/2 3/3"),
       ":" + std::to_string(face) +
           ": f: corner 2 '0/2': vertex index 0 is invalid (OBJ indices start at 1)"},
      {replace_line(f, face, "f 1/1 2/2 9999/3"),
       ":" + std::to_string(face) +
           ": f: corner 3 '9999/3': vertex index 9999 is out of range (the file has 132 "
           "vertices)"},
      {f.substr(0, f.find('\n', f.find("\nv ") + 1) + 5),
       ":" + std::to_string(v + 1) + ": v: expected 3 coordinates (x y z), found 1"},
      {"", ": no vertices (no 'v' statement)"},
  };
  for (const Case& c : cases) {
    INFO(c.message);
    job.set_frame(2, c.text);
    const auto before = snapshot(job.path("in"));
    const test::CliRun r = test::run_cli_args(job.dir.path(), {"job.json"});
    CHECK(r.code == 3);
    CHECK(r.err == "seqmassage: input error: " + frame2 + c.message + "\n");
    CHECK_FALSE(fs::exists(job.path("out")));
    CHECK(snapshot(job.path("in")) == before);
  }
}

TEST_CASE("frames whose triangles differ from the template's: exit 3, nothing written",
          "[cli][errors]") {
  Job job("cli_bad_count");
  // One triangle fewer, same vertices.
  const std::string f = job.frame(3);
  job.set_frame(3, replace_line(f, line_of(f, "f "), "# a face removed"));
  test::CliRun r = test::run_cli_args(job.dir.path(), {"job.json"});
  CHECK(r.code == 3);
  CHECK(r.err ==
        "seqmassage: input error: frame 3 (frame_0003.obj): 239 triangles, but the template, "
        "frame 0 (frame_0000.obj), has 240\n");
  CHECK_FALSE(fs::exists(job.path("out")));
}

TEST_CASE("an empty frame folder: exit 3 naming the folder", "[cli][errors]") {
  Job job("cli_empty_folder");
  fs::remove_all(job.path("in"));
  fs::create_directories(job.path("in"));
  write_text(job.path("in/readme.txt"), "no frames here\n");
  const test::CliRun r = test::run_cli_args(job.dir.path(), {"job.json"});
  CHECK(r.code == 3);
  CHECK(r.err == "seqmassage: input error: frame folder '" + job.path("in").string() +
                     "' has no .obj files\n");
  CHECK_FALSE(fs::exists(job.path("out")));
}

TEST_CASE("an output folder that cannot be created: exit 4 naming it, nothing written",
          "[cli][errors]") {
  // A regular file where the output folder should go (read-only folders do not stop root).
  Job job("cli_unwritable", "blocker/out");
  write_text(job.path("blocker"), "a file, not a folder\n");
  const test::CliRun r = test::run_cli_args(job.dir.path(), {"job.json"});
  CHECK(r.code == 4);
  CHECK_THAT(r.err, Catch::Contains("seqmassage: I/O error: cannot create folder '" +
                                    job.path("blocker/out").string()));
  CHECK(read_file(job.path("blocker")) == "a file, not a folder\n");
  CHECK(temporaries_in(job.dir.path()) == 0);
}

TEST_CASE("a full disk: exit 4 naming the file, no partial or temporary file is left",
          "[cli][errors]") {
  Job job("cli_disk_full");
  const auto inputs = snapshot(job.path("in"));
  // Below the size of a frame: the first output file fails.
  const size_t frame_size = job.frame(0).size();
  const test::CliRun r =
      test::run_cli_args(job.dir.path(), {"--threads", "2", "job.json"}, frame_size / 2);
  CHECK(r.code == 4);
  CHECK_THAT(r.err, Catch::Contains("seqmassage: I/O error: cannot write '" +
                                    job.path("out/frames/frame_0000.obj").string() +
                                    "': File too large\n"));
  CHECK(snapshot(job.path("in")) == inputs);
  CHECK(temporaries_in(job.dir.path()) == 0);
  CHECK(snapshot(job.path("out")).empty());  // no file at all, let alone a partial one

  // A limit that lets the template frame (written unchanged, the smallest frame) through but not
  // the optimized frames: what was written is complete (equal to the file of an unlimited run).
  const test::CliRun full = test::run_cli_args(job.dir.path(), {"--threads", "2", "job.json"});
  REQUIRE(full.code == 0);
  const auto complete = snapshot(job.path("out"));
  fs::remove_all(job.path("out"));
  const size_t limit = complete.at("frames/frame_0000.obj").size();
  REQUIRE(complete.at("frames/frame_0001.obj").size() > limit);
  const test::CliRun partial =
      test::run_cli_args(job.dir.path(), {"--threads", "2", "job.json"}, limit);
  CHECK(partial.code == 4);
  // Frames write their files in the parallel stage, so whichever optimized frame (1 to 4, all
  // larger than the limit) gets there first is the one named.
  int named = 0;
  for (const char* frame : {"frame_0001", "frame_0002", "frame_0003", "frame_0004"})
    named += partial.err.find("cannot write '" +
                              job.path(std::string("out/frames/") + frame + ".obj").string() +
                              "': File too large\n") != std::string::npos;
  INFO(partial.err);
  CHECK(named >= 1);
  CHECK(temporaries_in(job.dir.path()) == 0);
  const auto written = snapshot(job.path("out"));
  CHECK(written.count("frames/frame_0000.obj") == 1);
  CHECK(written.count("frames/frame_0001.obj") == 0);
  for (const auto& [name, bytes] : written) {
    INFO(name.string());
    REQUIRE(complete.count(name) == 1);
    CHECK(bytes == complete.at(name));
  }
}

TEST_CASE("the output folder may be the input folder: inputs untouched, outputs in subfolders",
          "[cli][errors]") {
  Job job("cli_out_is_in", "in");
  const auto inputs = snapshot(job.path("in"));
  test::CliRun r = test::run_cli_args(job.dir.path(), {"-q", "job.json"});
  CHECK(r.code == 0);
  for (const auto& [name, bytes] : inputs) CHECK(read_file(job.path("in") / name) == bytes);
  CHECK(fs::exists(job.path("in/frames/frame_0004.obj")));
  CHECK(fs::exists(job.path("in/summary.csv")));
  // A second run sees the same five frames (outputs are not .obj files of the folder itself).
  r = test::run_cli_args(job.dir.path(), {"--dry-run", "job.json"});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Catch::Contains("input: 5 OBJ frames in "));
  // Reading the outputs of a run as input with the same output folder would overwrite them.
  write_text(job.path("again.json"), R"({"job": "sequence", "input": {"frames": "in/frames"},
    "output": {"dir": "in"}})");
  r = test::run_cli_args(job.dir.path(), {"again.json"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("would overwrite an input file"));
}

TEST_CASE("a template with degenerate triangles runs with a warning", "[cli][errors]") {
  Job job("cli_degenerate_template");
  // Frame 0 (the template) with vertex 1 moved onto its neighbour, vertex 0: zero-area triangles.
  const std::string f = job.frame(0);
  const int v = line_of(f, "v ");
  const size_t first = f.find("\nv ") + 1;
  job.set_frame(0, replace_line(f, v + 1, f.substr(first, f.find('\n', first) - first)));
  const test::CliRun r = test::run_cli_args(job.dir.path(), {"job.json"});
  CHECK(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("seqmassage: warning: template (frame 0 (frame_0000.obj)): "));
  CHECK_THAT(r.err, Catch::Contains("degenerate triangles"));
  CHECK_THAT(read_file(job.path("out/report.json")), Catch::Contains("degenerate triangles"));
  for (int t = 1; t < 5; ++t) {
    const std::string out =
        read_file(job.path("out/frames/" + synthetic_frame_name(job.sequence, t)));
    CHECK(out.find("nan") == std::string::npos);
    CHECK(out.find("inf") == std::string::npos);
  }
}
