// The lines the command line prints about a run, against the forms their header documents.
#include <catch2/catch.hpp>

#include <cmath>

#include "pipeline/report/run_text.hpp"

using namespace sm;

namespace {

FrameSummary frame(int index, const char* file, double before, double after) {
  FrameSummary f;
  f.frame = index;
  f.file = file;
  f.shear_before.mean = before;
  f.shear_after.mean = after;
  f.iterations = 8;
  return f;
}

}  // namespace

TEST_CASE("clock_text writes M:SS or H:MM:SS and dashes when unknown") {
  CHECK(clock_text(0) == "0:00");
  CHECK(clock_text(5) == "0:05");
  CHECK(clock_text(59.6) == "1:00");  // rounded to the second
  CHECK(clock_text(3599) == "59:59");
  CHECK(clock_text(3600) == "1:00:00");
  CHECK(clock_text(2 * 3600 + 3 * 60 + 4) == "2:03:04");
  CHECK(clock_text(-1) == "--:--");
  CHECK(clock_text(std::nan("")) == "--:--");
  CHECK(clock_text(100 * 3600.0) == "--:--");  // 100 hours and more
  CHECK(clock_text(99 * 3600.0 + 59 * 60 + 59) == "99:59:59");
}

TEST_CASE("fixed_text has the asked decimals") {
  CHECK(fixed_text(2, 2) == "2.00");
  CHECK(fixed_text(0.27774, 4) == "0.2777");
  CHECK(fixed_text(-1.25, 1) == "-1.2");  // round half to even in printf's binary value
}

TEST_CASE("a frame's progress line: file, status, shear, iterations, rate and ETA") {
  // 3 of 12 frames in 1.5 s: 2 frames/s, 9 frames left take 4.5 s, shown as 0:05.
  const FrameSummary f = frame(2, "a.obj", 0.1, 0.01);
  CHECK(frame_progress_text(f, 3, 12, 1.5) ==
        "frame 3/12 a.obj: optimized, mean shear 0.1000 -> 0.0100, 8 iterations, 2.00 frames/s, "
        "ETA 0:05");
  FrameSummary kept = f;
  kept.resumed = true;
  CHECK_THAT(frame_progress_text(kept, 3, 12, 1.5),
             Catch::Contains("optimized (kept from an earlier run),"));
  // Nothing timed yet: no rate, no ETA.
  CHECK_THAT(frame_progress_text(f, 0, 12, 0.0), Catch::EndsWith("0.00 frames/s, ETA --:--"));
}

TEST_CASE("the progress bar fills in proportion") {
  CHECK(progress_bar_text(3, 12, 1.5) ==
        "[" + std::string(7, '#') + std::string(23, '.') + "] 3/12 frames  2.00 frames/s  ETA 0:05");
  CHECK(progress_bar_text(12, 12, 6.0).substr(0, 32) == "[" + std::string(30, '#') + "]");
  CHECK(progress_bar_text(0, 0, 0.0).substr(0, 32) == "[" + std::string(30, '#') + "]");
}

TEST_CASE("a failed frame's line says what happened to its output") {
  FrameSummary f = frame(3, "a.obj", 0.1, 0.1);
  f.status = FrameStatus::Failed;
  f.failure = "folded triangles: 2";
  CHECK(frame_failure_text(f, OnFailure::Skip) ==
        "frame 3 (a.obj) failed, not written: folded triangles: 2");
  CHECK_THAT(frame_failure_text(f, OnFailure::CopyInput), Catch::Contains("written unchanged: "));
  f.resumed = true;
  CHECK_THAT(frame_failure_text(f, OnFailure::Skip), Catch::Contains("(in an earlier run)"));
}

TEST_CASE("the resume and end lines count and average the frames") {
  SequenceResult r;
  for (int i = 0; i < 12; ++i) r.frames.push_back(frame(i, "f.obj", 0.25, 0.0125));
  r.resumed = 8;
  r.redone = {{"changed input", 3}, {"no record", 1}};
  CHECK(resume_text(r) ==
        "resume: 8 frames kept from earlier runs, 4 processed (3 changed input, 1 no record)");
  r.redone.clear();
  CHECK(resume_text(r) == "resume: 8 frames kept from earlier runs, 4 processed");
  r.seconds = 3.44;
  CHECK(run_end_text(r) == "12 frames in 3.4 s (0 failed), mean shear 0.2500 -> 0.0125");
}
