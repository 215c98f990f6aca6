#pragma once
// The Ipopt TNLP of IpoptSolver (internal header of pcr::core): every callback delegates to Problem; c
// and J are cached per point. Fixed variables reach Ipopt as variables with equal bounds (the values of
// the start x, ipopt_solver.cpp), which it makes parameters.
#include <coin/IpTNLP.hpp>

#include <algorithm>
#include <cmath>

#include "pcr/solve/problem.hpp"

namespace pcr::ipopt_internal {

using SparseRowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using Ipopt::Index;
using Ipopt::Number;

// Ipopt treats |bound| >= 1e19 as "no bound" (nlp_lower/upper_bound_inf defaults).
inline double ipopt_bound(double b) {
  return std::max(-1e20, std::min(1e20, b));
}

class ProblemNlp : public Ipopt::TNLP {
 public:
  explicit ProblemNlp(const Problem& problem) : problem_(problem) {}

  // Set by IpoptSolver before each solve.
  const VecX* start = nullptr;
  bool warm = false;
  bool exact_hessian = false;
  VecX x_lower, x_upper, c_lower, c_upper;
  // Primal-dual result of the last solve (also the warm start of the next).
  VecX x_final, z_lower, z_upper, lambda;
  bool have_multipliers = false;

  // Analyses the Jacobian (and, if exact, the Hessian) pattern at x.
  void analyse(const VecX& x) {
    problem_.evaluate_residuals_and_jacobian(x, c_, J_);
    x_.resize(x.size());
    if (exact_hessian) {
      multipliers_ = VecX::Zero(problem_.num_rows());
      problem_.evaluate_hessian(x, 1.0, multipliers_, H_);
    } else {
      H_ = SparseRowMajor();
    }
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = problem_.num_variables();
    m = problem_.num_rows();
    nnz_jac_g = static_cast<Index>(J_.nonZeros());
    nnz_h_lag = exact_hessian ? static_cast<Index>(H_.nonZeros()) : 0;
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    for (Index j = 0; j < n; ++j) {
      x_l[j] = ipopt_bound(x_lower[j]);
      x_u[j] = ipopt_bound(x_upper[j]);
    }
    for (Index i = 0; i < m; ++i) {
      g_l[i] = ipopt_bound(c_lower[i]);
      g_u[i] = ipopt_bound(c_upper[i]);
    }
    return true;
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number* z_L, Number* z_U, Index m,
                          bool init_lambda, Number* lambda_out) override {
    if (init_x) std::copy(start->data(), start->data() + n, x);
    if (init_z) {
      if (!have_multipliers) return false;
      std::copy(z_lower.data(), z_lower.data() + n, z_L);
      std::copy(z_upper.data(), z_upper.data() + n, z_U);
    }
    if (init_lambda) {
      if (!have_multipliers) return false;
      std::copy(lambda.data(), lambda.data() + m, lambda_out);
    }
    return true;
  }

  bool eval_f(Index n, const Number* x, bool new_x, Number& obj_value) override {
    if (!problem_.has_objective()) {
      obj_value = 0.0;
      return true;
    }
    load(n, x, new_x);
    obj_value = problem_.evaluate_objective(x_, nullptr);
    return std::isfinite(obj_value);
  }

  bool eval_grad_f(Index n, const Number* x, bool new_x, Number* grad_f) override {
    if (!problem_.has_objective()) {
      std::fill(grad_f, grad_f + n, 0.0);
      return true;
    }
    load(n, x, new_x);
    problem_.evaluate_objective(x_, &gradient_);
    std::copy(gradient_.data(), gradient_.data() + n, grad_f);
    return gradient_.allFinite();
  }

  bool eval_g(Index n, const Number* x, bool new_x, Index m, Number* g) override {
    load(n, x, new_x);
    if (!c_valid_) {
      problem_.evaluate_residuals(x_, c_);
      c_valid_ = true;
    }
    std::copy(c_.data(), c_.data() + m, g);
    return c_.allFinite();
  }

  bool eval_jac_g(Index n, const Number* x, bool new_x, Index, Index nele_jac, Index* iRow, Index* jCol,
                  Number* values) override {
    if (!values) {  // structure: the row-major compressed order of J
      Index e = 0;
      for (int i = 0; i < J_.outerSize(); ++i) {
        for (int p = J_.outerIndexPtr()[i]; p < J_.outerIndexPtr()[i + 1]; ++p, ++e) {
          iRow[e] = i;
          jCol[e] = J_.innerIndexPtr()[p];
        }
      }
      return e == nele_jac;
    }
    load(n, x, new_x);
    if (!J_valid_) {
      problem_.evaluate_residuals_and_jacobian(x_, c_, J_);
      ++jacobian_evaluations;
      c_valid_ = J_valid_ = true;
    }
    std::copy(J_.valuePtr(), J_.valuePtr() + nele_jac, values);
    return std::all_of(values, values + nele_jac, [](double v) { return std::isfinite(v); });
  }

  bool eval_h(Index n, const Number* x, bool new_x, Number obj_factor, Index m, const Number* lambda_in, bool,
              Index nele_hess, Index* iRow, Index* jCol, Number* values) override {
    if (!exact_hessian) return false;
    if (!values) {  // lower triangle, row-major compressed order
      Index e = 0;
      for (int i = 0; i < H_.outerSize(); ++i) {
        for (int p = H_.outerIndexPtr()[i]; p < H_.outerIndexPtr()[i + 1]; ++p, ++e) {
          iRow[e] = i;
          jCol[e] = H_.innerIndexPtr()[p];
        }
      }
      return e == nele_hess;
    }
    load(n, x, new_x);
    std::copy(lambda_in, lambda_in + m, multipliers_.data());
    problem_.evaluate_hessian(x_, obj_factor, multipliers_, H_);
    std::copy(H_.valuePtr(), H_.valuePtr() + nele_hess, values);
    return std::all_of(values, values + nele_hess, [](double v) { return std::isfinite(v); });
  }

  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number* z_L, const Number* z_U,
                         Index m, const Number*, const Number* lambda_in, Number, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    x_final = Eigen::Map<const VecX>(x, n);
    z_lower = Eigen::Map<const VecX>(z_L, n);
    z_upper = Eigen::Map<const VecX>(z_U, n);
    lambda = Eigen::Map<const VecX>(lambda_in, m);
    have_multipliers =
        x_final.allFinite() && z_lower.allFinite() && z_upper.allFinite() && lambda.allFinite();
    has_final = true;
  }

  bool has_final = false;

  /// Forget the per-point caches (a new solve may revisit the last point of the previous one).
  void begin_solve() {
    loaded_ = false;
    has_final = false;
    jacobian_evaluations = 0;
  }
  int jacobian_evaluations = 0;  ///< of the current solve

 private:
  // Copies Ipopt's point into x_ (Problem takes a VecX) and invalidates the caches at a new point.
  void load(Index n, const Number* x, bool new_x) {
    if (new_x || !loaded_) {
      std::copy(x, x + n, x_.data());
      c_valid_ = J_valid_ = false;
      loaded_ = true;
    }
  }

  const Problem& problem_;
  VecX x_, c_, gradient_, multipliers_;
  SparseRowMajor J_, H_;
  bool loaded_ = false, c_valid_ = false, J_valid_ = false;
};

}  // namespace pcr::ipopt_internal
