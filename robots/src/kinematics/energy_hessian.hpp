#pragma once
// Second derivatives of the energy terms and constraint rows (energy_terms.hpp) other than the rods' (whose
// are exact: hyper_dual.hpp) by central differences of their exact gradients and Jacobians (internal header
// of pcr::robots), for Ipopt's Newton steps and the contact verdict: with
// steps h = 1e-6 max(1, |x_k|) the truncation error is O(h^2) and the round-off O(eps / h), about 1e-10
// of the Hessian's size, far below what Ipopt's line search needs (the minimiser is refined by Newton on
// the collocation equations anyway).
#include <vector>

#include "pcr/solve/residual_block.hpp"

namespace pcr::kinematics {

/// Hessian of the term over its stacked variables (sizes: of each touched block), dense row-major.
void gradient_difference_hessian(const ObjectiveTerm& term, const std::vector<int>& sizes,
                                 const double* const* values, double* hessian);
/// Hessian of sum_i weights[i] c_i over the block's stacked variables, dense row-major.
void jacobian_difference_hessian(const ResidualBlock& block, const std::vector<int>& sizes,
                                 const double* const* values, const double* weights, double* hessian);

}  // namespace pcr::kinematics
