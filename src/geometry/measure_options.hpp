#pragma once
/// The options of the paper's measures of a mesh (measures.hpp); their config keys, the
/// single-mesh jobs' "measures": measure_keys.hpp.
#include <cmath>
#include <vector>

namespace sm {

/// "measures" of the single-mesh jobs: how the report measures the meshes (paper Tables 1–3).
struct MeasureOptions {
  double spacing = 0.25;        ///< Metro-style sample spacing, in mean edge lengths
  bool adaptive = false;        ///< DistanceOptions::adaptive (false: the paper's uniform samples)
  double feature_angle = 30.0;  ///< dihedral angle (degrees) above which an edge of N is sharp
  /// Increasing bin edges of the shear histogram (eq. 8); a last edge "inf" (infinity) counts the
  /// degenerate triangles too.
  std::vector<double> shear_bins = {0.0, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, INFINITY};
};

}  // namespace sm
