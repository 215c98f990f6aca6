#pragma once
// A nonlinear problem built from variable blocks and residual blocks (DESIGN.md §5):
//   find x with  c_l <= c(x) <= c_u,  x_l <= x <= x_u,  minimising f(x) (zero when no objective terms).
// The description is fixed once built; values live in a separate vector x (size num_variables()).
// The global sparse Jacobian pattern is the union of the blocks' dense (block rows x variable block)
// patterns, computed once; evaluation writes into it without rebuilding triplets.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/SparseCore>

#include "pcr/solve/residual_block.hpp"

namespace pcr {

struct VariableBlock {
  std::string name;
  int offset = 0;  ///< first index in x
  int size = 0;
  VecX initial, lower, upper;
  int group = -1;  ///< optional structural group (e.g. one rod) for structured linear solvers
};

class Problem {
 public:
  /// Adds a variable block; bounds default to +-infinity. Returns its id.
  VariableId add_variable_block(const std::string& name, const VecX& initial);
  VariableId add_variable_block(const std::string& name, const VecX& initial, const VecX& lower, const VecX& upper);
  /// Adds a residual block; its variables must exist. Returns its id.
  ResidualId add_residual_block(std::shared_ptr<const ResidualBlock> block);
  void add_objective_term(std::shared_ptr<const ObjectiveTerm> term);

  /// A switched-off block contributes no rows (the pattern is rebuilt lazily on the next evaluation).
  void set_residual_active(ResidualId id, bool active);
  void set_variable_group(VariableId id, int group);
  void set_variable_bounds(VariableId id, const VecX& lower, const VecX& upper);
  /// Fixes a variable block at value (lower = upper = value; solvers treat it as a constant).
  void fix_variable(VariableId id, const VecX& value);

  int num_variables() const;
  int num_rows() const;  ///< rows of the active residual blocks
  const VariableBlock& variable(VariableId id) const;
  int num_variable_blocks() const;
  const ResidualBlock& residual(ResidualId id) const;
  int num_residual_blocks() const;
  bool residual_active(ResidualId id) const;
  /// First row of an active residual block in c(x); -1 when inactive.
  int row_offset(ResidualId id) const;
  bool has_objective() const;

  /// Initial values of all variable blocks stacked (size num_variables()).
  VecX initial_values() const;
  /// c(x), size num_rows().
  void evaluate_residuals(const VecX& x, VecX& c) const;
  /// c(x) and its Jacobian in the fixed pattern (J keeps its pattern between calls).
  void evaluate_residuals_and_jacobian(const VecX& x, VecX& c, Eigen::SparseMatrix<double, Eigen::RowMajor>& J) const;
  /// f(x) and optionally its gradient (size num_variables()).
  double evaluate_objective(const VecX& x, VecX* gradient) const;

  /// Stacked row bounds of the active rows.
  VecX row_lower() const;
  VecX row_upper() const;
  VecX variable_lower() const;
  VecX variable_upper() const;

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
  void ensure_impl();
};

}  // namespace pcr
