#pragma once
/// What a Massager keeps from its template (internal to the massage module): built once by the
/// Massager's constructor, read by every run (massage_run.hpp).
///
/// Runs work on the template's vertices and triangles relabelled in a banded order
/// (mesh/reorder.hpp), for the caches and ILU(0); the interface (accessors, run's start and
/// result) keeps the caller's labels. `F`, `topology`, `bvh`, `lambda`, `pattern`, `target`, the
/// flags and edges are in the internal order; `*_in` are the caller's.
#include <array>
#include <memory>
#include <vector>

#include "geometry/bvh.hpp"
#include "geometry/weights.hpp"
#include "massage/massage_options.hpp"
#include "massage/massage_result.hpp"
#include "massage/reference.hpp"
#include "massage/shape_target.hpp"
#include "massage/system.hpp"
#include "mesh/reorder.hpp"
#include "mesh/topology.hpp"

namespace sm {

struct MassagerState {
  MassageOptions options;
  MeshOrder order;
  Triangles F, F_in;
  std::shared_ptr<const Topology> topology, topology_in;
  ShapeWeights weights;  // the caller's labels (weights())
  SparseMatrixR lambda;  // Λ relabelled
  Positions templ;       // T's positions relabelled (the plane term's area change)
  SystemPattern pattern;
  ShapeTarget target;                     // with ShapeTargetKind::Template
  TriangleBvh bvh;                        // over the template; copied and refitted per run
  TriangleBvh bvh_in;                     // the same in the caller's labels (template_bvh())
  std::vector<std::array<int, 2>> edges;  // for the mean edge length of M
  std::vector<unsigned char> pinned;      // n flags
  int num_pinned = 0;
  std::vector<unsigned char> isolated;  // n flags: vertices in no triangle (also pinned)
  int num_isolated = 0;
  /// With per-vertex weights other than 1 (vertex_weights): w_i in the internal order, and the
  /// shape matrix A_w = W A + (I − W) on the pattern (docs/method-vertex-weights.md).
  bool weighted = false;
  std::vector<double> vertex_weight;
  SparseMatrixR weighted_shape;
  /// The shape matrix of the runs: A_w when weighted, else A (the pattern's).
  const SparseMatrixR& shape() const { return weighted ? weighted_shape : pattern.shape_matrix(); }
};

}  // namespace sm
