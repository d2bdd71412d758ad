#pragma once
/// Metro-style one-sided and symmetric Hausdorff distances between meshes (paper Tables 1–3).
#include "geometry/bvh.hpp"
#include "geometry/distance_options.hpp"
#include "geometry/triangle_planes.hpp"
#include "mesh/mesh.hpp"
#include "mesh/topology.hpp"

namespace sm {

/// One-sided distance from mesh A to the mesh held by `B`, sampled on A: every vertex used by a
/// triangle; with spacing h = options.spacing · mean_edge_length(A), the ceil(L/h) − 1 interior
/// points splitting an edge of length L into equal parts; inside a triangle, the interior points
/// of the barycentric lattice with ceil(longest edge / h) divisions, or its centroid if there are
/// none. Each sample's distance to B is exact (the minimum over all of B's triangles, up to
/// rounding): a uniform grid over B's triangles (TriangleGrid, cells of B's mean edge length, as
/// in the Metro tool) answers the samples near B, starting from the previous sample's triangle,
/// and the BVH the others. `planes_b`, if given, are B's projection frames (e.g.
/// Reference::planes()), otherwise they are computed; with `topology_b` (B's connectivity, for
/// frames computed with it) a sample that settles in a face skips its edge neighbours.
/// With options.adaptive, see DistanceOptions::adaptive for the samples and statistics.
/// (DistanceMeter measures many frames of one connectivity with the same results, keeping the
/// sampling layout and the scratch memory from call to call.)
/// Deterministic: the result does not depend on the number of threads. No samples (A has no
/// triangles) gives all zeros.
/// Throws InputError if A is invalid (validate_mesh) or A has triangles but B has none, and
/// OptionError (naming the member) if options.spacing is not a positive number or refine_above
/// not in [0, 1].
DistanceStats one_sided_distance(const TriMesh& A, const TriangleBvh& B,
                                 const DistanceOptions& options = {},
                                 const TrianglePlanes* planes_b = nullptr,
                                 const Topology* topology_b = nullptr);

/// Symmetric Hausdorff distance d_H(A, B) = max(d_h(A, B), d_h(B, A)) from the two one-sided
/// results (absolute units; for relative units compare max_rel, which share one diagonal).
double symmetric_hausdorff(const DistanceStats& a_to_b, const DistanceStats& b_to_a);

}  // namespace sm
