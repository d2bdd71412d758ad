// The tracker on untracked sequences generated in code: each frame of an analytic deforming
// surface is triangulated anew at random, the truth of a template vertex is the surface point of
// its parameters. Errors are in mean edge lengths of the template.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "support/untracked_sequence.hpp"
#include "track/tracker.hpp"

using namespace sm;
using namespace sm::test;

namespace {

struct CaseFigures {
  double error_mean = 0, error_max_frame = 0;  // against the truth: mean over frames, worst frame
  double registration_error_mean = 0;
  double to_raw_mean = 0, from_raw_mean = 0, from_raw_p99 = 0;
  int folded = 0;
  std::vector<TrackStatus> status;
  std::vector<double> frame_error;
  double motion_mean = 0, motion_max = 0;  // per frame, truth, template edge lengths
};

double truth_error(const Positions& V, const std::vector<Eigen::Vector2d>& params,
                   const Surface& s, double time, double h) {
  double total = 0;
  for (int i = 0; i < V.rows(); ++i)
    total += (V.row(i).transpose() - s.at(params[i][0], params[i][1], time)).norm();
  return total / V.rows() / h;
}

// Tracks frames 1..frames of `s` (frame 0 is the template's own triangulation); `glitch`, if
// given, replaces a frame's raw mesh.
CaseFigures run_case(const Surface& s, int frames, double cell, unsigned seed,
                     TrackOptions options = {},
                     const std::function<void(int, TriMesh&)>& glitch = {}) {
  const SampledFrame templ = sample_surface(s, 0.0, cell, seed);
  Tracker tracker(templ.mesh, options);
  const double h = tracker.mean_edge();
  CaseFigures c;
  for (int k = 1; k <= frames; ++k) {
    SampledFrame raw = sample_surface(s, k, cell * 0.93, seed * 7919u + k);
    if (glitch) glitch(k, raw.mesh);
    const TrackFrame f = tracker.track(raw.mesh);
    const double e = truth_error(f.V, templ.params, s, k, h);
    double motion = 0;
    for (size_t i = 0; i < templ.params.size(); ++i)
      motion += (s.at(templ.params[i][0], templ.params[i][1], k) -
                 s.at(templ.params[i][0], templ.params[i][1], k - 1)).norm();
    motion /= templ.params.size() * h;
    c.motion_mean += motion / frames;
    c.motion_max = std::max(c.motion_max, motion);
    c.frame_error.push_back(e);
    c.status.push_back(f.status);
    if (f.status == TrackStatus::Lost) continue;
    c.error_mean += e;
    c.error_max_frame = std::max(c.error_max_frame, e);
    c.registration_error_mean += truth_error(f.registered, templ.params, s, k, h);
    c.to_raw_mean = std::max(c.to_raw_mean, f.fit.to_raw_mean);
    c.from_raw_mean = std::max(c.from_raw_mean, f.fit.from_raw_mean);
    c.from_raw_p99 = std::max(c.from_raw_p99, f.fit.from_raw_p99);
    c.folded += f.fit.folded;
  }
  int good = 0;
  for (TrackStatus st : c.status) good += st != TrackStatus::Lost;
  c.error_mean /= std::max(good, 1);
  c.registration_error_mean /= std::max(good, 1);
  return c;
}

void print(const char* name, const CaseFigures& c) {
  std::printf("%-28s motion %5.2f (max %5.2f)  reg %6.3f  final %6.3f (worst frame %6.3f)  "
              "to_raw %.4f from_raw %.4f p99 %.3f folded %d\n",
              name, c.motion_mean, c.motion_max, c.registration_error_mean, c.error_mean,
              c.error_max_frame, c.to_raw_mean, c.from_raw_mean, c.from_raw_p99, c.folded);
  for (size_t k = 0; k < c.status.size(); ++k)
    std::printf("  %zu:%s %.3f", k + 1, std::string(name_of(c.status[k], kTrackStatusNames)).c_str(),
                c.frame_error[k]);
  std::printf("\n");
}

}  // namespace

// Bounds: measured on these generated sequences (see the report), with a margin. The tube's bumps
// are smooth, so its twist is weakly observable and its error the largest.
TEST_CASE("tracker follows a bending, twisting tube", "[track]") {
  const CaseFigures c = run_case(bending_tube(/*speed=*/0.6, /*turn=*/0.02), 12, 0.25, 3);
  print("tube", c);
  CHECK(c.motion_mean > 1.0);
  CHECK(c.error_mean < 1.0);
  CHECK(c.error_mean < c.registration_error_mean + 0.05);
  CHECK(c.to_raw_mean < 0.06);
  CHECK(c.from_raw_p99 < 0.5);
  for (TrackStatus s : c.status) CHECK(s != TrackStatus::Lost);
}

TEST_CASE("tracker follows a limb bending at its joint", "[track]") {
  const CaseFigures c = run_case(bending_limb(/*speed=*/1.0, /*turn=*/0.03), 12, 0.25, 5);
  print("limb", c);
  CHECK(c.motion_mean > 2.0);
  CHECK(c.error_mean < 0.35);
  CHECK(c.to_raw_mean < 0.06);
  CHECK(c.folded <= 30);  // over 12 frames of ~1600 triangles: < 0.2% (measured up to 20)
  for (TrackStatus s : c.status) CHECK(s != TrackStatus::Lost);
}

TEST_CASE("tracker follows a rolling sheet at up to 10 edges per frame", "[track]") {
  const CaseFigures c = run_case(rolling_sheet(/*speed=*/2.5, /*turn=*/0.03), 12, 0.25, 7);
  print("sheet", c);
  CHECK(c.motion_max > 8.0);
  CHECK(c.error_mean < 0.35);
  CHECK(c.to_raw_mean < 0.06);
  CHECK(c.folded <= 30);  // over 12 frames of ~1600 triangles: < 0.2% (measured up to 20)
  for (TrackStatus s : c.status) CHECK(s != TrackStatus::Lost);
}

TEST_CASE("track.project puts every vertex on the raw frame", "[track]") {
  TrackOptions options;
  options.project = true;
  const CaseFigures c = run_case(bending_limb(/*speed=*/1.0, /*turn=*/0.03), 5, 0.25, 5, options);
  print("limb, projected", c);
  CHECK(c.to_raw_mean < 1e-9);  // the largest over the frames of the mean vertex distance
  CHECK(c.error_mean < 0.35);
  for (TrackStatus s : c.status) CHECK(s != TrackStatus::Lost);
}

TEST_CASE("a glitched frame is lost, a jump is recovered, tracking goes on", "[track]") {
  // Frame 4 is a capture glitch (every vertex thrown 6 units at random); from frame 8 on the
  // subject is 25 units away (a cut in the footage).
  const Surface limb = bending_limb(0.5, 0.02);
  Surface s = limb;
  s.at = [limb](double u, double v, double time) {
    const Vec3 p = limb.at(u, v, time);
    if (time < 8) return p;
    return Vec3(p + Vec3(3.0, 25.0, -4.0));
  };
  std::mt19937 random(9);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const CaseFigures c = run_case(s, 11, 0.25, 11, {}, [&](int k, TriMesh& raw) {
    if (k == 4)
      for (int i = 0; i < raw.num_vertices(); ++i)
        raw.V.row(i) += 6.0 * Vec3(unit(random), unit(random), unit(random)).transpose();
  });
  print("glitch and jump", c);
  CHECK(c.status[3] == TrackStatus::Lost);  // frame 4
  CHECK(c.status[4] != TrackStatus::Lost);  // frame 5: back from the last good frame
  CHECK(c.status[7] == TrackStatus::Recovered);  // frame 8: the jump
  CHECK(c.frame_error[4] < 1.0);  // restarted from frame 3, without its motion
  for (int k : {6, 7, 8, 9, 10, 11}) CHECK(c.frame_error[k - 1] < 0.6);
  CHECK(c.status[10] == TrackStatus::Ok);
}

TEST_CASE("track.small_motion shortens the coarse stages of frames near their fit", "[track]") {
  // The limb's motion is mostly along its smooth surface, so every frame starts within 0.75
  // edges of it: the coarse stages get one iteration each, and the error grows, which is why
  // the key is off by default (docs/tracking.md, "The schedule").
  const CaseFigures plain = run_case(bending_limb(1.0, 0.03), 6, 0.25, 5);
  TrackOptions options;
  options.small_motion = 0.75;
  const CaseFigures short_coarse = run_case(bending_limb(1.0, 0.03), 6, 0.25, 5, options);
  print("limb, small_motion 0.75", short_coarse);
  CHECK(short_coarse.to_raw_mean < 0.06);
  CHECK(short_coarse.error_mean > plain.error_mean);
  for (TrackStatus s : short_coarse.status) CHECK(s != TrackStatus::Lost);
}

// Not a test: per-frame figures for tuning (TRACK_CASE, TRACK_FRAMES, T_* environment variables).
TEST_CASE("tracker tuning", "[.tune]") {
  const char* which = std::getenv("TRACK_CASE");
  const std::string name = which ? which : "translate";
  Surface s = bending_tube(0.3, 0.0, 0.0, 0.0);
  if (name == "tube") s = bending_tube(0.6, 0.02);
  if (name == "tube_bend") s = bending_tube(0.0, 0.0, 0.25, 0.0);
  if (name == "tube_twist") s = bending_tube(0.0, 0.0, 0.0, 1.2);
  if (name == "turn") s = bending_tube(0.0, 0.05, 0.0, 0.0);
  if (name == "limb") s = bending_limb(0.6, 0.02);
  if (name == "sheet") s = rolling_sheet(0.6, 0.02);
  const SampledFrame templ = sample_surface(s, 0.0, 0.25, 3);
  TrackOptions o;
  auto env = [](const char* k, double d) { const char* v = std::getenv(k); return v ? std::atof(v) : d; };
  o.regularizer = env("T_REG", o.regularizer);
  o.regularizer_final = env("T_REGF", o.regularizer_final);
  o.node_spacing = env("T_SPACING", o.node_spacing);
  o.iterations = static_cast<int>(env("T_IT", o.iterations));
  o.stages = static_cast<int>(env("T_STAGES", o.stages));
  o.point_weight = env("T_POINT", o.point_weight);
  o.robust_scale = env("T_SIGMA", o.robust_scale);
  o.robust_scale_final = env("T_SIGMAF", o.robust_scale_final);
  o.refine_iterations = static_cast<int>(env("T_REFINE", o.refine_iterations));
  o.recover = env("T_RECOVER", 1) > 0;
  Tracker tracker(templ.mesh, o);
  const double h = tracker.mean_edge();
  std::printf("nodes %d h %.3f n %d\n", tracker.num_nodes(), h, templ.mesh.num_vertices());
  const int frames = std::getenv("TRACK_FRAMES") ? std::atoi(std::getenv("TRACK_FRAMES")) : 4;
  for (int k = 0; k <= frames; ++k) {
    SampledFrame raw = sample_surface(s, k, 0.25 * 0.93, 100 + k);
    if (std::getenv("T_FROM_TRUTH")) {
      TriMesh truth = templ.mesh;
      for (int i = 0; i < truth.num_vertices(); ++i)
        truth.V.row(i) = s.at(templ.params[i][0], templ.params[i][1], k).transpose();
      const TrackFrame g = tracker.track(truth);
      std::printf("   on truth: reg %.3f final %.3f\n", truth_error(g.registered, templ.params, s, k, h), truth_error(g.V, templ.params, s, k, h));
      tracker.restart_from(tracker.last_fit());
    }
    const TrackFrame f = tracker.track(raw.mesh);
    if (name == "tube_twist") {
      double ax = 0, ang = 0, angabs = 0;
      for (int i = 0; i < f.V.rows(); ++i) {
        const Vec3 t = s.at(templ.params[i][0], templ.params[i][1], k);
        const Vec3 p = f.V.row(i).transpose();
        ax += (p.x() - t.x());
        const double da = std::remainder(std::atan2(p.z(), p.y()) - std::atan2(t.z(), t.y()), 2 * M_PI);
        ang += da;
        angabs += std::abs(da);
      }
      std::printf("axial %.3f edges, angle mean %.4f abs %.4f rad (twist %.3f)\n", ax / f.V.rows() / h, ang / f.V.rows(), angabs / f.V.rows(), 1.2 * std::sin(0.1 * k));
    }
    std::printf("frame %d reg %.3f final %.3f it %d to_raw %.3f from_raw %.3f | %.3f %.3f fold %d status %d %s\n", k,
                truth_error(f.registered, templ.params, s, k, h),
                truth_error(f.V, templ.params, s, k, h), f.iterations, f.registration_fit.to_raw_mean,
                f.registration_fit.from_raw_mean, f.fit.to_raw_mean, f.fit.from_raw_mean, f.fit.folded, int(f.status), f.recovery.c_str());
  }
}
