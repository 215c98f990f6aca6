// Damped Newton on a Problem: the shared Newton loop on the Problem's system (see newton_solver.hpp).
#include "pcr/solve/newton_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/solve/newton_loop.hpp"
#include "problem_system.hpp"

namespace pcr {

namespace {
NewtonLoopOptions loop_options(const NewtonOptions& o) {
  NewtonLoopOptions l;
  l.tolerance = o.tolerance;
  l.max_iterations = o.max_iterations;
  l.armijo = o.armijo;
  l.backtrack = o.backtrack;
  l.min_step = o.min_step;
  l.natural_monotonicity = true;
  l.quasi_newton = o.reuse_factorization ? QuasiNewtonKind::Broyden : QuasiNewtonKind::None;
  l.broyden_contraction = o.chord_contraction;
  return l;
}
}  // namespace

struct NewtonSolver::Impl {
  const Problem& problem;
  NewtonOptions options;
  ProblemSystem system;
  NewtonLoop loop;

  Impl(const Problem& p, const NewtonOptions& o)
      : problem(p), options(o), system(p, options), loop(loop_options(o)) {}
};

NewtonSolver::NewtonSolver(const Problem& problem, NewtonOptions options) {
  require(options.tolerance > 0.0, "NewtonOptions: tolerance = ", options.tolerance, " <= 0");
  require(options.max_iterations >= 0, "NewtonOptions: max_iterations = ", options.max_iterations, " < 0");
  require(options.armijo > 0.0 && options.armijo < 1.0, "NewtonOptions: armijo = ", options.armijo,
          " not in (0, 1)");
  require(options.backtrack > 0.0 && options.backtrack < 1.0,
          "NewtonOptions: backtrack = ", options.backtrack, " not in (0, 1)");
  require(options.min_step > 0.0 && options.min_step < 1.0, "NewtonOptions: min_step = ", options.min_step,
          " not in (0, 1)");
  impl_ = std::make_unique<Impl>(problem, options);
  impl_->system.prepare();
}

NewtonSolver::~NewtonSolver() = default;

void NewtonSolver::continue_path() {
  impl_->loop.continue_path();
}

const NewtonOptions& NewtonSolver::options() const {
  return impl_->options;
}

const char* NewtonSolver::factorization_kind() const {
  return impl_->system.factorization_kind();
}

SolveSummary NewtonSolver::solve(VecX& x) {
  return solve(x, impl_->options.max_iterations);
}

SolveSummary NewtonSolver::solve(VecX& x, int max_iterations, int max_jacobian_evaluations) {
  const auto start_time = std::chrono::steady_clock::now();
  Impl& w = *impl_;
  require(max_iterations >= 0, "NewtonSolver::solve: max_iterations = ", max_iterations, " < 0");
  require(max_jacobian_evaluations >= 0,
          "NewtonSolver::solve: max_jacobian_evaluations = ", max_jacobian_evaluations, " < 0");
  w.system.prepare();
  const Problem& problem = w.problem;
  require(x.size() == problem.num_variables(), "NewtonSolver::solve: x has size ", x.size(), ", expected ",
          problem.num_variables());

  SolveSummary summary;
  summary.solver = "newton";
  const VecX* constraints = &w.system.constraints();
  VecX not_finite;
  if (!x.allFinite()) {
    summary.status = SolveStatus::InvalidInput;
    summary.message = "start point is not finite";
    not_finite.setConstant(problem.num_rows(), std::numeric_limits<double>::infinity());
    constraints = &not_finite;
  } else {
    w.system.bind(x);
    const NewtonLoopResult result =
        w.loop.run(w.system, {max_iterations, max_jacobian_evaluations}, w.options.reuse_factorization);
    summary.status = result.status;
    summary.message = result.message;
    summary.iterations = result.iterations;
    summary.jacobian_evaluations = result.jacobian_evaluations;
    summary.residual_round_off = result.round_off_bound;
    if (summary.converged() && w.options.reuse_factorization)
      summary.message = std::to_string(result.jacobian_evaluations) + " Jacobian evaluation" +
                        (result.jacobian_evaluations == 1 ? "" : "s") +
                        (result.message.empty() ? "" : "; " + result.message);
  }
  summary.residual_by_kind = problem.violation_by_kind(*constraints);
  summary.residual_max_abs = 0.0;  // = problem.constraint_violation(c), without a second pass
  for (const auto& kind : summary.residual_by_kind)
    summary.residual_max_abs = std::max(summary.residual_max_abs, kind.second);
  // Never report a non-finite point as converged.
  if (summary.converged() && !(x.allFinite() && std::isfinite(summary.residual_max_abs)))
    summary.status = SolveStatus::Diverged;
  summary.wall_time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return summary;
}

bool residuals_within_round_off(const Eigen::SparseMatrix<double, Eigen::RowMajor>& J, const VecX& x,
                                const VecX& scale, const VecX& r, double tolerance, double& bound) {
  bound = 0.0;
  if (J.rows() != r.size() || J.cols() != x.size() || scale.size() != x.size() || J.nonZeros() == 0)
    return false;
  constexpr double kUnitRoundoffs = 2.0 * std::numeric_limits<double>::epsilon();
  for (int i = 0; i < r.size(); ++i) {
    if (!(std::abs(r[i]) > tolerance)) continue;
    double sensitivity = 0.0;  // sum_j |J_ij x_j|
    double magnitude = 1.0;    // max(1, max_j |x_j| / scale_j)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(J, i); it; ++it) {
      const double xj = std::abs(x[it.col()]);
      sensitivity += std::abs(it.value()) * xj;
      magnitude = std::max(magnitude, xj / scale[it.col()]);
    }
    const double row_bound = kUnitRoundoffs * sensitivity;
    if (!(std::abs(r[i]) <= row_bound) || !(std::abs(r[i]) <= kRoundOffTolerances * tolerance * magnitude))
      return false;
    bound = std::max(bound, row_bound);
  }
  return true;
}

}  // namespace pcr
