#include "massage/massage_keys.hpp"

namespace sm {
namespace {

/// The paper's method: the shape term, the outer iterations, the distance term's weights (§2).
Fields<MassageOptions> method() {
  using O = MassageOptions;
  return {
      field<&O::weights>("weights", choice(kWeightKindNames),
                         "the weights λ of eq. 1 (§2.1), computed once on T: mean value "
                         "coordinates keep T's triangle shapes, uniform weights even the "
                         "triangles out"),
      field<&O::boundary_weights>("boundary_weights", choice(kBoundaryWeightsNames),
                                  "boundary vertices: 1-D weights over their two boundary "
                                  "neighbours, by edge length (reproduces a straight boundary), "
                                  "or Floater's formula on the triangles present (pulls open "
                                  "boundaries inwards)"),
      field<&O::shape_target>("shape_target", choice(kShapeTargetKindNames),
                              "the right-hand side δ of the shape system A v = δ (eq. 6): "
                              "`\"zero\"` is the paper's δ = 0; `\"template\"` is T's own "
                              "Laplacian turned ring by ring into the start frame, so that a "
                              "frame with T's triangle shapes is left as it is. Smoothing needs "
                              "`\"zero\"`: its T is M itself"),
      field<&O::iterations>("iterations", at_least(1),
                            "outer iterations (solve, closest points, Lawson update); the paper "
                            "finds 10 to 15 enough (§2.3)"),
      field<&O::mu>("mu", auto_or(right_open(0, 1)),
                    "μ of eq. 7, the weight of triangle shape against distance; `\"auto\"`: "
                    "‖B‖_F / (3‖A‖_F + ‖B‖_F), the paper's choice, every iteration"),
      field<&O::samples>("samples", choice(kSampleKindNames),
                         "the samples w_j of N in the distance term (eq. 4): N's vertices; also "
                         "every edge midpoint (`\"edges\"`); also every triangle centroid "
                         "(`\"faces\"`)"),
      field<&O::tolerance>("tolerance", at_least(0),
                           "stop before `iterations` when no vertex moved more than this times "
                           "M's mean edge length in an iteration"),
      field<&O::lawson>("lawson", any_value(),
                        "Lawson's reweighting of α, β after each iteration (eq. 5), which turns "
                        "the 2-norm into an approximation of the Hausdorff distance; `false` "
                        "keeps them at 1 (eq. 3)"),
      field<&O::lawson_floor>("lawson_floor", open(0, 1),
                              "α, β are normalized by their joint mean and kept at least this "
                              "times it, so B stays definite"),
  };
}

/// How each iteration solves and finds its closest points.
Fields<MassageOptions> numerics() {
  using O = MassageOptions;
  return {
      field<&O::solver>("solver", choice(kSolverKindNames),
                        "`\"iterative\"`: BiCGSTAB with ILU(0) on the fixed pattern, "
                        "warm-started, sparse LU as fall-back; `\"direct\"`: sparse LU every "
                        "iteration"),
      field<&O::solver_tolerance>("solver_tolerance", open(0, 1),
                                  "relative residual ‖R − K X‖ / ‖R‖ (each column) at which "
                                  "BiCGSTAB stops; a looser value costs the outer iterations "
                                  "accuracy"),
      field<&O::solver_max_iterations>("solver_max_iterations", at_least(1),
                                       "BiCGSTAB iterations before the LU fall-back"),
      field<&O::closest_points>("closest_points", choice(kClosestPointModeNames),
                                "`\"local\"`: walk from the previous correspondence over "
                                "adjacent triangles (§2.2.1), exact BVH query as fall-back; "
                                "`\"exact\"`: a BVH query for every point in every iteration"),
      field<&O::walk_max_steps>("walk_max_steps", at_least(0),
                                "moves of the local walk before the exact query"),
  };
}

/// Beyond the paper: pinned vertices, the point-to-plane term, per-vertex weights.
Fields<MassageOptions> extensions() {
  using O = MassageOptions;
  return {
      field<&O::pin_boundary>("pin_boundary", any_value(),
                              "boundary vertices of M keep their position exactly"),
      field<&O::pinned>("pinned", indices("vertex indices"),
                        "0-based vertex indices of M that keep their position exactly, below "
                        "M's vertex count (for glTF input: of the welded vertices)"),
      field<&O::distance_term>("distance_term", choice(kDistanceTermNames),
                               "vertex i's distance term (eq. 4): `\"point\"` α‖v − v̂‖², the "
                               "paper's; `\"plane\"` α[(n·(v − v̂))² + ε‖tangential part‖²] "
                               "with n N's normal at v̂ (point-to-plane, as in ICP: M slides "
                               "along N, boundary vertices stay point-to-point). Same stationary "
                               "points, reached faster along the surface; couples x, y, z (a "
                               "3n × 3n system on A's pattern)"),
      field<&O::tangential_stiffness>("tangential_stiffness", left_open(0, 1),
                                      "ε of the `\"plane\"` term: the weight of the part of "
                                      "v − v̂ along N against the part off it (1: `\"point\"`)"),
      field<&O::tangential_adapt>("tangential_adapt", at_least(0),
                                  "with `\"plane\"`: ε_i = min(1, tangential_stiffness + this × "
                                  "|log area ratio| between the template and the start around "
                                  "vertex i, smoothed over a few rings), stiff where the surface "
                                  "stretches, soft where it bends isometrically; 0: ε everywhere"),
      field<&O::tangential_smoothing>("tangential_smoothing", closed(0, 1000),
                                      "passes of 1-ring averaging of the log area ratio before "
                                      "`tangential_adapt` applies: more average out a wider "
                                      "tangential drift, fewer keep a stretch local"),
      field<&O::vertex_weights_file>(
          "vertex_weights", any_value(),
          "per-vertex weights in [0, 1], one per vertex of M (for glTF input: of the welded "
          "vertices): a text file of numbers separated by blanks or line breaks, or "
          "`\"file.ply#name\"`, the scalar vertex property `name` of a PLY file. 1 is the "
          "default behaviour, 0 keeps the vertex at its input position (like `pinned`), values "
          "between blend the vertex's shape equation (eq. 6) with \"stay at the input\" "
          "(docs/method-vertex-weights.md)"),
  };
}

}  // namespace

template <>
const Fields<MassageOptions>& fields_of<MassageOptions>() {
  static const Fields<MassageOptions> fields = concat_fields(
      {method(), numerics(), extensions()});
  return fields;
}

}  // namespace sm
