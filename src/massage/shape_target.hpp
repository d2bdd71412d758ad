#pragma once
/// The right-hand side δ of the shape system A v = δ (the paper's eq. 6 has δ = 0): the template's
/// own mean value Laplacian, turned ring by ring into the frame being optimized.
///
/// On a curved template, (A T)_i = t_i − Σ_j λ_ij t_j has a tangential component (mean value
/// weights reproduce planar one-rings only), so with δ = 0 neither T itself, nor a rigid copy of
/// it, nor a frame with its shapes is a fixed point of eq. 7: the optimizer drifts them. With
///   δ_i = R_i (A T)_i                                                              (n×3)
/// eq. 7 becomes (μA + (1−μ)B) v = μδ + (1−μ)c, and a start frame S whose one-rings are congruent
/// to T's satisfies A S = δ exactly and stays where it is. R_i, the rotation of vertex i's ring
/// from T to S, is estimated in closed form: T's area-weighted vertex normal onto S's, then the
/// twist about it that best aligns the ring's edges projected into the tangent planes (a 2-D
/// Kabsch fit with weights λ_ij; any tangent frames, the fit absorbs their choice).
///
/// δ is computed once per run, from the start S (N's copy in a sequence). A tangential drift of S
/// perturbs mainly the twist, which turns only the tangential part of (A T)_i, small already (it
/// vanishes on planar rings); the normal part, |(A T)_i · n|, is T's and does not depend on the
/// drift. Estimating R_i from the iterates, taking the normal part from S, or turning each
/// triangle by its own rotation would all let the target follow the drift; δ = 0 (the smooth
/// job's target) would pull every vertex to its neighbours' weighted mean and flatten detail.
///
/// Consistency: on a closed class C of Λ (rows that reference only C: a boundary loop with curve
/// weights, a small component), A's block is singular with left null vector π (πᵀ Λ_CC = πᵀ), so
/// A v = δ can hold there only if Σ_C π_i δ_i = 0. Turning every ring by its own R_i breaks that
/// slightly, and the remainder pulls the whole class along against the distance term alone (on
/// the horse, a three-vertex hole slid by half an edge and crushed the triangles around it). So δ
/// is made consistent on every closed class of at most kMaxProjectedClass vertices by subtracting
/// Σ_C π_i δ_i; for a congruent frame (δ = A S) this changes nothing. Larger classes (a whole
/// closed surface) are left alone: π costs a sparse LU there, and the remainder is small (crane
/// frames: |Σ π δ| ≤ 2e-3 mean edge lengths; with or without it the results agree to 1%).
#include <vector>

#include "geometry/weights.hpp"
#include "core/enum_names.hpp"
#include "mesh/mesh.hpp"
#include "mesh/topology.hpp"

namespace sm {

/// Which right-hand side the shape system A v = δ has.
enum class ShapeTargetKind {
  Zero,      ///< δ = 0, the paper's eq. 6
  Template,  ///< δ_i = R_i (A T)_i, T's Laplacian turned ring by ring into the start frame
};
inline constexpr EnumName<ShapeTargetKind> kShapeTargetKindNames[] = {
    {"zero", ShapeTargetKind::Zero}, {"template", ShapeTargetKind::Template}};

/// The per-template part of the rotated target: built once per template, then evaluate() per run.
class ShapeTarget {
 public:
  /// Closed classes of Λ up to this size are made consistent (see above).
  static constexpr int kMaxProjectedClass = 4096;

  ShapeTarget() = default;
  /// templ: T; lambda: Λ computed on T (n×n, compressed, the rows of A = I − Λ); topology: T's
  /// connectivity.
  ShapeTarget(const TriMesh& templ, const SparseMatrixR& lambda, const Topology& topology);

  bool empty() const { return verts_.empty(); }
  /// Closed classes of Λ that evaluate() makes consistent.
  int projected_classes() const { return static_cast<int>(classes_.size()); }

  /// δ (n×3) for a run starting at `start` (T's connectivity; lambda and topology as given to
  /// the constructor). Vertices whose normal is undefined in T or in `start` (no area around
  /// them) get δ_i = 0, the paper's target; their number is returned. Parallel over vertices, the
  /// same bits for any thread count.
  int evaluate(const Positions& start, const Triangles& F, const SparseMatrixR& lambda,
               const Topology& topology, Positions& delta) const;

 private:
  struct Vertex {
    bool has_normal;     ///< T's area-weighted normal n is defined (else δ_i = 0)
    double tangent[2];   ///< (A T)_i along a unit tangent u and along n × u
    double normal_part;  ///< (A T)_i along the normal
  };
  std::vector<Vertex> verts_;
  /// Per entry of Λ (in its storage order): λ_ij (t_j − t_i) in i's tangent frame (u, normal × u).
  std::vector<double> edges_;  ///< nnz×2
  /// The closed classes of Λ that are made consistent: sorted vertices and π.
  struct Class {
    std::vector<int> vertices;
    std::vector<double> pi;
  };
  std::vector<Class> classes_;
};

}  // namespace sm
