#pragma once
/// The options of the Metro-style distances (distance.hpp, distance_meter.hpp) and the statistics
/// they return: a low header, which the distance meter and the sample budget include. Their
/// config keys (the sequence job's "measures"): distance_keys.hpp.

namespace sm {

/// The defaults are the uniform sampling of the mesh jobs; the sequence job's "measures" default
/// to adaptive sampling at spacing 0.125 (default_sequence_measures in
/// pipeline/sequence/sequence_options.hpp). The keys: distance_keys.hpp.
struct DistanceOptions {
  double spacing = 0.25;      ///< sample spacing on A, in A's mean edge lengths (> 0)
  bool sample_edges = true;   ///< points along every edge, at most `spacing` apart
  bool sample_faces = true;   ///< points inside every triangle, on a barycentric lattice
  bool adaptive = false;      ///< coarse pass, then refine near the maximum (distance.hpp)
  double refine_above = 0.4;  ///< with `adaptive`: the fraction of the maximum that refines, [0, 1]
  /// A's triangle t and B's triangle t are one triangle moved: where the search starts only.
  bool corresponding_triangles = false;
};

/// Distances from the samples on A to B. The relative values are divided by the diagonal of the
/// bounding box of both meshes' vertices together (as Metro does), so the two directions of a
/// pair share one scale; they are 0 when that diagonal is 0.
struct DistanceStats {
  double max = 0.0, mean = 0.0, rms = 0.0;
  double max_rel = 0.0, mean_rel = 0.0, rms_rel = 0.0;
  long samples = 0;
  long refined = 0;  ///< with DistanceOptions::adaptive, the triangles sampled at `spacing`
};

}  // namespace sm
