#include "massage/bicgstab.hpp"

namespace sm::krylov {

Col3 column_dots(const Positions& a, const Positions& b) {
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

double dot_all(const Positions& a, const Positions& b) {
  const double* x = a.data();
  const double* y = b.data();
  double s = 0.0;
  for (Eigen::Index p = 0; p < a.size(); ++p) s += x[p] * y[p];
  return s;
}

void axpy_columns(const Positions& a, const Col3& k, const Positions& b, Positions& out) {
  const Eigen::Index n = a.rows();
  out.resize(n, 3);
  const double* x = a.data();
  const double* y = b.data();
  double* o = out.data();
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) o[3 * i + c] = x[3 * i + c] + k[c] * y[3 * i + c];
}

void update_direction(const Positions& r, const Positions& v, const Col3& beta, const Col3& omega,
                      Positions& p) {
  double* pp = p.data();
  const double* rr = r.data();
  const double* vv = v.data();
  for (Eigen::Index i = 0; i < p.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      pp[3 * i + c] = rr[3 * i + c] + beta[c] * (pp[3 * i + c] - omega[c] * vv[3 * i + c]);
}

}  // namespace sm::krylov
