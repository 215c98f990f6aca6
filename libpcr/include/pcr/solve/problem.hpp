#pragma once
// A nonlinear problem built from variable blocks and residual blocks (docs/design.md §5):
//   find x with  c_l <= c(x) <= c_u,  x_l <= x <= x_u,  minimising f(x) (zero when no objective terms).
// The description is fixed once built; values live in a separate vector x (size num_variables()).
// The global sparse Jacobian pattern is the union of the blocks' dense (block rows x variable block)
// patterns, computed once; evaluation writes into it without rebuilding triplets.
//
// Fixed variables are constants of a solve whose values are whatever x holds (the solvers leave those
// entries of x alone); the values given to fix_variable are the initial values, nothing more.
//
// Thread safety: the const functions only read the Problem (the derived structure, e.g. the Jacobian
// pattern, is updated by the non-const functions; evaluation scratch is per thread), so several threads
// may evaluate one Problem at once while none changes it. Copies are deep and independent (the blocks
// themselves are shared: they are immutable).
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/SparseCore>

#include "pcr/solve/residual_block.hpp"

namespace pcr {

struct VariableBlock {
  std::string name;
  int offset = 0;  ///< first index in x
  int size = 0;
  VecX initial, lower, upper;
  /// Natural magnitude of each entry in its units (e.g. a rod's force scale for its internal force),
  /// ones by default: how large a value is against the rows' scaling (residuals_within_round_off).
  VecX scale;
  int group = -1;  ///< optional structural group (e.g. one rod) for structured linear solvers
};

class Problem {
 public:
  Problem();
  Problem(const Problem& other);  ///< deep copy (blocks themselves are shared: they are immutable)
  Problem& operator=(const Problem& other);
  Problem(Problem&&) noexcept;
  Problem& operator=(Problem&&) noexcept;
  ~Problem();

  /// Adds a variable block; bounds default to +-infinity. Returns its id.
  VariableId add_variable_block(const std::string& name, const VecX& initial);
  VariableId add_variable_block(const std::string& name, const VecX& initial, const VecX& lower,
                                const VecX& upper);
  /// Adds a residual block; its variables must exist. Returns its id.
  ResidualId add_residual_block(std::shared_ptr<const ResidualBlock> block);
  void add_objective_term(std::shared_ptr<const ObjectiveTerm> term);

  /// A switched-off block contributes no rows (the patterns are rebuilt at once).
  void set_residual_active(ResidualId id, bool active);
  /// The same for several blocks at once (one rebuild).
  void set_residual_active(const std::vector<ResidualId>& ids, bool active);
  void set_variable_group(VariableId id, int group);
  void set_variable_bounds(VariableId id, const VecX& lower, const VecX& upper);
  /// The natural magnitude of each entry (VariableBlock::scale): positive and finite.
  void set_variable_scale(VariableId id, const VecX& scale);
  /// Fixes a variable block (lower = upper = initial = value): solvers treat it as a constant, with the
  /// value its entries of x hold. set_variable_bounds un-fixes it.
  void fix_variable(VariableId id, const VecX& value);
  bool variable_fixed(VariableId id) const;

  int num_variables() const;
  int num_rows() const;  ///< rows of the active residual blocks
  const VariableBlock& variable(VariableId id) const;
  int num_variable_blocks() const;
  const ResidualBlock& residual(ResidualId id) const;
  /// The same block, shared (blocks are immutable): for a block that wraps another one.
  std::shared_ptr<const ResidualBlock> residual_block(ResidualId id) const;
  int num_residual_blocks() const;
  bool residual_active(ResidualId id) const;
  /// First row of an active residual block in c(x); -1 when inactive.
  int row_offset(ResidualId id) const;
  bool has_objective() const;
  /// Changes whenever blocks are added, activity changes or a variable is fixed / un-fixed (solvers
  /// re-analyse their pattern when it does; bound values alone do not change it).
  std::uint64_t structure_version() const;
  /// Non-zeros of the Jacobian pattern of the active rows.
  int jacobian_nonzeros() const;
  /// The active residual block owning row (0 <= row < num_rows()).
  ResidualId residual_at_row(int row) const;

  /// Initial values of all variable blocks stacked (size num_variables()).
  VecX initial_values() const;
  /// c(x), size num_rows().
  void evaluate_residuals(const VecX& x, VecX& c) const;
  /// c(x) and its Jacobian in the fixed pattern (J keeps its pattern between calls). J is row-major
  /// because each block's dense row-major Jacobian then lands as one contiguous run per row (a copy per
  /// block row through precomputed positions); solvers needing another layout map values once.
  /// Neither evaluation allocates once c and J have their sizes (same structure_version()) and the calling
  /// thread has evaluated a problem with blocks as large before.
  void evaluate_residuals_and_jacobian(const VecX& x, VecX& c,
                                       Eigen::SparseMatrix<double, Eigen::RowMajor>& J) const;
  /// f(x) and optionally its gradient (size num_variables()).
  double evaluate_objective(const VecX& x, VecX* gradient) const;

  /// Stacked row bounds of the active rows.
  VecX row_lower() const;
  VecX row_upper() const;
  VecX variable_lower() const;
  VecX variable_upper() const;
  /// Stacked VariableBlock::scale.
  VecX variable_scales() const;

  /// Unscaled violation of row i: max(l_i - c_i, c_i - u_i, 0); returns its max over all rows
  /// (+infinity if any c_i is not finite, 0 when there are no rows).
  double constraint_violation(const VecX& c) const;
  /// Max violation per residual block kind, kinds in order of first appearance among active blocks.
  std::vector<std::pair<std::string, double>> violation_by_kind(const VecX& c) const;

  /// True when every active residual block and every objective term provides its Hessian.
  bool provides_hessian() const;
  /// Lower triangle (col <= row) of  objective_factor * Hess f(x) + sum_i multipliers[i] Hess c_i(x)
  /// in a fixed pattern (union of the blocks' dense touched-variable patterns); like J, H keeps its
  /// pattern between calls. Throws std::logic_error unless provides_hessian().
  void evaluate_hessian(const VecX& x, double objective_factor, const VecX& multipliers,
                        Eigen::SparseMatrix<double, Eigen::RowMajor>& H) const;

 private:
  struct Impl;                 // problem_impl.hpp
  friend class ProblemSystem;  // keeps its pattern analysis in Impl (problem_system.hpp)
  std::unique_ptr<Impl> impl_;
  void ensure_impl();
  const Impl& impl() const;
  Impl& impl();
};

}  // namespace pcr
