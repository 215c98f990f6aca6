#pragma once
// B-spline and NURBS basis functions with derivatives (The NURBS Book, Piegl & Tiller, A2.3, eq. 4.8).
// Only the p+1 functions that do not vanish at u are returned, with the index of the first one.
#include <Eigen/SparseCore>
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/splines/knot_vector.hpp"

namespace pcr {

/// values(d, j) = d-th derivative (d = 0..max_derivative) of N_{first+j}(u), j = 0..degree.
struct BasisDerivatives {
  int first = 0;
  MatX values;
  VecX integrals;  ///< optional (empty unless asked for): basis_integrals(knots, u), all num_basis()
};

/// J_j(u) = integral_0^u N_j(t) dt for every basis function j (dense, num_basis() values; zero for the
/// functions that start after u), by Gauss-Legendre quadrature on each knot span (exact: degree / 2 + 1
/// nodes). Throws InputError for u outside [0, 1].

/// The NURBS Book A2.3 (all non-zero basis functions and derivatives up to max_derivative at u).
/// Derivatives of order > degree are zero. Throws InputError for u outside [0,1] or max_derivative < 0.
BasisDerivatives basis_derivatives(const KnotVector& knots, double u, int max_derivative);

/// Allocation-free variant: values must be (max_derivative+1) x (degree+1) already (else InputError).
/// Allocates only for degree > 24 (scratch space beyond the fixed stack buffer).
void basis_derivatives(const KnotVector& knots, double u, int max_derivative, int& first,
                       Eigen::Ref<MatX> values);

VecX basis_integrals(const KnotVector& knots, double u);

/// integrals[j] = J_{first+j}(u) for the degree + 1 functions that do not vanish at u (first as
/// basis_derivatives gives it), by the quadrature of basis_integrals over the at most degree + 1 spans
/// of their supports below u: work independent of the number of basis functions. integrals must have
/// degree + 1 entries (else InputError).
void active_basis_integrals(const KnotVector& knots, double u, int& first, Eigen::Ref<VecX> integrals);

/// NURBS rational basis R_i = N_i w_i / W and its derivatives (The NURBS Book eq. 4.8 / A4.2 applied to
/// the basis); weights.size() == knots.num_basis(), all > 0 (else InputError).
BasisDerivatives rational_basis_derivatives(const KnotVector& knots, const VecX& weights, double u,
                                            int max_derivative);

/// Sparse (points.size() x num_basis) matrix of the derivative-th derivative of the basis (B-spline, or
/// NURBS when weights given) at the points.
Eigen::SparseMatrix<double> collocation_matrix(const KnotVector& knots, const std::vector<double>& points,
                                               int derivative, const VecX* weights = nullptr);

}  // namespace pcr
