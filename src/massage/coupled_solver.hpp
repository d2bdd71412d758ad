#pragma once
/// Solvers for the coupled system (K ⊗ I₃ − D) x = r, with K n×n on the fixed pattern (eq. 7) and
/// D one symmetric 3×3 block per entry of K's pattern: the point-to-plane distance term
/// (massage.hpp, "distance_term": "plane", plane_term.hpp) takes tangential projectors off the
/// isotropic terms of B, which couples x, y and z. So the 3n×3n matrix has 3×3 blocks on K's
/// pattern, and a product is one pass over the pattern with a 3×3 block per entry.
///
/// BiCGSTAB here (bicgstab.hpp, SharedScalars) uses one set of scalars for the whole 3n-vector
/// (the columns are coupled) and the ILU(0) factors of K with D's mean diagonal taken off (an
/// isotropic preconditioner on the same pattern, factored by the same schedule); the fall-back is
/// a sparse LU of the 3n×3n matrix.
#include <array>
#include <vector>

#include "massage/linear_solver.hpp"

namespace sm {

/// The blocks of D, 6 values per slot of K's value array (xx, yy, zz, xy, xz, yz); an empty
/// vector is D = 0.
using VertexBlocks = std::vector<std::array<double, 6>>;

/// Y = (K ⊗ I₃ − D) X, X and Y n×3 (row i is vertex i's x, y, z).
void multiply_coupled(const SparseMatrixR& K, const VertexBlocks& D, const Positions& X,
                      Positions& Y);

/// Preconditioned BiCGSTAB on (K ⊗ I₃ − D) X = R from the guess in X; stops when every column of
/// the residual is below tolerance · scale[c] (scale as in bicgstab(), centred_scale()).
SolveStats bicgstab_coupled(const SparseMatrixR& K, const VertexBlocks& D,
                            const Ilu0& preconditioner, const Positions& R, Positions& X,
                            double tolerance, int max_iterations, BicgstabWorkspace& ws,
                            const std::array<double, 3>& scale);

/// Sparse LU of the 3n×3n matrix (K ⊗ I₃ − D), the robust fall-back (assembled every call).
SolveStats solve_coupled_direct(const SparseMatrixR& K, const VertexBlocks& D, const Positions& R,
                                Positions& X);

}  // namespace sm
