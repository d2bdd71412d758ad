#pragma once
/// Per-frame numerical checks of a sequence job's output: non-finite positions, and triangles
/// folded over. M and the input frame N share their connectivity in a sequence job, so a fold is
/// decided exactly, triangle by triangle: output triangle t is folded when its normal opposes the
/// normal of the same triangle t in the input frame (n_out · n_in < 0), unless t was already
/// degenerate or folded in the input (then its input normal says nothing about the surface).
#include <optional>
#include <string>

#include "mesh/mesh.hpp"
#include "mesh/options_table.hpp"
#include "mesh/topology.hpp"

namespace sm {

/// "checks": when an optimized frame fails, besides a failed solve and non-finite positions
/// (which always fail it): when its folded triangles (below) exceed either limit. Real captures
/// give a few per frame at most.
struct FrameCheckOptions {
  std::optional<int> max_folded_triangles;            ///< empty: no limit
  std::optional<double> max_folded_fraction = 0.005;  ///< of the frame's triangles; empty: none
};

template <>
inline const Fields<FrameCheckOptions>& fields_of<FrameCheckOptions>() {
  using O = FrameCheckOptions;
  static const Fields<O> fields = {
      field<&O::max_folded_triangles>("max_folded_triangles", at_least(0),
                                      "a frame with more folded triangles fails; `0` tolerates "
                                      "none; `null`: no limit"),
      field<&O::max_folded_fraction>("max_folded_fraction", closed(0, 1),
                                     "a frame whose folded triangles exceed this fraction of its "
                                     "triangles fails; `null`: no limit"),
  };
  return fields;
}

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
