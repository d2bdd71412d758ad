#include "geometry/shear.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/errors.hpp"

namespace sm {
namespace {

constexpr double kDegenerateRatio = 1e-14;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Triangle (p0, p1, p2) in its own orthonormal frame: p0 at the origin, p1 at (l, 0), p2 at
// (x, y) with y ≥ 0. ok is false for a degenerate or non-finite triangle.
struct Frame2d {
  double l = 0.0, x = 0.0, y = 0.0;
  bool ok = false;
};

Frame2d planar_frame(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const Vec3 e = p1 - p0, f = p2 - p0;
  const double cross = e.cross(f).norm();
  const double longest2 = std::max({e.squaredNorm(), f.squaredNorm(), (p2 - p1).squaredNorm()});
  Frame2d frame;
  if (!(cross > kDegenerateRatio * longest2) || !std::isfinite(longest2)) return frame;
  frame.l = e.norm();
  frame.x = f.dot(e) / frame.l;
  frame.y = cross / frame.l;
  frame.ok = true;
  return frame;
}

// σ + 1/σ − 2 without cancellation near σ = 1.
double excess(double sigma) {
  return (sigma - 1.0) * (sigma - 1.0) / sigma;
}

double triangle_distortion(const Frame2d& t, const Frame2d& q) {
  if (!t.ok || !q.ok) return kInfinity;
  // J · [t1 t2] = [q1 q2] with both layouts upper triangular, so J = [[a, b], [0, d]].
  const double a = q.l / t.l;
  const double d = q.y / t.y;
  const double b = (q.x - a * t.x) / t.y;
  // Closed-form singular values of a 2×2 matrix; σ2 = det / σ1 keeps the small one accurate.
  const double sigma1 = 0.5 * (std::hypot(a + d, b) + std::hypot(a - d, b));
  const double sigma2 = (a * d) / sigma1;
  return std::max(excess(sigma1), excess(sigma2));
}

}  // namespace

Eigen::VectorXd shear_distortion(const Positions& templ_V, const Positions& V, const Triangles& F) {
  if (templ_V.rows() != V.rows()) {
    std::ostringstream msg;
    msg << "shear_distortion: the template has " << templ_V.rows() << " vertices, the mesh "
        << V.rows();
    throw InputError(msg.str());
  }
  const int n = static_cast<int>(V.rows());
  const int m = static_cast<int>(F.rows());
  for (int t = 0; t < m; ++t)
    for (int k = 0; k < 3; ++k)
      if (F(t, k) < 0 || F(t, k) >= n) {
        std::ostringstream msg;
        msg << "shear_distortion: triangle " << t << " refers to vertex " << F(t, k)
            << ", but the mesh has " << n << " vertices";
        throw InputError(msg.str());
      }
  Eigen::VectorXd D(m);
  tbb::parallel_for(tbb::blocked_range<int>(0, m, 4096), [&](const tbb::blocked_range<int>& r) {
    for (int t = r.begin(); t != r.end(); ++t) {
      auto corner = [&](const Positions& P, int k) -> Vec3 { return P.row(F(t, k)).transpose(); };
      D[t] = triangle_distortion(
          planar_frame(corner(templ_V, 0), corner(templ_V, 1), corner(templ_V, 2)),
          planar_frame(corner(V, 0), corner(V, 1), corner(V, 2)));
    }
  });
  return D;
}

DistortionSummary summarize_distortion(const Eigen::VectorXd& distortion) {
  DistortionSummary s;
  std::vector<double> finite;
  finite.reserve(distortion.size());
  for (Eigen::Index i = 0; i < distortion.size(); ++i) {
    if (std::isfinite(distortion[i]))
      finite.push_back(distortion[i]);
    else
      ++s.infinite;
  }
  if (s.infinite > 0) s.max = kInfinity;
  if (finite.empty()) return s;
  double sum = 0.0;
  for (double d : finite) {
    sum += d;
    if (s.infinite == 0) s.max = std::max(s.max, d);
  }
  s.mean = sum / static_cast<double>(finite.size());
  const size_t rank = static_cast<size_t>(std::ceil(0.95 * static_cast<double>(finite.size())));
  const auto nth = finite.begin() + static_cast<std::ptrdiff_t>(std::max<size_t>(rank, 1) - 1);
  std::nth_element(finite.begin(), nth, finite.end());
  s.p95 = *nth;
  return s;
}

std::vector<int> histogram(const Eigen::VectorXd& values, const std::vector<double>& edges) {
  if (edges.size() < 2) throw InputError("histogram: at least two bin edges are needed");
  for (size_t i = 1; i < edges.size(); ++i)
    if (!(edges[i] > edges[i - 1])) {
      std::ostringstream msg;
      msg << "histogram: bin edges must increase strictly, but edge " << i << " is " << edges[i]
          << " after " << edges[i - 1];
      throw InputError(msg.str());
    }
  std::vector<int> counts(edges.size() - 1, 0);
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    const double x = values[i];
    if (!(x >= edges.front() && x <= edges.back())) continue;
    // upper_bound finds the first edge above x; x == edges.back() falls into the last bin.
    const size_t bin =
        static_cast<size_t>(std::upper_bound(edges.begin(), edges.end(), x) - edges.begin());
    ++counts[std::min(bin, counts.size()) - 1];
  }
  return counts;
}

}  // namespace sm
