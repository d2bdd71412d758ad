#include "pipeline/sequence/synthetic.hpp"

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"
#include "pipeline/sequence/frame_source.hpp"

namespace sm {
namespace {

// Uniform double in [lo, hi) from a 64-bit generator: unlike std::uniform_real_distribution, the
// same on every standard library.
double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

struct Wave {
  int k_around;     // whole cycles around the tube (the field is periodic in the angle)
  double k_along;   // cycles along the tube
  double phase;     // radians
  double speed;     // cycles over the whole sequence
  double a_around;  // amplitude factors of the two tangential directions
  double a_along;
};

std::vector<Wave> make_waves(const SyntheticOptions& c) {
  std::mt19937_64 rng(static_cast<uint64_t>(c.seed) * 0x9E3779B97F4A7C15ull + 1);
  std::vector<Wave> waves;
  const double norm = 1.0 / std::sqrt(static_cast<double>(c.drift_waves));
  for (int w = 0; w < c.drift_waves; ++w) {
    Wave wave;
    wave.k_around = 2 + static_cast<int>(rng() % 3);
    wave.k_along = uniform(rng, 1.5, c.drift_cycles);
    wave.phase = uniform(rng, 0.0, 2.0 * M_PI);
    wave.speed = uniform(rng, 0.5, 1.5);
    wave.a_around = norm * uniform(rng, -1.0, 1.0);
    wave.a_along = norm * uniform(rng, -1.0, 1.0);
    waves.push_back(wave);
  }
  return waves;
}

// Point at angle theta and length s on the tube bent with curvature kappa: its centre line is a
// circular arc in the x-z plane starting at the origin along +z, curving towards -x.
Vec3 bent_point(double theta, double s, double r, double kappa) {
  const double ks = kappa * s;
  const double cx = kappa == 0.0 ? 0.0 : -2.0 * std::sin(0.5 * ks) * std::sin(0.5 * ks) / kappa;
  const double cz = kappa == 0.0 ? s : std::sin(ks) / kappa;
  const double c = r * std::cos(theta);
  return Vec3(cx + c * std::cos(ks), r * std::sin(theta), cz + c * std::sin(ks));
}

// Point at (u, s) on the sheet of width `width` rolled with curvature kappa: the line u = width/2
// stays on the y axis, the sheet bends towards +z (an isometry: arc length u is kept).
Vec3 rolled_point(double u, double s, double width, double kappa) {
  const double a = u - 0.5 * width;
  if (kappa == 0.0) return Vec3(a, s, 0.0);
  const double ka = kappa * a;
  return Vec3(std::sin(ka) / kappa, s, 2.0 * std::sin(0.5 * ka) * std::sin(0.5 * ka) / kappa);
}

double sheet_width(const SyntheticOptions& c) { return 2.0 * M_PI * c.radius; }

// The sheet's mesh (make_grid, segments vertices across) and one texture coordinate per vertex.
void make_sheet(SyntheticSequence& seq) {
  const SyntheticOptions& c = seq.config;
  seq.rest = make_grid(c.segments - 1, c.rings, sheet_width(c), c.length);
  seq.rest.V.col(0).array() -= 0.5 * sheet_width(c);
  seq.F = seq.rest.F;
  seq.uv.resize(seq.rest.num_vertices(), 2);
  for (int v = 0; v < seq.rest.num_vertices(); ++v)
    seq.uv.row(v) << static_cast<double>(v % c.segments) / (c.segments - 1),
        static_cast<double>(v / c.segments) / c.rings;
  seq.F_uv = seq.F;
}

}  // namespace

void check_synthetic_options(const SyntheticOptions& options) {
  check_ranges(options, "input.synthetic");
  if (options.shape == SyntheticShape::BendingTube && options.bend * M_PI / 180.0 * options.radius >= options.length)
    throw ConfigError(
        "input.synthetic.bend: the tube would fold onto itself: bend (in radians) times radius "
        "must stay below length");
}

SyntheticSequence make_synthetic_sequence(const SyntheticOptions& config) {
  check_synthetic_options(config);
  SyntheticSequence seq;
  seq.config = config;
  if (config.shape == SyntheticShape::RolledSheet) {
    make_sheet(seq);
    return seq;
  }
  const int nu = config.segments;
  seq.rest = make_cylinder(nu, config.rings, config.radius, config.length);
  seq.F = seq.rest.F;
  seq.uv.resize((nu + 1) * (config.rings + 1), 2);
  for (int j = 0; j <= config.rings; ++j)
    for (int i = 0; i <= nu; ++i)
      seq.uv.row(j * (nu + 1) + i) << static_cast<double>(i) / nu,
          static_cast<double>(j) / config.rings;
  seq.F_uv.resize(seq.F.rows(), 3);
  for (int t = 0; t < seq.F.rows(); ++t) {
    bool seam = false;  // the triangle joins the last column of vertices to the first
    for (int c = 0; c < 3; ++c) seam |= seq.F(t, c) % nu == nu - 1;
    for (int c = 0; c < 3; ++c) {
      const int v = seq.F(t, c);
      const int i = v % nu, j = v / nu;
      seq.F_uv(t, c) = j * (nu + 1) + (seam && i == 0 ? nu : i);
    }
  }
  return seq;
}

namespace {

// The sheet's frame: the drift moves the (across, along) parameters, vanishing on the boundary.
SyntheticFrame rolled_frame(const SyntheticSequence& seq, const std::vector<Wave>& waves,
                            double tau, double kappa, double amplitude) {
  const SyntheticOptions& c = seq.config;
  const int nu = c.segments;
  const int n = seq.rest.num_vertices();
  const double width = sheet_width(c);
  SyntheticFrame frame;
  frame.clean.resize(n, 3);
  frame.drifted.resize(n, 3);
  for (int v = 0; v < n; ++v) {
    const double u = width * (v % nu) / (nu - 1);
    const double s = c.length * (v / nu) / c.rings;
    double d_across = 0.0, d_along = 0.0;
    for (const Wave& w : waves) {
      const double arg = 2.0 * M_PI * (w.k_around * u / width + w.k_along * s / c.length +
                                       w.speed * tau) + w.phase;
      d_across += w.a_around * std::sin(arg);
      d_along += w.a_along * std::sin(arg);
    }
    const double window = amplitude * std::sin(M_PI * u / width) * std::sin(M_PI * s / c.length);
    frame.clean.row(v) = rolled_point(u, s, width, kappa).transpose();
    frame.drifted.row(v) =
        rolled_point(u + window * d_across, s + window * d_along, width, kappa).transpose();
  }
  return frame;
}

}  // namespace

SyntheticFrame synthetic_frame(const SyntheticSequence& seq, int t) {
  const SyntheticOptions& c = seq.config;
  if (t < 0 || t >= c.frames)
    throw InputError("synthetic frame " + std::to_string(t) + " does not exist (" +
                     std::to_string(c.frames) + " frames)");
  const double tau = static_cast<double>(t) / (c.frames - 1);
  const bool sheet = c.shape == SyntheticShape::RolledSheet;
  const double span = sheet ? sheet_width(c) : c.length;  // what the bend angle spreads over
  const double kappa = c.bend * M_PI / 180.0 * 0.5 * (1.0 - std::cos(M_PI * tau)) / span;
  const double amplitude = c.drift * (c.length / c.rings) * std::sin(0.5 * M_PI * tau);
  const std::vector<Wave> waves = make_waves(c);
  if (sheet) return rolled_frame(seq, waves, tau, kappa, amplitude);
  const int nu = c.segments;
  const int n = seq.rest.num_vertices();
  SyntheticFrame frame;
  frame.clean.resize(n, 3);
  frame.drifted.resize(n, 3);
  for (int v = 0; v < n; ++v) {
    const double theta = 2.0 * M_PI * (v % nu) / nu;
    const double s = c.length * (v / nu) / c.rings;
    double d_around = 0.0, d_along = 0.0;  // arc lengths
    for (const Wave& w : waves) {
      const double arg =
          w.k_around * theta + 2.0 * M_PI * (w.k_along * s / c.length + w.speed * tau) + w.phase;
      d_around += w.a_around * std::sin(arg);
      d_along += w.a_along * std::sin(arg);
    }
    const double window = amplitude * std::sin(M_PI * s / c.length);
    frame.clean.row(v) = bent_point(theta, s, c.radius, kappa).transpose();
    frame.drifted.row(v) =
        bent_point(theta + window * d_around / c.radius, s + window * d_along, c.radius, kappa)
            .transpose();
  }
  return frame;
}

std::string synthetic_frame_name(const SyntheticSequence& seq, int t) {
  return numbered_frame_name(t, seq.config.frames);
}

std::string format_synthetic_obj(const SyntheticSequence& seq, const Positions& V,
                                 const std::string& comment) {
  const bool sheet = seq.config.shape == SyntheticShape::RolledSheet;
  std::string out = "# " + comment + (sheet ? "\ng sheet\n" : "\ng tube\n");
  out.reserve(out.size() + 40 * (V.rows() + seq.uv.rows() + seq.F.rows()));
  for (int v = 0; v < V.rows(); ++v)
    out += "v " + format_number(V(v, 0)) + " " + format_number(V(v, 1)) + " " +
           format_number(V(v, 2)) + "\n";
  for (int k = 0; k < seq.uv.rows(); ++k)
    out += "vt " + format_number(seq.uv(k, 0)) + " " + format_number(seq.uv(k, 1)) + "\n";
  for (int t = 0; t < seq.F.rows(); ++t) {
    out += "f";
    for (int c = 0; c < 3; ++c)
      out += " " + std::to_string(seq.F(t, c) + 1) + "/" + std::to_string(seq.F_uv(t, c) + 1);
    out += "\n";
  }
  return out;
}

int write_synthetic_sequence(const SyntheticSequence& seq, const std::filesystem::path& drifted_dir,
                             const std::filesystem::path& clean_dir) {
  const int frames = seq.config.frames;
  for (int t = 0; t < frames; ++t) {
    const SyntheticFrame frame = synthetic_frame(seq, t);
    const std::string name = synthetic_frame_name(seq, t);
    const std::string what = std::string("seqmassage synthetic ") +
                             (seq.config.shape == SyntheticShape::RolledSheet ? "rolled sheet"
                                                                             : "bending tube") +
                             ", frame " + std::to_string(t) +
                             " of " + std::to_string(frames);
    write_file_atomic(drifted_dir / name,
                      format_synthetic_obj(seq, frame.drifted, what + ", drifted"));
    write_file_atomic(clean_dir / name,
                      format_synthetic_obj(seq, frame.clean, what + ", clean (ground truth)"));
  }
  return frames;
}

}  // namespace sm
