#pragma once
/// Preconditioned BiCGSTAB (van der Vorst 1992) on A X = R with X, R n×3: the one Krylov loop of
/// K X = R (linear_solver.hpp, eq. 7) and of the coupled (K ⊗ I₃ − D) X = R (coupled_solver.hpp).
/// Templated on the operator (A.apply(X, Y): Y = A X), the preconditioner (M.apply(R, Z):
/// Z = M⁻¹ R) and on how the scalars α, β, ρ, ω are shared among the three columns
/// (ColumnScalars, SharedScalars). Column c stops at ‖R − A X‖ <= tolerance · scale[c].
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "mesh/mesh.hpp"

namespace sm {

struct SolveStats {
  bool ok = false;
  int iterations = 0;
  double residual = 0.0;  ///< max over the columns of ‖R − A X‖ / scale[c] (‖R‖ by default)
  std::string message;    ///< why it failed, when !ok
};

/// Scratch vectors of the loop, kept between calls so iterations allocate nothing.
struct BicgstabWorkspace {
  Positions r, rhat, p, v, y, s, z, t;
};

/// The loop's kernels on n×3 row-major arrays, one pass each; inline, so that each loop gets
/// them specialized (an x·x dot product reads x once).
namespace krylov {

/// One value per column (x, y, z).
using Col3 = Eigen::Array<double, 1, 3>;

/// Per-column dot products aᵀb.
inline Col3 column_dots(const Positions& a, const Positions& b) {
  const double* x = a.data();
  const double* y = b.data();
  double s0 = 0.0, s1 = 0.0, s2 = 0.0;
  const Eigen::Index n = a.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    s0 += x[3 * i] * y[3 * i];
    s1 += x[3 * i + 1] * y[3 * i + 1];
    s2 += x[3 * i + 2] * y[3 * i + 2];
  }
  return Col3(s0, s1, s2);
}

/// The dot product of a and b as 3n-vectors, summed in storage order.
inline double dot_all(const Positions& a, const Positions& b) {
  const double* x = a.data();
  const double* y = b.data();
  double s = 0.0;
  for (Eigen::Index p = 0; p < a.size(); ++p) s += x[p] * y[p];
  return s;
}

/// out = a + k ⊙ b, k one scalar per column (out may be a).
inline void axpy_columns(const Positions& a, const Col3& k, const Positions& b, Positions& out) {
  const Eigen::Index n = a.rows();
  out.resize(n, 3);
  const double* x = a.data();
  const double* y = b.data();
  double* o = out.data();
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) o[3 * i + c] = x[3 * i + c] + k[c] * y[3 * i + c];
}

/// out = a + k b, one scalar for all 3n entries (out may be a).
inline void axpy_all(const Positions& a, double k, const Positions& b, Positions& out) {
  out.resize(a.rows(), 3);
  const double* x = a.data();
  const double* y = b.data();
  double* o = out.data();
  for (Eigen::Index p = 0; p < a.size(); ++p) o[p] = x[p] + k * y[p];
}

/// p = r + β (p − ω v), per column.
inline void update_direction(const Positions& r, const Positions& v, const Col3& beta,
                             const Col3& omega, Positions& p) {
  double* pp = p.data();
  const double* rr = r.data();
  const double* vv = v.data();
  for (Eigen::Index i = 0; i < p.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      pp[3 * i + c] = rr[3 * i + c] + beta[c] * (pp[3 * i + c] - omega[c] * vv[3 * i + c]);
}

/// p = r + β (p − ω v), one β and ω for all 3n entries.
inline void update_direction_all(const Positions& r, const Positions& v, double beta, double omega,
                                 Positions& p) {
  double* pp = p.data();
  const double* rr = r.data();
  const double* vv = v.data();
  for (Eigen::Index q = 0; q < p.size(); ++q) pp[q] = rr[q] + beta * (pp[q] - omega * vv[q]);
}

}  // namespace krylov

/// Three independent solves that share A (the columns of K X = R): each column has its own
/// scalars and stopping test; a converged column keeps its X (its step sizes are 0 from then on,
/// it takes no part in the breakdown tests) and the stabilizing half-step runs only for the
/// columns still above their target.
struct ColumnScalars {
  static krylov::Col3 dot(const Positions& a, const Positions& b) {
    return krylov::column_dots(a, b);
  }
  static void axpy(const Positions& a, const krylov::Col3& k, const Positions& b, Positions& out) {
    krylov::axpy_columns(a, k, b, out);
  }
  static void update_direction(const Positions& r, const Positions& v, const krylov::Col3& beta,
                               const krylov::Col3& omega, Positions& p) {
    krylov::update_direction(r, v, beta, omega, p);
  }
  /// Marks the columns at their target, for good; true when all are.
  static bool converged(const krylov::Col3& res, const krylov::Col3& target,
                        std::array<bool, 3>& done) {
    for (int c = 0; c < 3; ++c) done[c] = done[c] || res[c] <= target[c];
    return done[0] && done[1] && done[2];
  }
  /// 1 for the columns that need the stabilizing half-step, given ‖s‖ per column.
  static krylov::Col3 half_step(const krylov::Col3& s_norm, const krylov::Col3& target,
                                const std::array<bool, 3>& done) {
    krylov::Col3 second = krylov::Col3::Zero();
    for (int c = 0; c < 3; ++c)
      if (!done[c] && s_norm[c] > target[c]) second[c] = 1.0;
    return second;
  }
  static bool finite(const krylov::Col3& res) { return res.isFinite().all(); }
};

/// One solve on the 3n-vector (columns coupled by D): one set of scalars from dot products over
/// all 3n entries (copied to the three columns), all columns at their target at once to stop
/// (no column is ever marked done), and the half-step for all columns or none.
struct SharedScalars {
  static krylov::Col3 dot(const Positions& a, const Positions& b) {
    return krylov::Col3::Constant(krylov::dot_all(a, b));
  }
  // The three scalars are equal: one flat pass over the 3n entries.
  static void axpy(const Positions& a, const krylov::Col3& k, const Positions& b, Positions& out) {
    krylov::axpy_all(a, k[0], b, out);
  }
  static void update_direction(const Positions& r, const Positions& v, const krylov::Col3& beta,
                               const krylov::Col3& omega, Positions& p) {
    krylov::update_direction_all(r, v, beta[0], omega[0], p);
  }
  static bool at_target(const krylov::Col3& res, const krylov::Col3& target) {
    return res[0] <= target[0] && res[1] <= target[1] && res[2] <= target[2];
  }
  static bool converged(const krylov::Col3& res, const krylov::Col3& target,
                        std::array<bool, 3>& /*done*/) {
    return at_target(res, target);
  }
  static krylov::Col3 half_step(const krylov::Col3& s_norm, const krylov::Col3& target,
                                const std::array<bool, 3>& /*done*/) {
    return at_target(s_norm, target) ? krylov::Col3::Zero() : krylov::Col3::Ones();
  }
  static bool finite(const krylov::Col3& res) { return std::isfinite(res[0] + res[1] + res[2]); }
};

/// BiCGSTAB from the guess in X, preconditioned by M, at most `max_iterations` iterations.
/// `scale[c]` (positive; 1 where it is not) sets column c's target tolerance · scale[c].
template <class Scalars, class Operator, class Preconditioner>
SolveStats bicgstab_loop(const Operator& A, const Preconditioner& M, const Positions& R,
                         Positions& X, double tolerance, int max_iterations, BicgstabWorkspace& w,
                         const std::array<double, 3>& scale) {
  using krylov::Col3;
  using krylov::column_dots;
  SolveStats st;
  Positions &r = w.r, &rhat = w.rhat, &p = w.p, &v = w.v, &y = w.y, &s = w.s;
  A.apply(X, r);
  r = R - r;
  rhat = r;
  p.setZero(R.rows(), 3);
  v.setZero(R.rows(), 3);
  Col3 target;
  for (int c = 0; c < 3; ++c) target[c] = tolerance * (scale[c] > 0.0 ? scale[c] : 1.0);
  Col3 rho = Col3::Ones(), alpha = Col3::Ones(), omega = Col3::Ones();
  Col3 res = column_dots(r, r).sqrt();
  std::array<bool, 3> done{};
  auto finish = [&](bool ok, const char* why) {
    st.ok = ok;
    st.message = why;
    for (int c = 0; c < 3; ++c)
      st.residual = std::max(st.residual, res[c] / (target[c] / tolerance));
    return st;
  };
  if (Scalars::converged(res, target, done)) return finish(true, "");
  for (st.iterations = 1; st.iterations <= max_iterations; ++st.iterations) {
    const Col3 rho_new = Scalars::dot(rhat, r);
    Col3 beta = Col3::Zero();
    for (int c = 0; c < 3; ++c) {
      if (done[c]) continue;
      if (rho_new[c] == 0.0 || omega[c] == 0.0)
        return finish(false, "BiCGSTAB breakdown (rho or omega is 0)");
      beta[c] = (rho_new[c] / rho[c]) * (alpha[c] / omega[c]);
    }
    rho = rho_new;
    Scalars::update_direction(r, v, beta, omega, p);
    M.apply(p, y);
    A.apply(y, v);
    const Col3 rv = Scalars::dot(rhat, v);
    Col3 step = Col3::Zero();
    for (int c = 0; c < 3; ++c) {
      if (done[c]) continue;
      if (rv[c] == 0.0) return finish(false, "BiCGSTAB breakdown (r̂·v is 0)");
      alpha[c] = rho[c] / rv[c];
      step[c] = alpha[c];
    }
    Scalars::axpy(r, -step, v, s);  // s = r − α v
    Scalars::axpy(X, step, y, X);   // X += α y
    const Col3 s_norm = column_dots(s, s).sqrt();
    const Col3 second = Scalars::half_step(s_norm, target, done);
    if ((second == 0.0).all()) {
      for (int c = 0; c < 3; ++c)
        if (!done[c]) res[c] = s_norm[c];
      r.swap(s);
    } else {
      // The stabilizing half-step: z = M⁻¹ s, t = A z, ω = t·s / t·t (0 where t is 0),
      // X += ω z, r = s − ω t, for the columns in `second` (ω = 0 for the others).
      M.apply(s, w.z);
      A.apply(w.z, w.t);
      const Col3 ts = Scalars::dot(w.t, s), tt = Scalars::dot(w.t, w.t);
      Col3 om = Col3::Zero();
      for (int c = 0; c < 3; ++c) {
        if (second[c] == 0.0) continue;
        omega[c] = tt[c] > 0.0 ? ts[c] / tt[c] : 0.0;
        om[c] = omega[c];
      }
      Scalars::axpy(X, om, w.z, X);   // X += ω z
      Scalars::axpy(s, -om, w.t, r);  // r = s − ω t
      const Col3 rn = column_dots(r, r).sqrt();
      for (int c = 0; c < 3; ++c)
        if (!done[c]) res[c] = second[c] != 0.0 ? rn[c] : s_norm[c];
    }
    if (!Scalars::finite(res)) return finish(false, "BiCGSTAB produced a non-finite residual");
    if (Scalars::converged(res, target, done)) return finish(true, "");
  }
  st.iterations = max_iterations;
  return finish(false, "BiCGSTAB did not reach the tolerance");
}

}  // namespace sm
