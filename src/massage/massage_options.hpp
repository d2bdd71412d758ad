#pragma once
/// The options of the Mesh Massage optimizer (massage.hpp), with their defaults. Each member is
/// one key of the config's "massage" object; what the key means, its range and its name are in
/// the table beside it (massage_keys.hpp), which the JSON reader, the reference and the Python
/// keys read.
#include <filesystem>
#include <optional>
#include <vector>

#include "geometry/weights.hpp"
#include "massage/reference.hpp"
#include "massage/shape_target.hpp"

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

/// Every tunable of the optimizer; the JSON config's "massage" object maps onto it one-to-one.
struct MassageOptions {
  WeightKind weights = WeightKind::MeanValue;          ///< λ of eq. 1, computed on T
  BoundaryWeights boundary_weights = BoundaryWeights::Curve;  ///< boundary vertices' λ
  ShapeTargetKind shape_target = ShapeTargetKind::Template;  ///< δ of A v = δ (eq. 6)
  int iterations = 15;                        ///< outer iterations, >= 1
  std::optional<double> mu;                   ///< μ of eq. 7; empty: "auto"
  SampleKind samples = SampleKind::Vertices;  ///< the samples w_j of N (eq. 4)
  double tolerance = 1e-4;     ///< early stop: largest move / M's mean edge length
  bool lawson = true;          ///< update α, β by eq. 5 after each iteration
  double lawson_floor = 1e-8;  ///< α, β kept >= this times their mean
  SolverKind solver = SolverKind::Iterative;  ///< the linear solver of eq. 7
  double solver_tolerance = 1e-8;             ///< BiCGSTAB's relative residual
  int solver_max_iterations = 300;            ///< BiCGSTAB iterations before the LU fall-back
  ClosestPointMode closest_points = ClosestPointMode::Local;  ///< local walk or exact query
  int walk_max_steps = 16;    ///< local walk moves before the exact query
  bool pin_boundary = false;  ///< boundary vertices of M keep their position
  std::vector<int> pinned;    ///< vertex indices of M that keep their position
  DistanceTerm distance_term = DistanceTerm::Point;  ///< point or point-to-plane (eq. 4)
  double tangential_stiffness = 0.2;  ///< ε of the plane term, (0, 1]
  double tangential_adapt = 5.0;      ///< ε's rise with the area change around a vertex
  int tangential_smoothing = 12;      ///< 1-ring passes over the area change
  /// "vertex_weights": the file the jobs read `vertex_weights` from; the Massager reads only the
  /// vector.
  std::filesystem::path vertex_weights_file;
  /// Per-vertex weights w_i in [0, 1], one per vertex of M in the caller's labels, or empty (all
  /// 1). Row i of the shape system becomes w_i (A v − δ)_i + (1 − w_i)(v_i − p_i) = 0, p_i the
  /// start position; w_i = 0 pins vertex i (docs/method-vertex-weights.md). Not a config key:
  /// the jobs fill it from `vertex_weights_file`, code (bindings) sets it directly.
  std::vector<double> vertex_weights;
};

}  // namespace sm
