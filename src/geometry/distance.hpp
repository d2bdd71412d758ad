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
/// Samples: along every edge at most `spacing` mean edge lengths of A apart and inside every
/// triangle on a barycentric lattice (about 8 per triangle at the default 0.25 on a regular mesh;
/// Metro's default is 10 per face); mean and RMS are those of the samples.
/// With options.adaptive, a coarse pass samples every vertex and every centroid of A; mean and
/// RMS are the integrals of d and d² over A's area by the rule of degree 2 on each triangle (1/12
/// of the area at each corner, 3/4 at the centroid). Then the triangles whose samples reach
/// `refine_above` times the largest sample are sampled at twice `spacing`, and those whose
/// samples then reach sqrt(refine_above) times the largest so far at `spacing` (all three edges
/// and the lattice); the maximum is taken over every sample (DistanceStats::samples counts them
/// all). Every sample's distance is exact and the triangles refined depend on those distances
/// alone. The default refine_above is the largest value that still finds the finest uniform
/// sampling's maximum on captured sequences (bench_sequence measures it).
/// With options.corresponding_triangles (a frame and its corrected output share their
/// connectivity), the first sample of A's triangle t tries B's triangle t first (with
/// `adaptive`, a vertex tries the first triangle using it, a centroid its own triangle): only
/// where the search starts, the distances stay exact.
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
