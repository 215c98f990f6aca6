#pragma once
// Dense eigen- and singular value decompositions of dynamic-size matrices, compiled once here: every
// source file that instantiates Eigen's SelfAdjointEigenSolver or JacobiSVD itself pays 7-12 s of
// compile time (twice that under the sanitizers).
#include "pcr/core/types.hpp"

namespace pcr {

/// Eigenvalues (ascending) and orthonormal eigenvectors (columns) of a symmetric matrix.
struct SymmetricEigen {
  VecX values;
  MatX vectors;
};

/// Eigenvalues and eigenvectors of the symmetric matrix A (its lower triangle is read).
SymmetricEigen symmetric_eigen(const MatX& A);
/// Eigenvalues (ascending) of the symmetric matrix A, without the eigenvectors.
VecX symmetric_eigenvalues(const MatX& A);

/// Singular values (descending) and the full square matrix V of right singular vectors (columns) of C.
struct RightSingularVectors {
  VecX sigma;
  MatX V;
};

/// The singular values of C and its right singular vectors (two-sided Jacobi SVD).
RightSingularVectors right_singular_vectors(const MatX& C);
/// The singular values (descending) of C alone.
VecX singular_values(const MatX& C);

}  // namespace pcr
