#pragma once
/// glTF 2.0 animation samplers evaluated as the specification says (Appendix C): STEP, LINEAR
/// (normalized spherical interpolation for rotations) and CUBICSPLINE (Hermite, tangents scaled by
/// the keyframe interval).
#include <Eigen/Geometry>
#include <vector>

namespace sm {

enum class GltfInterpolation { kStep, kLinear, kCubicSpline };

/// One sampler's keyframes. Per keyframe, `values` holds `width` numbers (3 for translation and
/// scale, 4 for a rotation quaternion x, y, z, w, the morph target count for weights); with
/// CUBICSPLINE it holds three groups per keyframe: in-tangent, value, out-tangent.
struct GltfKeyframes {
  std::vector<double> times;  ///< strictly increasing seconds
  std::vector<double> values;
  int width = 0;
  GltfInterpolation interpolation = GltfInterpolation::kLinear;
  bool rotation = false;  ///< unit quaternions: slerp between keys and unit-length results
};

/// Value at time `t` (`width` numbers). Before the first keyframe and after the last one the
/// first and last values hold (a single keyframe is a constant).
std::vector<double> sample_keyframes(const GltfKeyframes& keys, double t);

/// Spherical linear interpolation from q0 (u = 0) to q1 (u = 1) along the shorter arc (q1 is
/// negated when q0·q1 < 0), normalized; exact for unit inputs at any angle.
Eigen::Quaterniond slerp_shortest(const Eigen::Quaterniond& q0, const Eigen::Quaterniond& q1,
                                  double u);

}  // namespace sm
