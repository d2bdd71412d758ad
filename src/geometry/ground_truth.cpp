#include "geometry/ground_truth.hpp"

#include <algorithm>
#include <cmath>

namespace sm {

CorrespondenceError correspondence_error(const Positions& V, const TriMesh& truth, double unit) {
  const Positions normals = vertex_normals(truth);
  CorrespondenceError e;
  const int n = truth.num_vertices();
  for (int i = 0; i < n; ++i) {
    const Vec3 d = (V.row(i) - truth.V.row(i)).transpose() / unit;
    const double normal = std::abs(normals.row(i).dot(d));
    const double all = d.norm();
    const double tangential = std::sqrt(std::max(0.0, all * all - normal * normal));
    e.mean += all;
    e.tangential_mean += tangential;
    e.normal_mean += normal;
    e.max = std::max(e.max, all);
    e.tangential_max = std::max(e.tangential_max, tangential);
    e.normal_max = std::max(e.normal_max, normal);
  }
  if (n > 0) {
    e.mean /= n;
    e.tangential_mean /= n;
    e.normal_mean /= n;
  }
  return e;
}

}  // namespace sm
