#pragma once
/// The options of the Metro-style distances (distance.hpp, distance_meter.hpp) with their config
/// keys (the sequence job's "measures", the mesh jobs' measures), and the statistics they return:
/// a low header, which the distance meter and the sample budget include.
#include "core/options_table.hpp"

namespace sm {

/// The defaults are the uniform sampling of the mesh jobs; the sequence job's "measures" (the
/// table below, without corresponding_triangles, which the job sets) default to adaptive sampling
/// at spacing 0.125 (default_sequence_measures in pipeline/sequence/sequence_options.hpp).
struct DistanceOptions {
  /// Target spacing of the samples on A, as a fraction of A's mean edge length (> 0). The default
  /// gives about 8 samples per triangle on a regular mesh (Metro's default is 10 per face).
  double spacing = 0.25;
  bool sample_edges = true;  ///< points along every edge, at most `spacing` apart
  bool sample_faces = true;  ///< points inside every triangle, on a barycentric lattice
  /// Adaptive sampling. A coarse pass samples every vertex and every centroid of A; mean and RMS
  /// are the integrals of d and d² over A's area by the rule of degree 2 on each triangle
  /// (1/12 of the area at each corner, 3/4 at the centroid). Then the triangles whose samples
  /// reach `refine_above` times the largest sample are sampled at twice `spacing`, and those
  /// whose samples then reach sqrt(refine_above) times the largest so far at `spacing` (all
  /// three edges and the lattice, as above); the maximum is taken over every sample
  /// (DistanceStats::samples counts them all). Every sample's distance is exact, and the triangles
  /// refined depend on those distances alone, so the result does not depend on the number of
  /// threads either. Off: every triangle is sampled at `spacing`; mean and RMS are those of the
  /// samples.
  bool adaptive = false;
  /// In [0, 1]: with `adaptive`, the fraction of the largest sample that a triangle's samples
  /// must reach for it to be refined (0: every triangle with a nonzero distance). The default is
  /// the largest value that still finds the finest uniform sampling's maximum on captured
  /// sequences (bench_sequence measures it).
  double refine_above = 0.4;
  /// A's triangle t and B's triangle t are the same triangle moved (a frame and its corrected
  /// output share their connectivity): the first sample of A's triangle t tries B's triangle t
  /// first (the others, as always, the previous sample's closest triangle; with `adaptive`, a
  /// vertex tries the first triangle using it, a centroid its own triangle). Only where the
  /// search starts: the distances stay exact.
  bool corresponding_triangles = false;
};

template <>
inline const Fields<DistanceOptions>& fields_of<DistanceOptions>() {
  using O = DistanceOptions;
  static const Fields<O> fields = {
      field<&O::spacing>("spacing", above(0),
                         "samples along the edges and inside the triangles at most this far "
                         "apart, in mean edge lengths of the sampled frame (with `adaptive`: in "
                         "the triangles near the maximum)"),
      field<&O::sample_edges>("sample_edges", any_value(),
                              "sample along every edge (with `adaptive`: of the refined "
                              "triangles)"),
      field<&O::sample_faces>("sample_faces", any_value(),
                              "sample inside every triangle, a barycentric lattice (with "
                              "`adaptive`: of the refined triangles)"),
      field<&O::adaptive>("adaptive", any_value(),
                          "adaptive sampling: every vertex and centroid first (RMS: "
                          "area-weighted integral over the frame), then only the triangles near "
                          "the maximum at twice `spacing` and at `spacing`; `false`: every "
                          "triangle at `spacing`, RMS of the samples"),
      field<&O::refine_above>("refine_above", closed(0, 1),
                              "with `adaptive`: a triangle is sampled at twice `spacing` when "
                              "its samples reach this fraction of the largest sample, and at "
                              "`spacing` when they then reach its square root (0: every "
                              "triangle with a nonzero distance)"),
  };
  return fields;
}

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
