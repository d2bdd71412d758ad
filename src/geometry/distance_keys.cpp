#include "geometry/distance_keys.hpp"

namespace sm {

template <>
const Fields<DistanceOptions>& fields_of<DistanceOptions>() {
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

}  // namespace sm
