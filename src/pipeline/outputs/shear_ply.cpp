#include "pipeline/outputs/shear_ply.hpp"

#include <algorithm>
#include <cmath>

#include "io/ply.hpp"
#include "core/errors.hpp"

namespace sm {

std::array<uint8_t, 3> scale_color(double t) {
  if (std::isnan(t)) t = 1.0;
  t = std::clamp(t, 0.0, 1.0);
  const int segment = std::min(3, static_cast<int>(std::floor(4.0 * t)));
  const double f = 4.0 * t - segment;
  double r = 0, g = 0, b = 0;
  switch (segment) {
    case 0:  // blue -> cyan
      r = 0, g = f, b = 1;
      break;
    case 1:  // cyan -> green
      r = 0, g = 1, b = 1 - f;
      break;
    case 2:  // green -> yellow
      r = f, g = 1, b = 0;
      break;
    default:  // yellow -> red
      r = 1, g = 1 - f, b = 0;
      break;
  }
  const auto byte = [](double x) { return static_cast<uint8_t>(std::lround(255.0 * x)); };
  return {byte(r), byte(g), byte(b)};
}

double shear_scale_position(double shear, double max) {
  if (!std::isfinite(shear)) return 1.0;
  return std::clamp(shear / max, 0.0, 1.0);
}

std::array<uint8_t, 3> shear_color(double shear, double max) {
  return scale_color(shear_scale_position(shear, max));
}

std::string format_shear_ply(const Positions& V, const Triangles& F, const Eigen::VectorXd& shear,
                             double max, ShearColorMode mode) {
  const Eigen::Index m = F.rows();
  if (shear.size() != m)
    throw InputError("shear colours: " + std::to_string(shear.size()) + " values for " +
                     std::to_string(m) + " triangles");
  if (!(max > 0.0)) throw InputError("shear colours: the maximum must be > 0");
  PlyColors colors;
  colors.face.reserve(size_t(m));
  for (Eigen::Index t = 0; t < m; ++t) colors.face.push_back(shear_color(shear[t], max));

  if (mode == ShearColorMode::Faces) {
    TriMesh split{Positions(3 * m, 3), Triangles(m, 3)};
    colors.vertex.reserve(size_t(3 * m));
    for (Eigen::Index t = 0; t < m; ++t) {
      for (int k = 0; k < 3; ++k) {
        const int v = F(t, k);
        if (v < 0 || v >= V.rows())
          throw InputError("shear colours: triangle " + std::to_string(t) +
                           " refers to a missing vertex");
        split.V.row(3 * t + k) = V.row(v);
        split.F(t, k) = int(3 * t + k);
        colors.vertex.push_back(colors.face[size_t(t)]);
      }
    }
    return format_ply(split, &colors, true);
  }

  const TriMesh mesh{V, F};
  validate_mesh(mesh, "shear colours");
  std::vector<double> sum(size_t(V.rows()), 0.0);
  std::vector<int> count(size_t(V.rows()), 0);
  for (Eigen::Index t = 0; t < m; ++t) {
    const double position = shear_scale_position(shear[t], max);
    for (int k = 0; k < 3; ++k) {
      sum[size_t(F(t, k))] += position;
      ++count[size_t(F(t, k))];
    }
  }
  colors.vertex.reserve(size_t(V.rows()));
  for (size_t v = 0; v < sum.size(); ++v)
    colors.vertex.push_back(scale_color(count[v] > 0 ? sum[v] / count[v] : 0.0));
  return format_ply(mesh, &colors, true);
}

}  // namespace sm
