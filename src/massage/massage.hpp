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
/// The options: massage_options.hpp; their config keys (the "massage" object): massage_keys.hpp.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geometry/weights.hpp"
#include "massage/massage_options.hpp"
#include "massage/massage_result.hpp"
#include "massage/reference.hpp"
#include "mesh/topology.hpp"

namespace sm {

struct MassagerState;

/// Everything that depends only on the template T and the connectivity of M: the weights, A,
/// the fixed sparsity pattern of K and its symbolic analysis, M's topology. Build once, then call
/// run() for any number of (start, reference) pairs, from any number of threads at once.
/// Internally everything is relabelled in banded order (mesh/reorder.hpp, for the caches and
/// ILU(0)); every argument, result and accessor uses the caller's labels.
class Massager {
 public:
  /// Throws InputError (naming `name`) if T has out-of-range indices, non-finite coordinates or
  /// no triangle; OptionError naming the member ("pinned", "vertex_weights[3]") for out-of-range
  /// options (callers that know the config path wrap it: with_option_path). Degenerate template corners fall back to
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
