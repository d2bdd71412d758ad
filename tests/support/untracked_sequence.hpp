#pragma once
// Untracked sequences with known truth: an analytic deforming surface S(u, v, time), sampled
// every frame by its own random triangulation of the parameter domain (a grid with a random
// offset, jittered interior vertices and random diagonals), so no two frames share a vertex.
// The truth of a template vertex with parameters (u, v) at frame k is S(u, v, k).
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "mesh/mesh.hpp"

namespace sm::test {

struct Surface {
  std::function<Vec3(double u, double v, double time)> at;
  double u_length = 1, v_length = 1;
  bool v_periodic = false;
};

struct SampledFrame {
  TriMesh mesh;
  std::vector<Eigen::Vector2d> params;  // (u, v) of each vertex
};

// A random triangulation of the surface's domain with about `cell` spacing in parameter space.
inline SampledFrame sample_surface(const Surface& s, double time, double cell, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int nu = std::max(2, static_cast<int>(std::round(s.u_length / cell)));
  const int nv = std::max(s.v_periodic ? 3 : 2, static_cast<int>(std::round(s.v_length / cell)));
  const double du = s.u_length / nu, dv = s.v_length / nv;
  const double ou = 0.2 + 0.6 * unit(random), ov = unit(random);
  // Rows along u: 0, the shifted interior rows, u_length; columns along v likewise (periodic:
  // nv shifted columns).
  std::vector<double> rows = {0.0};
  for (int i = 0; i + ou < nu - 0.2; ++i) rows.push_back((i + ou) * du);
  rows.push_back(s.u_length);
  std::vector<double> cols;
  if (s.v_periodic) {
    for (int j = 0; j < nv; ++j) cols.push_back((j + ov) * dv);
  } else {
    const double ov2 = 0.2 + 0.6 * ov;
    cols.push_back(0.0);
    for (int j = 0; j + ov2 < nv - 0.2; ++j) cols.push_back((j + ov2) * dv);
    cols.push_back(s.v_length);
  }
  const int R = static_cast<int>(rows.size()), C = static_cast<int>(cols.size());
  SampledFrame f;
  f.mesh.V.resize(R * C, 3);
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j) {
      double u = rows[i], v = cols[j];
      const bool u_edge = i == 0 || i == R - 1;
      const bool v_edge = !s.v_periodic && (j == 0 || j == C - 1);
      if (!u_edge) u += (unit(random) - 0.5) * 0.4 * du;
      if (!v_edge) v += (unit(random) - 0.5) * 0.4 * dv;
      if (s.v_periodic) v = std::fmod(v + s.v_length, s.v_length);
      f.params.push_back({u, v});
      f.mesh.V.row(i * C + j) = s.at(u, v, time).transpose();
    }
  const int quads_v = s.v_periodic ? C : C - 1;
  f.mesh.F.resize(2 * (R - 1) * quads_v, 3);
  int t = 0;
  for (int i = 0; i + 1 < R; ++i)
    for (int j = 0; j < quads_v; ++j) {
      const int j1 = (j + 1) % C;
      const int a = i * C + j, b = (i + 1) * C + j, c = (i + 1) * C + j1, d = i * C + j1;
      if (unit(random) < 0.5) {
        f.mesh.F.row(t++) << a, b, c;
        f.mesh.F.row(t++) << a, c, d;
      } else {
        f.mesh.F.row(t++) << a, b, d;
        f.mesh.F.row(t++) << b, c, d;
      }
    }
  return f;
}

// A rigid motion per frame: `speed` units along a fixed direction, and a slow turn.
inline Vec3 carried(const Vec3& p, double time, double speed, double turn) {
  const double a = turn * time;
  const Vec3 q(std::cos(a) * p.x() - std::sin(a) * p.y(), std::sin(a) * p.x() + std::cos(a) * p.y(),
               p.z());
  return q + speed * time * Vec3(0.8, 0.6, 0.0);
}

// Centre line in the xy-plane with tangent angle phi(u): positions by Simpson's rule.
inline Vec3 centre_line(const std::function<double(double)>& phi, double u) {
  const int n = 48;
  const double h = u / n;
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k <= n; ++k) {
    const double w = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
    const double a = phi(k * h);
    sum += w * Vec3(std::cos(a), std::sin(a), 0);
  }
  return sum * h / 3.0;
}

// The radius of a tube, with bumps so that sliding along it or turning about it shows (a
// round tube's truth would be ambiguous).
inline double bumpy_radius(double r, double u, double v) {
  return r * (1.0 + 0.2 * std::cos(2 * v) + 0.15 * std::sin(1.5 * u + v) + 0.1 * std::sin(0.9 * u));
}

// A tube of radius r around a centre line bending (curvature bend·sin) and twisting over time.
inline Surface bending_tube(double speed, double turn, double bend = 0.25, double twist = 1.2) {
  Surface s;
  s.u_length = 8.0;
  s.v_length = 2 * M_PI;
  s.v_periodic = true;
  s.at = [=](double u, double v, double time) {
    const double kappa = bend * std::sin(0.15 * time);
    auto phi = [&](double x) { return kappa * x; };
    const double a = phi(u), w = v + twist * std::sin(0.1 * time) * u / 8.0;
    const Vec3 n1(-std::sin(a), std::cos(a), 0), n2(0, 0, 1);
    const Vec3 p = centre_line(phi, u) + bumpy_radius(1.0, u, v) * (std::cos(w) * n1 + std::sin(w) * n2);
    return carried(p, time, speed, turn);
  };
  return s;
}

// A limb: two straight segments of a tube joined at u = 5, bending there by up to 100 degrees.
inline Surface bending_limb(double speed, double turn, double rate = 0.12) {
  Surface s;
  s.u_length = 10.0;
  s.v_length = 2 * M_PI;
  s.v_periodic = true;
  s.at = [=](double u, double v, double time) {
    const double theta = 1.75 * 0.5 * (1 - std::cos(rate * time));
    auto phi = [&](double x) {
      const double y = std::clamp((x - 5.0 + 1.2) / 2.4, 0.0, 1.0);
      return theta * y * y * (3 - 2 * y);
    };
    const double a = phi(u);
    const Vec3 n1(-std::sin(a), std::cos(a), 0), n2(0, 0, 1);
    const Vec3 p = centre_line(phi, u) + bumpy_radius(0.8, u, v) * (std::cos(v) * n1 + std::sin(v) * n2);
    return carried(p, time, speed, turn);
  };
  return s;
}

// A sheet 10 × 4 rolling up along u (up to 0.8 of a turn) while it moves.
inline Surface rolling_sheet(double speed, double turn, double rate = 0.1) {
  Surface s;
  s.u_length = 10.0;
  s.v_length = 4.0;
  s.at = [=](double u, double v, double time) {
    const double kappa = 0.8 * 2 * M_PI / 10.0 * 0.5 * (1 - std::cos(rate * time)) + 1e-9;
    // Bumps along the sheet's normal give it features to hold on to.
    const double f = 0.3 * std::sin(1.3 * u) * std::cos(1.6 * v) + 0.15 * std::sin(0.7 * u + 2.1 * v);
    const Vec3 normal(-std::sin(kappa * u), 0, std::cos(kappa * u));
    const Vec3 p = Vec3(std::sin(kappa * u) / kappa, v, (1 - std::cos(kappa * u)) / kappa) + f * normal;
    return carried(p, time, speed, turn);
  };
  return s;
}

}  // namespace sm::test
