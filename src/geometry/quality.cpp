#include "geometry/quality.hpp"

#include <algorithm>
#include <sstream>

#include "core/errors.hpp"

namespace sm {

Eigen::VectorXd radius_ratio(const TriMesh& mesh) {
  const int n = mesh.num_vertices();
  const int m = mesh.num_triangles();
  Eigen::VectorXd ratio(m);
  for (int t = 0; t < m; ++t) {
    for (int k = 0; k < 3; ++k)
      if (mesh.F(t, k) < 0 || mesh.F(t, k) >= n) {
        std::ostringstream msg;
        msg << "radius_ratio: triangle " << t << " refers to vertex " << mesh.F(t, k)
            << ", but the mesh has " << n << " vertices";
        throw InputError(msg.str());
      }
    const Vec3 p0 = mesh.vertex(mesh.F(t, 0)), p1 = mesh.vertex(mesh.F(t, 1)),
               p2 = mesh.vertex(mesh.F(t, 2));
    const double a = (p2 - p1).norm(), b = (p0 - p2).norm(), c = (p1 - p0).norm();
    const double denom = (a + b + c) * a * b * c;
    const double value = 4.0 * (p1 - p0).cross(p2 - p0).squaredNorm() / denom;
    // A zero edge (denominator 0) or a non-finite corner fails the test and counts as degenerate.
    ratio[t] = denom > 0.0 && value >= 0.0 ? std::min(value, 1.0) : 0.0;
  }
  return ratio;
}

QualitySummary summarize_quality(const Eigen::VectorXd& ratio) {
  QualitySummary s;
  if (ratio.size() == 0) return s;
  s.min = ratio.minCoeff();
  s.mean = ratio.mean();
  return s;
}

}  // namespace sm
