#pragma once
// The Jacobian of a square problem with respect to its free (not fixed) variables, for the implicit
// function theorem and for stability monitoring (docs/design.md §4: the sign of det J along a quasi-static
// path changes where the path crosses a fold or a bifurcation, e.g. a buckling load).
#include <Eigen/SparseCore>
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/solve/problem.hpp"

namespace pcr {

struct FreeJacobian {
  Eigen::SparseMatrix<double> matrix;  ///< active rows x free columns, column-major (for sparse LU)
  std::vector<int> columns;            ///< global variable index of each free column
  std::vector<int> groups;             ///< VariableBlock::group of each free column (BorderedBlockLu)
};

/// dc/dx_free at x (all active rows; fixed variables are left out).
FreeJacobian free_jacobian(const Problem& problem, const VecX& x);
/// The free columns of a Jacobian J of the problem already evaluated
/// (Problem::evaluate_residuals_and_jacobian).
FreeJacobian free_jacobian(const Problem& problem, const Eigen::SparseMatrix<double, Eigen::RowMajor>& J);

/// Sign of det(dc/dx_free) at x: +1 or -1, and 0 when the problem is not square or the sparse LU finds
/// the matrix singular. Costs one Jacobian evaluation and one sparse LU factorisation.
int jacobian_determinant_sign(const Problem& problem, const VecX& x);

}  // namespace pcr
