#pragma once
/// Meshes generated in code: the fixtures of tests, benchmarks and the demo sequence.
#include "mesh/mesh.hpp"

namespace sm {

/// Flat (nx+1)×(ny+1)-vertex grid in the z = 0 plane over [0, sx]×[0, sy], each cell split
/// along alternating diagonals. Counter-clockwise seen from +z.
TriMesh make_grid(int nx, int ny, double sx, double sy);

/// Icosphere: an icosahedron subdivided `subdivisions` times and projected on the sphere.
TriMesh make_icosphere(int subdivisions, double radius);

/// Torus around the z axis with major radius R and minor radius r, nu×nv quads split in two.
TriMesh make_torus(int nu, int nv, double R, double r);

/// Open cylinder around the z axis, z in [0, height], nu segments around, nv rings along.
TriMesh make_cylinder(int nu, int nv, double radius, double height);

/// Closed axis-aligned box [0,sx]×[0,sy]×[0,sz], each face an n×n grid, welded along its sharp
/// edges and corners.
TriMesh make_box(int n, double sx, double sy, double sz);

}  // namespace sm
