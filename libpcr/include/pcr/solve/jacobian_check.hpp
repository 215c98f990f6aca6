#pragma once
// Analytic derivatives against central finite differences, for one residual block or a whole problem.
//   numeric J_ij = (c_i(x + h e_j) - c_i(x - h e_j)) / (2 h),  h = relative_step * max(1, |x_j|),
// truncation error O(h^2 |c'''|), round-off O(eps |c| / h); the defaults balance both near 1e-10 |c|.
// An entry passes when |analytic - numeric| <= absolute_tolerance + relative_tolerance * max(|a|, |n|).
#include <string>
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/solve/problem.hpp"
#include "pcr/solve/residual_block.hpp"

namespace pcr {

struct JacobianCheckOptions {
  double relative_step = 1e-6;
  double absolute_tolerance = 1e-6;
  double relative_tolerance = 1e-6;
};

struct JacobianCheckResult {
  bool passed = true;
  int entries_checked = 0;
  int entries_failed = 0;
  // The worst entry (largest |a - n| / (absolute_tolerance + relative_tolerance * max(|a|, |n|))).
  std::string block_name, block_kind;  ///< "objective" kind for objective gradients in a problem check
  int row = -1;                        ///< row within the block (for a problem check: global row too)
  int global_row = -1;
  int variable_index = -1;  ///< position k in the block's variables()
  VariableId variable = -1;
  std::string variable_name;  ///< filled by the problem check (a lone block does not know the names)
  int column = -1;            ///< column within that variable block
  double analytic = 0.0, numeric = 0.0, abs_error = 0.0, rel_error = 0.0;
  double worst_ratio = 0.0;  ///< error / allowed error of the worst entry (passed iff <= 1)

  /// "jacobian check passed: 12 entries, worst block 'circle' (kind 'test') row 0, variable 1 col 0:
  ///  analytic 2, numeric 2, abs err 1e-10, rel err 5e-11"
  std::string to_string() const;
};

/// values[k]: values of block.variables()[k] (their sizes define the variable block sizes).
JacobianCheckResult check_block_jacobian(const ResidualBlock& block, const std::vector<VecX>& values,
                                         const JacobianCheckOptions& options = {});

/// Second derivatives of a block that provides_hessian(): its Hessian of sum_i weights[i] c_i against
/// central differences of J(x)^T weights. Reported entries: row = Hessian row, variable_index/column
/// = Hessian column (touched variable k, column in it). Throws InputError if the block has no Hessian.
JacobianCheckResult check_block_hessian(const ResidualBlock& block, const std::vector<VecX>& values,
                                        const VecX& weights, const JacobianCheckOptions& options = {});

/// The whole Jacobian of the active rows of problem at x (every column, fixed variables included) and
/// the gradient of the objective (reported with kind "objective"). Costs 2 num_variables() evaluations.
JacobianCheckResult check_problem_jacobian(const Problem& problem, const VecX& x,
                                           const JacobianCheckOptions& options = {});

}  // namespace pcr
