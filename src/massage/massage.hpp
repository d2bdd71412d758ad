#pragma once
/// The Mesh Massage optimizer (paper §2): moves the vertices of M so that its triangles take the
/// shapes of a template T (eq. 1, 6) while it stays close to a reference surface N (eq. 4), by
/// iterating the combined solve (eq. 7) with Lawson's reweighting (eq. 5).
///
/// Per iteration k, with M's positions v (n×3):
///   K = μA + (1−μ)B,  K v = μδ + (1−μ)c                                     (eq. 7)
///   A = I − Λ (n×n, not symmetric, fixed), shape target A v = δ               (eq. 6)
///   B = Σ_i α_i e_i e_iᵀ + Σ_j β_j b_j b_jᵀ,  c = Σ_i α_i v̂_i + Σ_j β_j b_j w_j  (eq. 4)
/// where v̂_i is the closest point of N to v_i, and b_j (n-vector, three non-zeros) holds the
/// barycentric coordinates of the closest point of M to the sample w_j; δ = 0 as in the paper, or
/// T's Laplacian turned into the start frame (shape_target.hpp), fixed for the run. The sparsity of
/// K is A's (with its diagonal) for every iteration, frame and reference: it is analysed once.
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geometry/weights.hpp"
#include "massage/reference.hpp"
#include "massage/shape_target.hpp"
#include "core/options_table.hpp"
#include "mesh/topology.hpp"

namespace sm {

enum class SolverKind {
  Iterative,  ///< BiCGSTAB with an ILU(0) preconditioner on the fixed pattern, warm-started
  Direct,     ///< sparse LU, refactored every iteration (robust, slower)
};

enum class ClosestPointMode {
  Local,  ///< walk from the previous correspondence (§2.2.1), exact BVH query as fall-back
  Exact,  ///< exact BVH query for every point in every iteration
};

/// The distance term of vertex i of M (eq. 4's α-part).
enum class DistanceTerm {
  Point,  ///< α_i ‖v_i − v̂_i‖², the paper's: as stiff along the surface as off it
  Plane,  ///< α_i [(nᵀ(v_i − v̂_i))² + ε_i ‖tangential part‖²], soft along N (plane_term.hpp)
};
inline constexpr EnumName<DistanceTerm> kDistanceTermNames[] = {{"point", DistanceTerm::Point},
                                                                {"plane", DistanceTerm::Plane}};

/// Every tunable of the optimizer; the JSON config's "massage" object maps onto it one-to-one
/// (key names in quotes).
struct MassageOptions {
  WeightKind weights = WeightKind::MeanValue;  ///< "weights": "mean_value" | "uniform"
  /// "boundary_weights": "curve" (1-D weights along boundary loops) | "one_sided" (Floater's
  /// formula on the triangles present, which pulls open boundaries inwards; see weights.hpp)
  BoundaryWeights boundary_weights = BoundaryWeights::Curve;
  /// "shape_target": the right-hand side δ of the shape system A v = δ: "template" (T's own
  /// Laplacian turned ring by ring into the start, so frames with T's shapes are fixed points; see
  /// shape_target.hpp) or "zero" (the paper's eq. 6; the smooth job's default).
  ShapeTargetKind shape_target = ShapeTargetKind::Template;
  int iterations = 15;                        ///< "iterations": outer iterations, >= 1
  std::optional<double> mu;                   ///< "mu": "auto" (empty) or a value in [0, 1)
  SampleKind samples = SampleKind::Vertices;  ///< "samples": samples w_j of N
  /// "tolerance": stop early when no vertex moved more than this times M's mean edge length.
  double tolerance = 1e-4;
  bool lawson = true;          ///< "lawson": update α, β by eq. 5 after each iteration
  double lawson_floor = 1e-8;  ///< "lawson_floor": α, β kept >= this times their mean
  SolverKind solver = SolverKind::Iterative;  ///< "solver": "iterative" | "direct"
  double solver_tolerance = 1e-8;             ///< "solver_tolerance": relative residual
  int solver_max_iterations = 300;            ///< "solver_max_iterations"
  ClosestPointMode closest_points = ClosestPointMode::Local;  ///< "closest_points"
  int walk_max_steps = 16;    ///< "walk_max_steps": local search moves before the exact query
  bool pin_boundary = false;  ///< "pin_boundary": boundary vertices of M keep their position
  std::vector<int> pinned;    ///< "pinned": vertex indices of M that keep their position
  DistanceTerm distance_term = DistanceTerm::Point;  ///< "distance_term": "point" | "plane"
  double tangential_stiffness = 0.2;  ///< "tangential_stiffness": ε of the plane term, (0, 1]
  double tangential_adapt = 5.0;      ///< "tangential_adapt": ε's rise with the area change
  int tangential_smoothing = 12;  ///< "tangential_smoothing": 1-ring passes over the area change
  /// "vertex_weights": a file of per-vertex weights (a text file of numbers, or "file.ply#name",
  /// a scalar vertex property of a PLY file), read by the jobs into `vertex_weights`; the
  /// Massager itself reads only the vector.
  std::filesystem::path vertex_weights_file;
  /// Per-vertex weights w_i in [0, 1], one per vertex of M in the caller's labels, or empty (all
  /// 1). Row i of the shape system becomes w_i (A v − δ)_i + (1 − w_i)(v_i − p_i) = 0, p_i the
  /// start position; w_i = 0 pins vertex i (docs/method-vertex-weights.md). Not a config key:
  /// the jobs fill it from `vertex_weights_file`, code (bindings) sets it directly.
  std::vector<double> vertex_weights;
};

inline constexpr EnumName<SolverKind> kSolverKindNames[] = {{"iterative", SolverKind::Iterative},
                                                            {"direct", SolverKind::Direct}};
inline constexpr EnumName<ClosestPointMode> kClosestPointModeNames[] = {
    {"local", ClosestPointMode::Local}, {"exact", ClosestPointMode::Exact}};

namespace massage_fields {

/// The paper's method: the shape term, the outer iterations, the distance term's weights (§2).
inline Fields<MassageOptions> method() {
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
inline Fields<MassageOptions> numerics() {
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
inline Fields<MassageOptions> extensions() {
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

}  // namespace massage_fields

template <>
inline const Fields<MassageOptions>& fields_of<MassageOptions>() {
  static const Fields<MassageOptions> fields = concat_fields(
      {massage_fields::method(), massage_fields::numerics(), massage_fields::extensions()});
  return fields;
}

/// What one outer iteration did (all distances in model units).
struct IterationStats {
  int iteration = 0;
  double mu = 0.0;
  double energy = 0.0;  ///< μ‖Av − δ‖² + (1−μ)·(weighted distances, eq. 4), after solve
  double max_dist_m_to_n = 0.0;  ///< max_i |v_i − v̂_i| (after the solve)
  double rms_dist_m_to_n = 0.0;
  double max_dist_n_to_m = 0.0;  ///< max_j |w_j − ŵ_j|
  double rms_dist_n_to_m = 0.0;
  double max_move = 0.0;  ///< largest vertex displacement of this iteration
  int solver_iterations = 0;
  double solver_residual = 0.0;   ///< relative residual reached
  int exact_queries = 0;          ///< closest-point queries that needed the exact (BVH) search
  double seconds_closest = 0.0;   ///< closest points both ways, BVH refit
  double seconds_assemble = 0.0;  ///< B, c, K, preconditioner or factorization
  double seconds_solve = 0.0;
};

struct MassageResult {
  Positions V;  ///< optimized positions of M (n×3)
  std::vector<IterationStats> iterations;
  bool ok = true;              ///< false: numerical failure, see `failure`; V is then the start
  std::string failure;         ///< why the run failed (solver breakdown, NaN, ...)
  bool stopped_early = false;  ///< the movement tolerance was met before the last iteration
  int folded_triangles = 0;    ///< triangles whose normal opposes N's at their centroid
  /// With shape_target "template": vertices whose normal is undefined in T or in the start (no
  /// area around them), which keep the paper's target δ_i = 0.
  int target_fallback_vertices = 0;
  double seconds = 0.0;
};

/// Sees each outer iteration as it ends: its figures and M's positions then (n×3, the caller's
/// labels; valid during the call). Not called for an iteration that fails.
using IterationObserver = std::function<void(const IterationStats& stats, const Positions& V)>;

struct MassagerState;

/// Everything that depends only on the template T and the connectivity of M: the weights, A,
/// the fixed sparsity pattern of K and its symbolic analysis, M's topology. Build once, then call
/// run() for any number of (start, reference) pairs, from any number of threads at once.
/// Internally everything is relabelled in banded order (mesh/reorder.hpp, for the caches and
/// ILU(0)); every argument, result and accessor uses the caller's labels.
class Massager {
 public:
  /// Throws InputError (naming `name`) if T has out-of-range indices, non-finite coordinates or
  /// no triangle; ConfigError for out-of-range options. Degenerate template corners fall back to
  /// uniform weights (weights().fallback_vertices counts them). Vertices in no triangle are
  /// pinned: they keep their start position and take no part in the distance energy.
  Massager(const TriMesh& templ, MassageOptions options, const char* name = "template");
  ~Massager();
  Massager(Massager&&) noexcept;
  Massager& operator=(Massager&&) noexcept;

  /// Optimizes M, starting at `start` (n×3, the template's connectivity), against `reference`.
  /// Numerical failures are reported in the result (ok = false), never thrown. `observer`, if
  /// given, is called after every iteration (from the calling thread); the iterates are the
  /// same with or without it.
  MassageResult run(const Positions& start, const Reference& reference,
                    const IterationObserver& observer = {}) const;

  const MassageOptions& options() const;
  const Topology& topology() const;
  std::shared_ptr<const Topology> shared_topology() const;
  const ShapeWeights& weights() const;
  const Triangles& triangles() const;
  int num_vertices() const;
  /// The BVH of the template's triangles: run() refits a copy of it to M instead of building one,
  /// and a Reference with the same connectivity may do the same (Reference's `tree`).
  const TriangleBvh& template_bvh() const;

 private:
  std::unique_ptr<MassagerState> impl_;
};

}  // namespace sm
