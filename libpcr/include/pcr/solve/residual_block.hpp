#pragma once
// A residual block: a few rows of the nonlinear system c(x) (with row bounds: equality by default),
// touching a fixed list of variable blocks. Ceres-style evaluation: values of each touched variable
// block in, residual values out, and — when asked — one dense row-major Jacobian per touched block.
// The global sparsity pattern is the union of these dense blocks (less the entries a block declares
// structurally zero), fixed when the problem is built.
#include <limits>
#include <string>
#include <vector>

#include "pcr/core/types.hpp"

namespace pcr {

using VariableId = int;
using ResidualId = int;

class ResidualBlock {
 public:
  /// kind groups blocks in solve summaries (e.g. "rod.force_balance"); name identifies this block.
  ResidualBlock(std::string kind, std::string name, int num_rows, std::vector<VariableId> variables);
  virtual ~ResidualBlock() = default;

  /// values[k]: the current values of variables()[k] (size of that block).
  /// residual: num_rows() values.
  /// jacobians: null for values only; else jacobians[k] is null (skip) or a row-major
  /// num_rows() x size(variables()[k]) array to fill completely (entries not written are undefined).
  virtual void evaluate(const double* const* values, double* residual, double* const* jacobians) const = 0;

  /// Optional size check: the size variables()[k] must have, or -1 (default) for "any". Problem
  /// validates it when the block is added.
  virtual int expected_variable_size(int k) const {
    (void)k;
    return -1;
  }

  /// Optional structural sparsity: false promises that d c_row / d (column of variables()[k]) is zero
  /// for every x, and the entry is left out of the problem's Jacobian pattern (evaluate may still
  /// write it; the value is ignored). Default: every entry of every touched block is a nonzero.
  /// Asked only when the problem's structure is (re)built. Checked by check_problem_jacobian, which
  /// compares the omitted entries against finite differences as zeros.
  virtual bool structural_nonzero(int k, int row, int column) const {
    (void)k, (void)row, (void)column;
    return true;
  }
  /// structural_nonzero for all entries of touched block k at once: mask[row * size + column], size =
  /// the size of variables()[k]. The default asks structural_nonzero entry by entry; blocks with many
  /// entries may answer faster (the answers must be the same).
  virtual void structural_mask(int k, int size, char* mask) const;

  /// Optional second derivatives (used by Ipopt for exact Hessians when EVERY active block and objective
  /// term provides them, else limited-memory BFGS). Default: not provided.
  virtual bool provides_hessian() const { return false; }
  /// Hessian of sum_i weights[i] c_i(x) with respect to the stacked touched variables (ordered as
  /// variables(), dimension n = sum of their sizes): a dense row-major symmetric n x n array to fill
  /// completely. Only called when provides_hessian(); the default throws std::logic_error.
  virtual void evaluate_hessian(const double* const* values, const double* weights, double* hessian) const;

  const std::string& kind() const { return kind_; }
  const std::string& name() const { return name_; }
  int num_rows() const { return num_rows_; }
  const std::vector<VariableId>& variables() const { return variables_; }

  /// Row bounds l <= c(x) <= u; both 0 (equality) unless set.
  const VecX& row_lower() const { return row_lower_; }
  const VecX& row_upper() const { return row_upper_; }
  void set_row_bounds(const VecX& lower, const VecX& upper);

 private:
  std::string kind_, name_;
  int num_rows_;
  std::vector<VariableId> variables_;
  VecX row_lower_, row_upper_;
};

/// A term of the objective f(x) = sum of terms (optimisation problems such as IK).
class ObjectiveTerm {
 public:
  ObjectiveTerm(std::string name, std::vector<VariableId> variables);
  virtual ~ObjectiveTerm() = default;
  /// Returns the term's value; gradients null for value only, else gradients[k] null or size(k).
  virtual double evaluate(const double* const* values, double* const* gradients) const = 0;

  /// As ResidualBlock::expected_variable_size: -1 (default) for "any".
  virtual int expected_variable_size(int k) const {
    (void)k;
    return -1;
  }
  /// Optional Hessian of the term over the stacked touched variables (dense row-major symmetric n x n,
  /// filled completely). Default: not provided (the default evaluate_hessian throws std::logic_error).
  virtual bool provides_hessian() const { return false; }
  virtual void evaluate_hessian(const double* const* values, double* hessian) const;

  const std::string& name() const { return name_; }
  const std::vector<VariableId>& variables() const { return variables_; }

 private:
  std::string name_;
  std::vector<VariableId> variables_;
};

}  // namespace pcr
