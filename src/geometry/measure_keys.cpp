#include "geometry/measure_keys.hpp"

namespace sm {

template <>
const Fields<MeasureOptions>& fields_of<MeasureOptions>() {
  using O = MeasureOptions;
  static const Fields<O> fields = {
      field<&O::spacing>("spacing", above(0),
                         "Metro-style sample spacing along edges and inside triangles, in mean "
                         "edge lengths of the sampled mesh"),
      field<&O::adaptive>("adaptive", any_value(),
                          "as the sequence job's `measures.adaptive`: vertices and centroids "
                          "first, then only the triangles near the maximum at twice `spacing` "
                          "and at `spacing` (mean and RMS: area integrals); `false`: every "
                          "triangle at `spacing`, as the paper's Tables"),
      field<&O::feature_angle>("feature_angle", open(0, 180),
                               "an edge of N whose two triangles' normals differ by more than "
                               "this many degrees is a sharp (feature) edge, measured in "
                               "`measures.csv`"),
      field<&O::shear_bins>("shear_bins", any_value(),
                            "bin edges of the shear histogram (eq. 8), one "
                            "`shear_hist_<lower edge>` column per bin; a last edge `\"inf\"` also "
                            "counts degenerate triangles"),
  };
  return fields;
}

}  // namespace sm
