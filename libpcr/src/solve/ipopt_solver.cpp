// Ipopt adapter: a TNLP that only delegates to Problem, one IpoptApplication reused across solves.
#include "pcr/solve/ipopt_solver.hpp"

#include <coin/IpIpoptApplication.hpp>
#include <coin/IpRegOptions.hpp>
#include <coin/IpSolveStatistics.hpp>
#include <coin/IpTNLP.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "pcr/core/error.hpp"

namespace pcr {

namespace {

using SparseRowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using Ipopt::Index;
using Ipopt::Number;

// Ipopt treats |bound| >= 1e19 as "no bound" (nlp_lower/upper_bound_inf defaults).
double ipopt_bound(double b) {
  return std::max(-1e20, std::min(1e20, b));
}

const char* ipopt_status_name(Ipopt::ApplicationReturnStatus s) {
  switch (s) {
    case Ipopt::Solve_Succeeded: return "Solve_Succeeded";
    case Ipopt::Solved_To_Acceptable_Level: return "Solved_To_Acceptable_Level";
    case Ipopt::Infeasible_Problem_Detected: return "Infeasible_Problem_Detected";
    case Ipopt::Search_Direction_Becomes_Too_Small: return "Search_Direction_Becomes_Too_Small";
    case Ipopt::Diverging_Iterates: return "Diverging_Iterates";
    case Ipopt::User_Requested_Stop: return "User_Requested_Stop";
    case Ipopt::Feasible_Point_Found: return "Feasible_Point_Found";
    case Ipopt::Maximum_Iterations_Exceeded: return "Maximum_Iterations_Exceeded";
    case Ipopt::Restoration_Failed: return "Restoration_Failed";
    case Ipopt::Error_In_Step_Computation: return "Error_In_Step_Computation";
    case Ipopt::Maximum_CpuTime_Exceeded: return "Maximum_CpuTime_Exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom: return "Not_Enough_Degrees_Of_Freedom";
    case Ipopt::Invalid_Problem_Definition: return "Invalid_Problem_Definition";
    case Ipopt::Invalid_Option: return "Invalid_Option";
    case Ipopt::Invalid_Number_Detected: return "Invalid_Number_Detected";
    case Ipopt::Unrecoverable_Exception: return "Unrecoverable_Exception";
    case Ipopt::NonIpopt_Exception_Thrown: return "NonIpopt_Exception_Thrown";
    case Ipopt::Insufficient_Memory: return "Insufficient_Memory";
    case Ipopt::Internal_Error: return "Internal_Error";
  }
  return "unknown Ipopt status";
}

// Status implied by Ipopt's return code alone (before our own feasibility check).
SolveStatus map_ipopt_status(Ipopt::ApplicationReturnStatus s) {
  switch (s) {
    case Ipopt::Solve_Succeeded:
    case Ipopt::Solved_To_Acceptable_Level:
    case Ipopt::Feasible_Point_Found: return SolveStatus::Converged;
    case Ipopt::Infeasible_Problem_Detected: return SolveStatus::Infeasible;
    case Ipopt::Diverging_Iterates: return SolveStatus::Diverged;
    case Ipopt::Maximum_Iterations_Exceeded:
    case Ipopt::Maximum_CpuTime_Exceeded: return SolveStatus::MaxIterations;
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
    case Ipopt::Invalid_Problem_Definition:
    case Ipopt::Invalid_Option: return SolveStatus::InvalidInput;
    default: return SolveStatus::Failed;  // tiny step, restoration failure, step error, exceptions, ...
  }
}

// The TNLP: every callback delegates to Problem; c and J are cached per point (new_x).
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

}  // namespace

struct IpoptSolver::Impl {
  const Problem& problem;
  IpoptOptions options;
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app;
  Ipopt::SmartPtr<ProblemNlp> nlp;
  std::uint64_t version = 0;  // structure of the last Ipopt solve (0: none yet)
  bool last_exact = false;
  VecX c;

  Impl(const Problem& p, IpoptOptions o) : problem(p), options(std::move(o)) {}
};

IpoptSolver::IpoptSolver(const Problem& problem, IpoptOptions options)
    : impl_(std::make_unique<Impl>(problem, std::move(options))) {
  const IpoptOptions& o = impl_->options;
  require(o.tol > 0.0, "IpoptOptions: tol = ", o.tol, " <= 0");
  require(o.constraint_tolerance > 0.0, "IpoptOptions: constraint_tolerance = ", o.constraint_tolerance,
          " <= 0");
  require(o.max_iterations >= 0, "IpoptOptions: max_iterations = ", o.max_iterations, " < 0");
  require(o.print_level >= 0 && o.print_level <= 12, "IpoptOptions: print_level = ", o.print_level,
          " not in [0, 12]");
  require(o.warm_start_mu > 0.0, "IpoptOptions: warm_start_mu = ", o.warm_start_mu, " <= 0");
  Impl& w = *impl_;
  w.app = IpoptApplicationFactory();
  w.app->RethrowNonIpoptException(false);
  // Checked against the registered settings first: Ipopt would print its own complaint to stdout.
  require(w.app->RegOptions()->GetOption("linear_solver")->IsValidStringSetting(o.linear_solver),
          "IpoptOptions: linear_solver = '", o.linear_solver, "' is not available in this Ipopt");
  Ipopt::OptionsList& opts = *w.app->Options();
  bool ok =
      opts.SetStringValue("sb", "yes") && opts.SetIntegerValue("print_level", o.print_level) &&
      opts.SetNumericValue("tol", o.tol) && opts.SetNumericValue("constr_viol_tol", o.constraint_tolerance) &&
      opts.SetIntegerValue("acceptable_iter", 0) && opts.SetIntegerValue("max_iter", o.max_iterations) &&
      opts.SetStringValue("linear_solver", o.linear_solver) &&
      opts.SetStringValue("nlp_scaling_method",
                          o.scaling == IpoptScaling::None ? "none" : "gradient-based") &&
      opts.SetStringValue("fixed_variable_treatment", "make_parameter") &&
      opts.SetStringValue("honor_original_bounds", "yes") &&
      // Ipopt relaxes every bound by 1e-8 max(1, |bound|) by default, so a "converged" inequality
      // such as c >= 25 may be violated by 2.5e-7 > constr_viol_tol: keep the bounds exact.
      opts.SetNumericValue("bound_relax_factor", 0.0);
  require(ok, "IpoptSolver: Ipopt rejected an option (linear_solver = '", o.linear_solver, "'?)");
  for (const auto& [name, value] : o.extra_options) {
    const Ipopt::SmartPtr<const Ipopt::RegisteredOption> option = w.app->RegOptions()->GetOption(name);
    require(Ipopt::IsValid(option), "IpoptOptions::extra_options: unknown Ipopt option '", name, "'");
    char* end = nullptr;
    bool set = false;
    if (option->Type() == Ipopt::OT_Integer) {
      const long integer = std::strtol(value.c_str(), &end, 10);
      set = !value.empty() && *end == '\0' && opts.SetIntegerValue(name, static_cast<Index>(integer));
    } else if (option->Type() == Ipopt::OT_Number) {
      const double number = std::strtod(value.c_str(), &end);
      set = !value.empty() && *end == '\0' && opts.SetNumericValue(name, number);
    } else {
      set = option->IsValidStringSetting(value) && opts.SetStringValue(name, value);  // quiet check first
    }
    require(set, "IpoptOptions::extra_options: Ipopt rejected option '", name, "' = '", value, "'");
  }
  const Ipopt::ApplicationReturnStatus status = w.app->Initialize("");
  require(status == Ipopt::Solve_Succeeded,
          "IpoptSolver: Ipopt initialisation failed: ", ipopt_status_name(status));
  w.nlp = new ProblemNlp(problem);
}

IpoptSolver::~IpoptSolver() = default;
const IpoptOptions& IpoptSolver::options() const {
  return impl_->options;
}
void IpoptSolver::reset_warm_start() {
  impl_->nlp->have_multipliers = false;
}

SolveSummary IpoptSolver::solve(VecX& x) {
  const auto start_time = std::chrono::steady_clock::now();
  Impl& w = *impl_;
  const Problem& problem = w.problem;
  const IpoptOptions& o = w.options;
  require(x.size() == problem.num_variables(), "IpoptSolver::solve: x has size ", x.size(), ", expected ",
          problem.num_variables());
  SolveSummary summary;
  summary.solver = "ipopt";
  if (!x.allFinite()) {
    summary.status = SolveStatus::InvalidInput;
    summary.message = "start point is not finite";
    summary.residual_max_abs = std::numeric_limits<double>::infinity();
    return summary;
  }
  ProblemNlp& nlp = *w.nlp;
  // Fixed entries take their values; bounds are read per solve (they may change without a new structure).
  for (VariableId v = 0; v < problem.num_variable_blocks(); ++v) {
    if (problem.variable_fixed(v))
      x.segment(problem.variable(v).offset, problem.variable(v).size) = problem.variable(v).lower;
  }
  nlp.x_lower = problem.variable_lower();
  nlp.x_upper = problem.variable_upper();
  nlp.c_lower = problem.row_lower();
  nlp.c_upper = problem.row_upper();
  nlp.start = &x;
  const bool exact = o.hessian == IpoptHessian::ExactWhenAvailable && problem.provides_hessian();
  const bool same_structure = w.version == problem.structure_version() && w.last_exact == exact;
  if (!same_structure) {
    nlp.exact_hessian = exact;
    nlp.analyse(x);
    nlp.have_multipliers = false;  // multipliers of another structure are meaningless
  }
  const bool warm = o.warm_start && nlp.have_multipliers;
  Ipopt::OptionsList& opts = *w.app->Options();
  opts.SetStringValue("hessian_approximation", exact ? "exact" : "limited-memory");
  opts.SetStringValue("warm_start_init_point", warm ? "yes" : "no");
  // Warm start: the previous solution is near-optimal, so start the barrier parameter small and keep
  // the iterate and multipliers close to where they were (Ipopt's warm_start_* pushes).
  opts.SetNumericValue("mu_init", warm ? o.warm_start_mu : 0.1);
  opts.SetNumericValue("warm_start_bound_push", 1e-9);
  opts.SetNumericValue("warm_start_mult_bound_push", 1e-9);
  opts.SetNumericValue("warm_start_slack_bound_push", 1e-9);
  nlp.begin_solve();
  Ipopt::SmartPtr<Ipopt::TNLP> tnlp = Ipopt::GetRawPtr(w.nlp);
  const Ipopt::ApplicationReturnStatus status =
      same_structure ? w.app->ReOptimizeTNLP(tnlp) : w.app->OptimizeTNLP(tnlp);
  w.version = problem.structure_version();
  w.last_exact = exact;

  if (nlp.has_final && nlp.x_final.size() == x.size()) x = nlp.x_final;
  Ipopt::SmartPtr<Ipopt::SolveStatistics> stats = w.app->Statistics();
  summary.iterations = Ipopt::IsValid(stats) ? stats->IterationCount() : 0;
  summary.jacobian_evaluations = nlp.jacobian_evaluations;

  // Our own, unscaled verdict.
  problem.evaluate_residuals(x, w.c);
  summary.residual_max_abs = problem.constraint_violation(w.c);
  summary.residual_by_kind = problem.violation_by_kind(w.c);
  if (problem.has_objective()) summary.objective = problem.evaluate_objective(x, nullptr);
  const bool finite =
      x.allFinite() && std::isfinite(summary.residual_max_abs) && std::isfinite(summary.objective);
  const bool feasible = finite && summary.residual_max_abs <= o.constraint_tolerance;
  const char* ipopt_name = ipopt_status_name(status);
  char buffer[256];
  SolveStatus mapped = map_ipopt_status(status);
  if (!problem.has_objective() && feasible) {
    // Zero objective: every feasible point is a solution, whatever Ipopt's stopping reason.
    mapped = SolveStatus::Converged;
    std::snprintf(buffer, sizeof buffer, "Ipopt: %s", ipopt_name);
  } else if (mapped == SolveStatus::Converged && !feasible) {
    mapped = finite ? SolveStatus::Failed : SolveStatus::Diverged;
    std::snprintf(buffer, sizeof buffer, "Ipopt: %s, but unscaled |c|max = %.3g > constraint_tolerance %.3g",
                  ipopt_name, summary.residual_max_abs, o.constraint_tolerance);
  } else {
    std::snprintf(buffer, sizeof buffer, "Ipopt: %s", ipopt_name);
  }
  if (!finite && mapped == SolveStatus::Converged) mapped = SolveStatus::Diverged;
  summary.status = mapped;
  summary.message = buffer;
  summary.wall_time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return summary;
}

}  // namespace pcr
