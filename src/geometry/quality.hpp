#pragma once
/// Radius ratio of every triangle, the shape quality of the paper's Table 3.
#include <Eigen/Core>

#include "mesh/mesh.hpp"

namespace sm {

/// Radius ratio 2r/R of every triangle of `mesh` (m values in [0, 1]): r the inradius, R the
/// circumradius; 1 for an equilateral triangle, 0 for a degenerate one (or non-finite corners).
/// With edge lengths a, b, c and n = (p1 − p0) × (p2 − p0):
///
///     2r/R = 16 A² / ((a + b + c) a b c) = 4 |n|² / ((a + b + c) a b c)
///
/// Throws InputError if a triangle refers to a missing vertex.
Eigen::VectorXd radius_ratio(const TriMesh& mesh);

struct QualitySummary {
  double min = 0.0;  ///< worst triangle
  double mean = 0.0;
};

/// Minimum and mean of per-triangle ratios; both zero for an empty vector.
QualitySummary summarize_quality(const Eigen::VectorXd& ratio);

}  // namespace sm
