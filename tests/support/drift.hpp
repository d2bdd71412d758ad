#pragma once
// Generated drift scenarios for the optimizer's acceptance tests (issue 2): a flat grid rolled
// onto a cylinder (isometric) and a straight tube bent into a torus arc (stretching), each with
// its vertices slid tangentially by a smooth random field and put back on the exact surface.
#include <cmath>
#include <random>

#include "mesh/primitives.hpp"

namespace sm::test {

// A smooth random displacement field in parameter space: a few random low-frequency sinusoids,
// windowed so it vanishes on the boundary of [0,U]×[0,V] (the drift stays inside the domain).
struct SmoothField {
  struct Wave {
    double ku, kv, phase, au, av;
  };
  std::vector<Wave> waves;
  double U = 1, V = 1;
  bool window_u = true, window_v = true;

  SmoothField(unsigned seed, double amplitude, double U_, double V_, int count = 6,
              double kmin = 2.0, double kmax = 5.0)
      : U(U_), V(V_) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> k(kmin, kmax), ph(0.0, 2.0 * M_PI), a(-1.0, 1.0);
    for (int i = 0; i < count; ++i)
      waves.push_back({k(rng), k(rng), ph(rng), amplitude * a(rng) / std::sqrt(count),
                       amplitude * a(rng) / std::sqrt(count)});
  }
  Eigen::Vector2d operator()(double u, double v) const {
    Eigen::Vector2d d(0, 0);
    for (const Wave& w : waves) {
      const double s = std::sin(2 * M_PI * (w.ku * u / U + w.kv * v / V) + w.phase);
      d += Eigen::Vector2d(w.au * s, w.av * s);
    }
    const double win = (window_u ? std::sin(M_PI * u / U) : 1.0) * (window_v ? std::sin(M_PI * v / V) : 1.0);
    return d * win;
  }
};

// Grid vertices (u, v) → cylinder of radius R around the y axis (isometric: arc length = u).
inline Vec3 roll(double u, double v, double R) {
  return Vec3(R * std::sin(u / R), v, R * (1.0 - std::cos(u / R)));
}

struct Scenario {
  TriMesh templ;    // the template T (rest shape)
  TriMesh clean;    // the deformed surface, vertices where they belong (ground truth)
  TriMesh drifted;  // the same surface, vertices slid tangentially (the reference N and M's start)
};

// Flat (nx × ny) grid with spacing h rolled onto a cylinder of radius R; drift of `amplitude`
// edge lengths.
inline Scenario rolled_grid(int nx, int ny, double R, double amplitude, unsigned seed) {
  const double h = 1.0;
  Scenario s;
  s.templ = make_grid(nx, ny, nx * h, ny * h);
  const SmoothField field(seed, amplitude * h, nx * h, ny * h);
  s.clean = s.templ;
  s.drifted = s.templ;
  for (int i = 0; i < s.templ.num_vertices(); ++i) {
    const double u = s.templ.V(i, 0), v = s.templ.V(i, 1);
    s.clean.V.row(i) = roll(u, v, R).transpose();
    const Eigen::Vector2d d = field(u, v);
    s.drifted.V.row(i) = roll(u + d.x(), v + d.y(), R).transpose();
  }
  return s;
}

// Straight tube (radius r, length L along z, nu × nv) bent into a torus arc of centre-line radius
// Rb over the angle L / Rb: the outside stretches, the inside compresses. Drift is along the
// tube's (angle, length) parameters, windowed along the length only (the angle wraps around).
inline Scenario bent_tube(int nu, int nv, double r, double L, double Rb, double amplitude,
                          unsigned seed) {
  Scenario s;
  s.templ = make_cylinder(nu, nv, r, L);
  const double h = L / nv;
  SmoothField field(seed, amplitude * h, 2 * M_PI, L);
  field.window_u = false;
  for (auto& w : field.waves) w.ku = std::round(w.ku);  // periodic in the angle
  auto bend = [&](double theta, double z) {
    const double phi = z / Rb;  // centre-line angle
    const double rad = Rb + r * std::cos(theta);
    return Vec3(rad * std::cos(phi) - Rb, r * std::sin(theta), rad * std::sin(phi));
  };
  s.clean = s.templ;
  s.drifted = s.templ;
  for (int i = 0; i < s.templ.num_vertices(); ++i) {
    const double theta = std::atan2(s.templ.V(i, 1), s.templ.V(i, 0));
    const double z = s.templ.V(i, 2);
    s.clean.V.row(i) = bend(theta, z).transpose();
    const Eigen::Vector2d d = field(theta < 0 ? theta + 2 * M_PI : theta, z);
    s.drifted.V.row(i) = bend(theta + d.x() / r, z + d.y()).transpose();
  }
  return s;
}

}  // namespace sm::test
