#pragma once
/// How many samples one_sided_distance takes on a mesh, counted in floating point before any is
/// taken, and the budget every spacing must keep: the sampling density is bounded by the input.
#include <cmath>
#include <string>

#include "geometry/distance_options.hpp"
#include "geometry/distance_layout.hpp"
#include "mesh/mesh.hpp"

namespace sm {

/// Bounds on the subdivisions of one edge and one triangle, so that a single huge triangle in a
/// finely meshed model cannot ask for billions of samples.
inline constexpr long kMaxEdgeSegments = 1 << 20;
inline constexpr long kMaxFaceDivisions = 1 << 12;

/// The samples one sampling of a mesh may take: 50 million, or 100 per triangle of the sampled
/// mesh when that is more (the defaults take about 8 per triangle uniformly, at most about 55 per
/// triangle adaptively on a regular mesh). A spacing of 1e-9 took 166 s on 98 triangles.
inline constexpr double kDistanceSampleBudget = 50e6;
inline constexpr double kDistanceSamplesPerTriangle = 100;

/// ceil(length / h) clamped to [1, cap], computed in floating point: length / h may be far beyond
/// any integer (a spacing of 1e-30 overflowed the conversion to an integer). 1 when h is not
/// positive or the quotient is NaN.
inline long sample_divisions(double length, double h, long cap) {
  if (!(h > 0.0)) return 1;
  const double n = std::ceil(length / h);
  if (!(n > 1.0)) return 1;
  return n >= double(cap) ? cap : static_cast<long>(n);
}

/// The samples one_sided_distance(A, ·, options) takes on A, whose sampling layout is `layout`,
/// in floating point; with options.adaptive, the most it can take (every triangle refined at both
/// levels). Linear in A's size; takes no sample.
double distance_sample_count(const TriMesh& A, const DistanceLayout& layout,
                             const DistanceOptions& options);

/// The budget for a mesh of `triangles` triangles: max(kDistanceSampleBudget,
/// kDistanceSamplesPerTriangle × triangles).
double distance_sample_budget(long triangles);

/// Throws OptionError, key "spacing", "S would take [up to] N samples on <what> (M triangles),
/// more than the budget of B (...)" when `samples` exceeds the budget of `triangles` (the jobs
/// name it "measures.spacing").
void check_sample_budget(double samples, long triangles, double spacing, bool up_to,
                         const std::string& what);

/// distance_sample_count checked against the budget of A's triangles (above). `what` names A.
void check_distance_samples(const TriMesh& A, const DistanceLayout& layout,
                            const DistanceOptions& options, const std::string& what);
/// The same with A's own layout.
void check_distance_samples(const TriMesh& A, const DistanceOptions& options,
                            const std::string& what);

}  // namespace sm
