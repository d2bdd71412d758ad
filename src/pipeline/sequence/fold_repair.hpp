#pragma once
/// Local repair of folded triangles (checks.repair_folds, docs/fold-repair.md). The optimized
/// frame is solved again, from the input, with per-vertex weights (massage.vertex_weights,
/// docs/method-vertex-weights.md) that keep the vertices of the folded triangles at their input
/// position (weight 0) and ramp up to 1 over `rings` rings around them; the rest of the frame is
/// massaged as before. Rounds repeat with the new folds and one more ring added to the region
/// kept at the input, until no triangle is folded or `rounds` re-solves are spent.
#include <string>
#include <vector>

#include "massage/massage.hpp"
#include "massage/reference.hpp"
#include "mesh/mesh.hpp"
#include "mesh/topology.hpp"

namespace sm {

struct FoldRepair {
  bool repaired = false;  ///< a round ended with no folded triangle; V holds it
  Positions V;            ///< the last round's positions (n×3), when a round ran
  int rounds = 0;         ///< re-solves done
  int pinned = 0;         ///< vertices kept at the input in the last round (weight 0)
  int weighted = 0;       ///< vertices with a weight in (0, 1) in the last round
  int folded_left = 0;    ///< folded triangles after the last round
  std::string failure;    ///< a round's solve failed (then no further round ran)
};

/// The ring distance of every vertex from the flagged ones (`seeds`, n flags) over `topology`'s
/// one-rings, up to `limit` (vertices farther away get limit + 1).
std::vector<int> ring_distance(const Topology& topology, const std::vector<unsigned char>& seeds,
                               int limit);

/// The repair weights: 0 on the seeds, d/(rings+1) at ring distance d <= rings, 1 beyond, each
/// capped by `base` (the user's vertex_weights; empty: 1).
std::vector<double> repair_weights(const Topology& topology,
                                   const std::vector<unsigned char>& seeds, int rings,
                                   const std::vector<double>& base);

/// Repairs the folds `folded` (triangle indices, from count_folded_triangles of the optimized
/// frame against `input`) by re-solving from `input` against `reference` with a Massager on
/// `templ` and `massage` (whose vertex_weights cap the repair's). `topology` is templ's.
FoldRepair repair_folds(const TriMesh& templ, const MassageOptions& massage,
                        const Topology& topology, const Positions& input,
                        const Reference& reference, const std::vector<int>& folded, int rings,
                        int rounds);

}  // namespace sm
