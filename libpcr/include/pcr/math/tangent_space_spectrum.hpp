#pragma once
// Eigenvalues of a symmetric matrix H restricted to the null space of a constraint Jacobian A: those of
// Z^T H Z for an orthonormal basis Z of {v : A v = 0} (the second-order test of a constrained
// stationary point: the count of negative ones is the number of unstable modes). They do not depend on
// which orthonormal basis: Z is built as Z_b Z_g, where Z_b is block diagonal, per block of variables an
// orthonormal null basis of the rows that touch that block only (a unit-quaternion row per control
// point: 6 of 7 columns), and Z_g the null basis of the remaining rows A Z_b from a Householder QR,
// whose reflectors are applied to Z_b^T H Z_b instead of being formed. Where the block-local rows are
// most of A, this costs (rows left) n^2 plus the dense eigenvalue solve instead of the n^3 of forming a
// full Z and the products with it.
#include <Eigen/SparseCore>
#include <vector>

#include "pcr/core/types.hpp"

namespace pcr {

/// A run of variables [offset, offset + size) that block-local constraint rows may touch.
struct VariableRange {
  int offset, size;
};

/// Eigenvalues (ascending) of H (symmetric, both triangles stored, n x n) on the null space of A (m x n);
/// blocks partition the columns [0, n) or part of them (columns in no block are treated as a block of
/// their own each). Rows of A that are dependent within round-off (column-pivoted QR's rank) are dropped.
VecX tangent_space_eigenvalues(const Eigen::SparseMatrix<double>& H, const Eigen::SparseMatrix<double>& A,
                               const std::vector<VariableRange>& blocks);

}  // namespace pcr
