#include "pcr/solve/jacobian_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "pcr/core/error.hpp"

namespace pcr {

namespace {

double step_for(double x, const JacobianCheckOptions& o) {
  return o.relative_step * std::max(1.0, std::abs(x));
}

// Compares one entry and keeps it when it is the worst so far; non-finite values always fail.
struct EntryJudge {
  const JacobianCheckOptions& options;
  JacobianCheckResult& result;
  bool consider(double analytic, double numeric) {
    ++result.entries_checked;
    const double scale = std::max(std::abs(analytic), std::abs(numeric));
    const double abs_error = std::abs(analytic - numeric);
    const double allowed = options.absolute_tolerance + options.relative_tolerance * scale;
    const double ratio = std::isfinite(abs_error) ? abs_error / allowed : HUGE_VAL;
    if (!(ratio <= 1.0)) {
      ++result.entries_failed;
      result.passed = false;
    }
    if (!(ratio <= result.worst_ratio) || result.entries_checked == 1) {
      result.worst_ratio = ratio;
      result.analytic = analytic;
      result.numeric = numeric;
      result.abs_error = abs_error;
      result.rel_error = scale > 0.0 ? abs_error / scale : 0.0;
      return true;
    }
    return false;
  }
};

void check_options(const JacobianCheckOptions& o) {
  require(o.relative_step > 0.0 && o.relative_step < 1.0,
          "JacobianCheckOptions: relative_step = ", o.relative_step, " not in (0, 1)");
  require(o.absolute_tolerance >= 0.0 && o.relative_tolerance >= 0.0 &&
              o.absolute_tolerance + o.relative_tolerance > 0.0,
          "JacobianCheckOptions: tolerances (", o.absolute_tolerance, ", ", o.relative_tolerance,
          ") must be >= 0 and not both 0");
}

// Central differences of f() (a vector-valued function of the touched blocks x) over every entry j of
// every block k, each compared by `judge` with analytic(k, j, i) = d f_i / d x[k][j]; the worst entry is
// recorded in result (row i, block k, column j).
template <typename F, typename Analytic>
void compare_with_central_differences(std::vector<VecX>& x, const std::vector<VariableId>& ids,
                                      const JacobianCheckOptions& options, F f, Analytic analytic,
                                      EntryJudge& judge, JacobianCheckResult& result) {
  for (size_t k = 0; k < x.size(); ++k) {
    for (int j = 0; j < x[k].size(); ++j) {
      const double x0 = x[k][j], h = step_for(x0, options);
      x[k][j] = x0 + h;
      const VecX plus = f();
      x[k][j] = x0 - h;
      const VecX minus = f();
      x[k][j] = x0;
      for (int i = 0; i < plus.size(); ++i) {
        if (judge.consider(analytic(static_cast<int>(k), j, i), (plus[i] - minus[i]) / (2.0 * h))) {
          result.row = result.global_row = i;
          result.variable_index = static_cast<int>(k);
          result.variable = ids[k];
          result.column = j;
        }
      }
    }
  }
}

}  // namespace

std::string JacobianCheckResult::to_string() const {
  char buffer[512];
  std::snprintf(
      buffer, sizeof buffer,
      "jacobian check %s: %d entries (%d failed); worst: block '%s' (kind '%s') row %d, variable %d "
      "(id %d) col %d: analytic %.10g, numeric %.10g, abs err %.3g, rel err %.3g",
      passed ? "passed" : "FAILED", entries_checked, entries_failed, block_name.c_str(), block_kind.c_str(),
      row, variable_index, variable, column, analytic, numeric, abs_error, rel_error);
  return buffer;
}

JacobianCheckResult check_block_jacobian(const ResidualBlock& block, const std::vector<VecX>& values,
                                         const JacobianCheckOptions& options) {
  check_options(options);
  const auto& ids = block.variables();
  require(values.size() == ids.size(), "check_block_jacobian: block '", block.name(), "' touches ",
          ids.size(), " variable blocks, got ", values.size(), " values");
  const int rows = block.num_rows();
  std::vector<VecX> x = values;
  std::vector<const double*> value_ptrs(ids.size());
  std::vector<RowMajorMatX> jacobians(ids.size());
  std::vector<double*> jacobian_ptrs(ids.size());
  for (size_t k = 0; k < ids.size(); ++k) {
    const int expected = block.expected_variable_size(static_cast<int>(k));
    require(expected < 0 || expected == values[k].size(), "check_block_jacobian: block '", block.name(),
            "': values[", k, "] has size ", values[k].size(), ", expected ", expected);
    value_ptrs[k] = x[k].data();
    jacobians[k] = RowMajorMatX::Constant(rows, values[k].size(), std::nan(""));
    jacobian_ptrs[k] = jacobians[k].data();
  }
  VecX c(rows);
  block.evaluate(value_ptrs.data(), c.data(), jacobian_ptrs.data());

  JacobianCheckResult result;
  result.block_name = block.name();
  result.block_kind = block.kind();
  EntryJudge judge{options, result};
  const auto residual = [&]() {
    VecX r(rows);
    block.evaluate(value_ptrs.data(), r.data(), nullptr);
    return r;
  };
  compare_with_central_differences(
      x, ids, options, residual, [&](int k, int j, int i) { return jacobians[k](i, j); }, judge, result);
  return result;
}

JacobianCheckResult check_block_hessian(const ResidualBlock& block, const std::vector<VecX>& values,
                                        const VecX& weights, const JacobianCheckOptions& options) {
  check_options(options);
  require(block.provides_hessian(), "check_block_hessian: block '", block.name(), "' provides no Hessian");
  const auto& ids = block.variables();
  require(values.size() == ids.size(), "check_block_hessian: block '", block.name(), "' touches ", ids.size(),
          " variable blocks, got ", values.size(), " values");
  require(weights.size() == block.num_rows(), "check_block_hessian: block '", block.name(),
          "': ", weights.size(), " weights for ", block.num_rows(), " rows");
  const int rows = block.num_rows();
  std::vector<VecX> x = values;
  std::vector<const double*> value_ptrs(ids.size());
  std::vector<int> start(ids.size() + 1, 0);  // offset of variable k in the stacked local vector
  for (size_t k = 0; k < ids.size(); ++k) {
    value_ptrs[k] = x[k].data();
    start[k + 1] = start[k] + static_cast<int>(values[k].size());
  }
  const int n = start.back();
  // g(x) = J(x)^T weights over the stacked variables.
  std::vector<RowMajorMatX> jacobians(ids.size());
  std::vector<double*> jacobian_ptrs(ids.size());
  VecX c(rows);
  auto weighted_gradient = [&]() {
    VecX g(n);
    for (size_t k = 0; k < ids.size(); ++k) {
      jacobians[k].resize(rows, values[k].size());
      jacobian_ptrs[k] = jacobians[k].data();
    }
    block.evaluate(value_ptrs.data(), c.data(), jacobian_ptrs.data());
    for (size_t k = 0; k < ids.size(); ++k)
      g.segment(start[k], values[k].size()) = jacobians[k].transpose() * weights;
    return g;
  };
  RowMajorMatX H = RowMajorMatX::Constant(n, n, std::nan(""));
  block.evaluate_hessian(value_ptrs.data(), weights.data(), H.data());

  JacobianCheckResult result;
  result.block_name = block.name();
  result.block_kind = block.kind();
  EntryJudge judge{options, result};
  compare_with_central_differences(
      x, ids, options, weighted_gradient, [&](int k, int j, int i) { return H(i, start[k] + j); }, judge,
      result);
  return result;
}

JacobianCheckResult check_problem_jacobian(const Problem& problem, const VecX& x_in,
                                           const JacobianCheckOptions& options) {
  check_options(options);
  const int n = problem.num_variables(), m = problem.num_rows();
  require(x_in.size() == n, "check_problem_jacobian: x has size ", x_in.size(), ", expected ", n);
  // Column -> (variable block, column within it).
  std::vector<int> block_of(n), column_in(n);
  for (VariableId v = 0; v < problem.num_variable_blocks(); ++v) {
    const VariableBlock& b = problem.variable(v);
    for (int j = 0; j < b.size; ++j) {
      block_of[b.offset + j] = v;
      column_in[b.offset + j] = j;
    }
  }
  VecX x = x_in, c(m), c_plus(m), c_minus(m), gradient(n);
  Eigen::SparseMatrix<double, Eigen::RowMajor> J;
  problem.evaluate_residuals_and_jacobian(x, c, J);
  const bool objective = problem.has_objective();
  if (objective) problem.evaluate_objective(x, &gradient);

  JacobianCheckResult result;
  EntryJudge judge{options, result};
  for (int j = 0; j < n; ++j) {
    const double x0 = x[j], h = step_for(x0, options);
    x[j] = x0 + h;
    problem.evaluate_residuals(x, c_plus);
    const double f_plus = objective ? problem.evaluate_objective(x, nullptr) : 0.0;
    x[j] = x0 - h;
    problem.evaluate_residuals(x, c_minus);
    const double f_minus = objective ? problem.evaluate_objective(x, nullptr) : 0.0;
    x[j] = x0;
    auto record_column = [&]() {
      result.variable = block_of[j];
      result.variable_name = problem.variable(block_of[j]).name;
      result.column = column_in[j];
    };
    for (int i = 0; i < m; ++i) {
      if (judge.consider(J.coeff(i, j),  // structural zeros compare as 0
                         (c_plus[i] - c_minus[i]) / (2.0 * h))) {
        const ResidualId b = problem.residual_at_row(i);
        const ResidualBlock& block = problem.residual(b);
        result.block_name = block.name();
        result.block_kind = block.kind();
        result.global_row = i;
        result.row = i - problem.row_offset(b);
        const auto& ids = block.variables();
        const auto it = std::find(ids.begin(), ids.end(), block_of[j]);
        result.variable_index = it == ids.end() ? -1 : static_cast<int>(it - ids.begin());
        record_column();
      }
    }
    if (objective && judge.consider(gradient[j], (f_plus - f_minus) / (2.0 * h))) {
      result.block_name = "objective";
      result.block_kind = "objective";
      result.row = result.global_row = -1;
      result.variable_index = -1;
      record_column();
    }
  }
  return result;
}

}  // namespace pcr
