#pragma once
/// Convex combination weights λ_ij of every vertex over its neighbours (paper eq. 1), computed on
/// a template mesh T, and the shape matrix A = I − Λ of eq. 6.
#include <Eigen/SparseCore>

#include "core/enum_names.hpp"
#include "mesh/mesh.hpp"

namespace sm {

/// Row-major sparse matrix: row i holds vertex i's equation, the layout the solvers use.
using SparseMatrixR = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

enum class WeightKind {
  MeanValue,  ///< Floater's mean value coordinates: positive, reproduce planar one-rings
  Uniform,    ///< 1/valence: equalizes triangles (the paper's smoothing, §4)
};
inline constexpr EnumName<WeightKind> kWeightKindNames[] = {{"mean_value", WeightKind::MeanValue},
                                                            {"uniform", WeightKind::Uniform}};

/// How vertices on a boundary loop are weighted.
enum class BoundaryWeights {
  /// Floater's formula restricted to the triangles present (a boundary edge has one triangle and
  /// one term). Its average lies well inside the mesh (0.6 edge lengths on a regular grid), so
  /// the shape term pulls open boundaries inwards and only the distance term holds them.
  OneSided,
  /// 1-D barycentric weights over the two boundary neighbours (by edge length), 0 for the others:
  /// reproduces a straight boundary exactly, like mean value weights reproduce a planar one-ring,
  /// so the boundary keeps the template's spacing along itself.
  Curve,
};
inline constexpr EnumName<BoundaryWeights> kBoundaryWeightsNames[] = {
    {"curve", BoundaryWeights::Curve}, {"one_sided", BoundaryWeights::OneSided}};

struct ShapeWeights {
  /// Λ, n×n: row i holds λ_ij ≥ 0 over i's neighbours j, summing to 1 (an isolated vertex has an
  /// empty row).
  SparseMatrixR lambda;
  /// Vertices whose template corners were degenerate (zero-length edge, zero-area triangle) and
  /// that fell back to uniform weights (mean value weights only).
  int fallback_vertices = 0;
};

/// Weights over the neighbours of every vertex of `templ`. Mean value weights (Floater 2003):
/// w_ij = Σ over the (one or two) triangles holding edge (i, j) of tan(θ_i/2) / |t_j − t_i|, θ_i the
/// triangle's angle at t_i, with tan(θ/2) = |e1×e2| / (|e1||e2| + e1·e2) (no trig calls, stable);
/// λ_ij = w_ij / Σ_k w_ik. Works on any triangle list, manifold or not, with or without boundary.
/// `boundary` chooses the weights of vertices on a boundary loop (manifold boundaries only: a
/// vertex with other than two boundary neighbours keeps the one-sided weights).
ShapeWeights compute_weights(const TriMesh& templ, WeightKind kind,
                             BoundaryWeights boundary = BoundaryWeights::Curve);

/// A = I − Λ (n×n, not symmetric), with an explicit diagonal entry in every row; a vertex with no
/// neighbours gets an all-zero row (it has no shape to keep).
SparseMatrixR shape_matrix(const ShapeWeights& weights);

}  // namespace sm
