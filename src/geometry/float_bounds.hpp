#pragma once
/// Conservative rounding of doubles to floats, for float bounding boxes that must contain the
/// double ones (the BVH's nodes, the triangle grid's boxes).
#include <cmath>
#include <limits>

namespace sm {

/// The largest float <= x (beyond the float range: -infinity below it, the largest float above).
inline float float_at_most(double x) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  constexpr float kMax = std::numeric_limits<float>::max();
  if (x > kMax) return kMax;
  if (!(x >= -kMax)) return -kInf;
  const float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -kInf) : f;
}

/// The smallest float >= x (beyond the float range: the lowest float below it, +infinity above).
inline float float_at_least(double x) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  constexpr float kMax = std::numeric_limits<float>::max();
  if (x < -kMax) return -kMax;
  if (!(x <= kMax)) return kInf;
  const float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, kInf) : f;
}

}  // namespace sm
