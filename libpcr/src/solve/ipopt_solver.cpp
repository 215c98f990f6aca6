// Ipopt adapter: a TNLP that only delegates to Problem, one IpoptApplication reused across solves.
#include "pcr/solve/ipopt_solver.hpp"

#include <coin/IpIpoptApplication.hpp>
#include <coin/IpRegOptions.hpp>
#include <coin/IpSolveStatistics.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "ipopt_nlp.hpp"
#include "pcr/core/error.hpp"

namespace pcr {

namespace {

using Ipopt::Index;
using ipopt_internal::ProblemNlp;

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

// Sets each (name, value) by the option's registered type; InputError for an unknown or rejected one.
void set_extra_options(Ipopt::IpoptApplication& app,
                       const std::vector<std::pair<std::string, std::string>>& extra_options) {
  Ipopt::OptionsList& opts = *app.Options();
  for (const auto& [name, value] : extra_options) {
    const Ipopt::SmartPtr<const Ipopt::RegisteredOption> option = app.RegOptions()->GetOption(name);
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
}

// The outcome from Ipopt's return status and our own, unscaled verdict at x: converged only if the
// violation is within constraint_tolerance and everything is finite (fills status, residuals, objective
// and message).
void judge(const Problem& problem, const VecX& x, Ipopt::ApplicationReturnStatus status,
           double constraint_tolerance, VecX& c, SolveSummary& summary) {
  problem.evaluate_residuals(x, c);
  summary.residual_max_abs = problem.constraint_violation(c);
  summary.residual_by_kind = problem.violation_by_kind(c);
  if (problem.has_objective()) summary.objective = problem.evaluate_objective(x, nullptr);
  const bool finite =
      x.allFinite() && std::isfinite(summary.residual_max_abs) && std::isfinite(summary.objective);
  const bool feasible = finite && summary.residual_max_abs <= constraint_tolerance;
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
                  ipopt_name, summary.residual_max_abs, constraint_tolerance);
  } else {
    std::snprintf(buffer, sizeof buffer, "Ipopt: %s", ipopt_name);
  }
  if (!finite && mapped == SolveStatus::Converged) mapped = SolveStatus::Diverged;
  summary.status = mapped;
  summary.message = buffer;
}

// Bounds of the solve at start x: read per solve (they may change without a new structure); a fixed
// variable is a constant at the value x holds (Ipopt makes a variable with equal bounds a parameter).
void set_bounds(const Problem& problem, const VecX& x, ProblemNlp& nlp) {
  nlp.x_lower = problem.variable_lower();
  nlp.x_upper = problem.variable_upper();
  for (VariableId v = 0; v < problem.num_variable_blocks(); ++v) {
    if (!problem.variable_fixed(v)) continue;
    const VariableBlock& b = problem.variable(v);
    nlp.x_lower.segment(b.offset, b.size) = x.segment(b.offset, b.size);
    nlp.x_upper.segment(b.offset, b.size) = x.segment(b.offset, b.size);
  }
  nlp.c_lower = problem.row_lower();
  nlp.c_upper = problem.row_upper();
}

// Hessian and warm-start options of one solve.
void set_solve_options(Ipopt::OptionsList& opts, const IpoptOptions& o, bool exact, bool warm) {
  opts.SetStringValue("hessian_approximation", exact ? "exact" : "limited-memory");
  opts.SetStringValue("warm_start_init_point", warm ? "yes" : "no");
  // Warm start: the previous solution is near-optimal, so start the barrier parameter small and keep
  // the iterate and multipliers close to where they were (Ipopt's warm_start_* pushes).
  opts.SetNumericValue("mu_init", warm ? o.warm_start_mu : 0.1);
  opts.SetNumericValue("warm_start_bound_push", 1e-9);
  opts.SetNumericValue("warm_start_mult_bound_push", 1e-9);
  opts.SetNumericValue("warm_start_slack_bound_push", 1e-9);
}

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
  set_extra_options(*w.app, o.extra_options);
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
VecX IpoptSolver::constraint_multipliers() const {
  return impl_->nlp->have_multipliers ? impl_->nlp->lambda : VecX();
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
  set_bounds(problem, x, nlp);
  nlp.start = &x;
  const bool exact = o.hessian == IpoptHessian::ExactWhenAvailable && problem.provides_hessian();
  const bool same_structure = w.version == problem.structure_version() && w.last_exact == exact;
  if (!same_structure) {
    nlp.exact_hessian = exact;
    nlp.analyse(x);
    nlp.have_multipliers = false;  // multipliers of another structure are meaningless
  }
  set_solve_options(*w.app->Options(), o, exact, o.warm_start && nlp.have_multipliers);
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

  judge(problem, x, status, o.constraint_tolerance, w.c, summary);
  summary.wall_time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return summary;
}

}  // namespace pcr
