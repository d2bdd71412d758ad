#pragma once
/// Per-frame numerical checks of a sequence job's output: non-finite positions, and triangles
/// folded over. M and the input frame N share their connectivity in a sequence job, so a fold is
/// decided exactly, triangle by triangle: output triangle t is folded when its normal opposes the
/// normal of the same triangle t in the input frame (n_out · n_in < 0), unless t was already
/// degenerate or folded in the input (then its input normal says nothing about the surface).
#include <string>

#include "mesh/mesh.hpp"
#include "mesh/topology.hpp"

namespace sm {

struct FoldCount {
  int folded = 0;  ///< output triangles whose normal opposes their input normal
  int degenerate_input =
      0;  ///< not judged: zero area in the input (|n_in| ≤ 1e-12 · longest edge²)
  /// Not judged: folded in the input already, i.e. n_in opposes the sum of the unit normals of
  /// the triangles that share an edge with it (an output that unfolds them is no fault).
  int folded_input = 0;
};

/// Counts the folded triangles of `output` (n×3) against `input` (n×3), both with the triangles
/// `F` (m×3) whose adjacency is `topology`. Linear in m.
FoldCount count_folded_triangles(const Triangles& F, const Topology& topology,
                                 const Positions& input, const Positions& output);

/// "" if every coordinate of `V` is finite, else what is wrong with the first vertex that is not:
/// "vertex 17 has a non-finite coordinate (nan, 0.5, 1)".
std::string non_finite_positions(const Positions& V);

}  // namespace sm
