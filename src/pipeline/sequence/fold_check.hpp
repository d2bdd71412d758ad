#pragma once
/// Per-frame numerical checks of a sequence job's output: non-finite positions, and triangles
/// folded over. M and the input frame N share their connectivity in a sequence job, so a fold is
/// decided exactly, triangle by triangle: output triangle t is folded when its normal opposes the
/// normal of the same triangle t in the input frame (n_out · n_in < 0), unless t was already
/// degenerate or folded in the input (then its input normal says nothing about the surface).
#include <optional>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"
#include "core/options_table.hpp"
#include "mesh/topology.hpp"

namespace sm {

/// "checks": when an optimized frame fails, besides a failed solve and non-finite positions
/// (which always fail it): when its folded triangles (below) exceed either limit. Real captures
/// give a few per frame at most.
struct FrameCheckOptions {
  std::optional<int> max_folded_triangles;            ///< empty: no limit
  std::optional<double> max_folded_fraction = 0.005;  ///< of the frame's triangles; empty: none
  /// "repair_folds": a frame with more folds than the limits above allow is solved again with
  /// the folded region pulled back towards the input (fold_repair.hpp) until no fold is left; it
  /// fails only if that does not succeed.
  bool repair_folds = true;
  int repair_rings = 2;   ///< "repair_rings": rings around the folds whose weight ramps up to 1
  int repair_rounds = 4;  ///< "repair_rounds": re-solves, each with a wider region, before giving up
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
      field<&O::repair_folds>("repair_folds", any_value(),
                              "a frame with more folded triangles than the limits above allow "
                              "is solved again with the vertices of the folds kept at their "
                              "input position and the rings around them pulled towards it "
                              "(per-vertex weights, docs/fold-repair.md), widening the region "
                              "until no fold is left; it fails only if that does not succeed. "
                              "With `max_folded_triangles` 0 every frame with a fold is "
                              "repaired"),
      field<&O::repair_rings>("repair_rings", closed(0, 16),
                              "rings of vertices around the folds whose weight ramps from 0 up "
                              "to 1 (1/(r+1), 2/(r+1), ...)"),
      field<&O::repair_rounds>("repair_rounds", closed(1, 16),
                               "re-solves before the repair gives up; each adds the new folds "
                               "and one more ring to the region kept at the input"),
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
/// `F` (m×3) whose adjacency is `topology`; with `folded`, also lists them (increasing). Linear
/// in m.
FoldCount count_folded_triangles(const Triangles& F, const Topology& topology,
                                 const Positions& input, const Positions& output,
                                 std::vector<int>* folded = nullptr);

/// "" if every coordinate of `V` is finite, else what is wrong with the first vertex that is not:
/// "vertex 17 has a non-finite coordinate (nan, 0.5, 1)".
std::string non_finite_positions(const Positions& V);

}  // namespace sm
