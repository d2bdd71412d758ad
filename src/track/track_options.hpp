#pragma once
/// The options of the tracker (track job, Python Tracker): the deformation graph, its non-rigid
/// ICP schedule, the tolerances that mark a frame `lost`, and recovery. Lengths are in mean edge
/// lengths of the template, angles in degrees. The config's "track" object maps onto it.
#include "core/enum_names.hpp"
#include "core/options_table.hpp"
#include "massage/massage_options.hpp"

namespace sm {

/// The robust weight of a correspondence at distance d for scale σ.
enum class RobustKind {
  Welsch,        ///< exp(−d² / 2σ²)
  GemanMcClure,  ///< (σ² / (σ² + d²))²
  None,          ///< 1
};
inline constexpr EnumName<RobustKind> kRobustKindNames[] = {
    {"welsch", RobustKind::Welsch},
    {"geman_mcclure", RobustKind::GemanMcClure},
    {"none", RobustKind::None}};

struct TrackOptions {
  double node_spacing = 4.0;  ///< "node_spacing": graph node radius, template edge lengths
  int node_influences = 6;    ///< "node_influences": nodes blended at a vertex, at most
  int stages = 3;             ///< "stages": coarse-to-fine stages of the fit
  int iterations = 8;         ///< "iterations": ICP iterations per stage, at most
  double small_motion = 0.0;  ///< "small_motion": near already: short coarse stages
  double regularizer = 0.3;   ///< "regularizer": the graph term's weight in the first stage
  double regularizer_final = 0.001;  ///< "regularizer_final": its weight in the last stage
  double point_weight = 0.1;        ///< "point_weight": point-to-point part beside point-to-plane
  RobustKind robust = RobustKind::Welsch;  ///< "robust"
  double robust_scale = 4.0;        ///< "robust_scale": σ of the first stage, halved per stage
  double robust_scale_final = 1.0;  ///< "robust_scale_final": σ is never below this
  double max_distance = 3.0;        ///< "max_distance": pruning at this times σ
  double max_normal_angle = 60.0;   ///< "max_normal_angle": pruning by normals, degrees
  int samples = 4000;               ///< "samples": correspondences per direction, at most
  bool extrapolate = true;          ///< "extrapolate": start from the last motion continued
  int refine_iterations = 15;       ///< "refine_iterations": Mesh Massage toward the raw frame
  bool project = false;             ///< "project": last, each vertex onto the raw frame
  double lost_distance = 0.2;       ///< "lost_distance": mean distance (both ways) beyond: lost
  double lost_distance_p99 = 3.0;   ///< "lost_distance_p99": 99th percentile beyond: lost
  double lost_folded_fraction = 0.01;  ///< "lost_folded_fraction": folded triangles beyond: lost
  bool recover = true;                 ///< "recover": re-register a frame beyond the tolerances
  double recover_scale = 4.0;          ///< "recover_scale": recovery's σ and pruning, times more
};

template <>
inline const Fields<TrackOptions>& fields_of<TrackOptions>() {
  using O = TrackOptions;
  static const Fields<TrackOptions> fields = {
      field<&O::node_spacing>("node_spacing", above(0),
                              "radius of the deformation graph's Poisson-disk node sampling, in "
                              "mean edge lengths of the template; each vertex follows the nodes "
                              "within twice this distance along the surface"),
      field<&O::node_influences>("node_influences", closed(1, 16),
                                 "nodes blended at a vertex, at most (the nearest)"),
      field<&O::stages>("stages", closed(1, 10),
                        "coarse-to-fine stages of the non-rigid ICP: the graph term's weight "
                        "goes from `regularizer` to `regularizer_final`, σ halves"),
      field<&O::iterations>("iterations", at_least(1),
                            "ICP iterations (closest points both ways, one Gauss-Newton solve) "
                            "per stage, at most; the last stage also takes what the earlier "
                            "stages left of their share"),
      field<&O::small_motion>("small_motion", at_least(0),
                              "when a frame's first correspondences lie closer than this on "
                              "average (mean edge lengths), its coarse stages take one "
                              "iteration each and the last stage the rest; 0: never "
                              "(docs/tracking.md: 0.75 on captures)"),
      field<&O::regularizer>("regularizer", above(0),
                             "weight of the graph's as-rigid-as-possible term in the first stage"),
      field<&O::regularizer_final>("regularizer_final", above(0),
                                   "weight of the graph term in the last stage"),
      field<&O::point_weight>("point_weight", closed(0, 1),
                              "weight of the point-to-point part of a correspondence beside the "
                              "point-to-plane part (1: point-to-point only)"),
      field<&O::robust>("robust", choice(kRobustKindNames),
                        "robust weight of a correspondence by its distance: Welsch, "
                        "Geman-McClure, or none"),
      field<&O::robust_scale>("robust_scale", above(0),
                              "σ of the robust weight in the first stage, in mean edge lengths; "
                              "halved each stage"),
      field<&O::robust_scale_final>("robust_scale_final", above(0),
                                    "σ never falls below this, in mean edge lengths"),
      field<&O::max_distance>("max_distance", above(0),
                              "correspondences farther than this times σ are pruned"),
      field<&O::max_normal_angle>("max_normal_angle", closed(0, 180),
                                  "correspondences whose normals differ by more than this "
                                  "(degrees) are pruned"),
      field<&O::samples>("samples", at_least(16),
                         "correspondences per direction (template → frame, frame → template) "
                         "and iteration, at most"),
      field<&O::extrapolate>("extrapolate", any_value(),
                             "start each frame from the previous one's fit continued by its "
                             "motion (else from the previous fit)"),
      field<&O::refine_iterations>("refine_iterations", at_least(0),
                                   "Mesh Massage iterations toward the raw frame after the "
                                   "registration (T = template, N = frame); 0: registration only"),
      field<&O::project>("project", any_value(),
                         "last, move every vertex to its closest point on the raw frame (after "
                         "the refinement), so that the result lies on the captured surface"),
      field<&O::lost_distance>("lost_distance", above(0),
                               "a frame whose mean distance to the raw frame, or the raw frame's "
                               "to it, exceeds this (mean edge lengths) is `lost`"),
      field<&O::lost_distance_p99>("lost_distance_p99", above(0),
                                   "likewise for the 99th percentile of either distance"),
      field<&O::lost_folded_fraction>("lost_folded_fraction", closed(0, 1),
                                      "likewise for the fraction of folded triangles"),
      field<&O::recover>("recover", any_value(),
                         "re-register a frame beyond the tolerances: from the last good frame "
                         "with a wider search, then from the template rigidly aligned"),
      field<&O::recover_scale>("recover_scale", at_least(1),
                               "the recovery's σ and pruning distance, times the first stage's"),
  };
  return fields;
}

/// The refinement's Mesh Massage options by default (track job, Python Tracker): the massage
/// defaults without Lawson's reweighting. Lawson's weights approximate the Hausdorff distance, so
/// the refinement evens the distances out instead of lowering them: on the untracked dancer
/// (9 frames) the tracked → raw mean is 0.114 edges with them and 0.021 without, and on the
/// remeshed samba the error against the truth 0.350 with them and 0.325 without.
inline MassageOptions refinement_massage_options() {
  MassageOptions o;
  o.lawson = false;
  return o;
}

}  // namespace sm
