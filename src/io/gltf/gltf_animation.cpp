#include "io/gltf/gltf_animation.hpp"

#include <algorithm>
#include <cmath>

namespace sm {

Eigen::Quaterniond slerp_shortest(const Eigen::Quaterniond& q0, const Eigen::Quaterniond& q1,
                                  double u) {
  Eigen::Vector4d a = q0.coeffs(), b = q1.coeffs();
  double d = a.dot(b);
  if (d < 0) {
    b = -b;
    d = -d;
  }
  Eigen::Vector4d r;
  if (d > 1 - 1e-10) {
    // Angle below ~1.4e-5 rad: the chord and the arc agree to far below double precision needs.
    r = (1 - u) * a + u * b;
  } else {
    const double theta = std::acos(std::min(d, 1.0));
    const double s = std::sin(theta);
    r = (std::sin((1 - u) * theta) / s) * a + (std::sin(u * theta) / s) * b;
  }
  r.normalize();
  return Eigen::Quaterniond(r[3], r[0], r[1], r[2]);
}

namespace {

Eigen::Quaterniond quaternion_at(const std::vector<double>& v, size_t offset) {
  return Eigen::Quaterniond(v[offset + 3], v[offset], v[offset + 1], v[offset + 2]);
}

void normalize_quaternion(double* q) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (n > 0) {
    for (int c = 0; c < 4; ++c) q[c] /= n;
  }
}

}  // namespace

std::vector<double> sample_keyframes(const GltfKeyframes& keys, double t) {
  const size_t w = size_t(keys.width);
  const size_t n = keys.times.size();
  const bool cubic = keys.interpolation == GltfInterpolation::kCubicSpline;
  // Offset of keyframe k's value: cubic splines store (in-tangent, value, out-tangent) per key.
  const auto value_offset = [&](size_t k) { return cubic ? (3 * k + 1) * w : k * w; };
  std::vector<double> out(w);
  const auto copy_value = [&](size_t k) {
    std::copy_n(keys.values.begin() + std::ptrdiff_t(value_offset(k)), w, out.begin());
  };
  if (n == 0) return out;
  if (n == 1 || t <= keys.times.front()) {
    copy_value(0);
    return out;
  }
  if (t >= keys.times.back()) {
    copy_value(n - 1);
    return out;
  }
  // keys.times[k] <= t < keys.times[k + 1]
  const size_t k =
      size_t(std::upper_bound(keys.times.begin(), keys.times.end(), t) - keys.times.begin()) - 1;
  const double td = keys.times[k + 1] - keys.times[k];
  const double u = (t - keys.times[k]) / td;
  switch (keys.interpolation) {
    case GltfInterpolation::kStep:
      copy_value(k);
      break;
    case GltfInterpolation::kLinear:
      if (keys.rotation) {
        const Eigen::Quaterniond q =
            slerp_shortest(quaternion_at(keys.values, value_offset(k)),
                           quaternion_at(keys.values, value_offset(k + 1)), u);
        out = {q.x(), q.y(), q.z(), q.w()};
      } else {
        for (size_t c = 0; c < w; ++c) {
          out[c] =
              (1 - u) * keys.values[value_offset(k) + c] + u * keys.values[value_offset(k + 1) + c];
        }
      }
      break;
    case GltfInterpolation::kCubicSpline: {
      // p(u) = (2u³ - 3u² + 1) v_k + td (u³ - 2u² + u) b_k + (-2u³ + 3u²) v_k+1 + td (u³ - u²)
      // a_k+1
      const double u2 = u * u, u3 = u2 * u;
      const double h00 = 2 * u3 - 3 * u2 + 1, h10 = td * (u3 - 2 * u2 + u);
      const double h01 = -2 * u3 + 3 * u2, h11 = td * (u3 - u2);
      const size_t v0 = (3 * k + 1) * w, b0 = (3 * k + 2) * w;
      const size_t a1 = (3 * k + 3) * w, v1 = (3 * k + 4) * w;
      for (size_t c = 0; c < w; ++c) {
        out[c] = h00 * keys.values[v0 + c] + h10 * keys.values[b0 + c] + h01 * keys.values[v1 + c] +
                 h11 * keys.values[a1 + c];
      }
      if (keys.rotation) normalize_quaternion(out.data());
      break;
    }
  }
  return out;
}

}  // namespace sm
