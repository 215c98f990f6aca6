#include "pcr/rods/rod_solve.hpp"

#include <chrono>
#include <sstream>

#include "pcr/core/error.hpp"
#include "pcr/solve/free_jacobian.hpp"
#include "pcr/solve/ipopt_solver.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "pcr/solve/sparse_lu.hpp"

#include "pcr/splines/basis.hpp"
#include "pcr/splines/spline_curve.hpp"

namespace pcr {
namespace {

SolveSummary solve_at(const CollocationRod& rod, const RodSolveOptions& options, double load_factor, VecX& x,
                      RodVariables& vars) {
  Problem problem;
  vars = rod.add_to_problem(problem, {}, load_factor);
  if (x.size() != problem.num_variables()) x = problem.initial_values();
  if (options.solver == SolverKind::Newton) {
    NewtonOptions o;
    o.tolerance = options.tolerance;
    o.max_iterations = options.max_iterations;
    return NewtonSolver(problem, o).solve(x);
  }
  IpoptOptions o;
  o.tol = options.tolerance;
  o.constraint_tolerance = options.tolerance;
  o.max_iterations = options.max_iterations;
  return IpoptSolver(problem, o).solve(x);
}

// Sign of det J at the unloaded state (load factor 0, the initial guess) and at the solution.
// The unloaded state is the straight initial guess (whatever initial guess the solve itself used).
StabilityIndicator stability_of(const CollocationRod& rod, const VecX& x_solution, double tolerance) {
  Problem unloaded, loaded;
  rod.add_to_problem(unloaded, {}, 0.0);
  rod.add_to_problem(loaded, {}, 1.0);
  const VecX x0 = unloaded.initial_values();
  VecX c;
  unloaded.evaluate_residuals(x0, c);
  if (!(unloaded.constraint_violation(c) <= tolerance)) return StabilityIndicator::NotChecked;
  const int sign0 = jacobian_determinant_sign(unloaded, x0),
            sign1 = jacobian_determinant_sign(loaded, x_solution);
  if (sign0 == 0 || sign1 == 0) return StabilityIndicator::NotChecked;
  return sign0 == sign1 ? StabilityIndicator::SignKept : StabilityIndicator::Unstable;
}

}  // namespace

const char* to_string(StabilityIndicator s) {
  switch (s) {
    case StabilityIndicator::SignKept: return "sign_kept";
    case StabilityIndicator::Unstable: return "unstable";
    default: return "not_checked";
  }
}

const char* to_string(SolverKind solver) {
  return solver == SolverKind::Newton ? "newton" : "ipopt";
}

RodSolution solve_rod(const RodModel& model, const RodSolveOptions& options, const VecX* initial) {
  const auto start = std::chrono::steady_clock::now();
  RodSolution sol;
  sol.rod = std::make_shared<const CollocationRod>(model, options.discretization);
  const CollocationRod& rod = *sol.rod;
  // The direct solve starts from `initial` or the stress-free shape (the straight rod without intrinsic
  // strains); load stepping from `initial` or the straight rod, exact at load factor 0.
  VecX x0;
  {
    Problem probe;
    sol.variables = rod.add_to_problem(probe, {}, 0.0, false, -1, initial);
    x0 = probe.initial_values();
  }
  if (initial) {
    sol.x = x0;
  } else {
    const VecX stress_free = rod.stress_free_configuration();
    Problem probe;
    rod.add_to_problem(probe, {}, 1.0, false, -1, &stress_free);
    sol.x = probe.initial_values();
  }
  sol.summary = solve_at(rod, options, 1.0, sol.x, sol.variables);
  int iterations = sol.summary.iterations;
  // Continuation helps a Newton iteration that is lost far from the solution, not one that stalls at
  // round-off just above the tolerance: then the direct result is reported as it is.
  const bool stalled_near_solution = sol.summary.residual_max_abs < 1e-6;
  if (!sol.summary.converged() && options.load_stepping && !stalled_near_solution) {
    // Continuation: lambda from 0 (the initial guess is exact for zero load when it starts at the
    // clamped end) to 1; step grows by 1.5 after a success and halves after a failure.
    double lambda = 0.0, step = 0.25, previous_step = 0.0;
    VecX x = x0, x_previous = x0;
    SolveSummary last;
    last.status = SolveStatus::Failed;
    int steps = 0;
    while (lambda < 1.0 && steps < options.max_load_steps && step > 1e-7) {
      const double target = std::min(1.0, lambda + step);
      VecX trial = x;
      if (previous_step > 0.0)
        trial += (x - x_previous) * ((target - lambda) / previous_step);  // secant predictor
      last = solve_at(rod, options, target, trial, sol.variables);
      iterations += last.iterations;
      ++steps;
      if (last.converged()) {
        x_previous = x;
        x = trial;
        previous_step = target - lambda;
        lambda = target;
        step *= 1.5;
      } else {
        step *= 0.5;
      }
    }
    sol.load_steps = steps;
    std::ostringstream msg;
    msg << "direct solve failed (" << to_string(sol.summary.status)
        << (sol.summary.message.empty() ? "" : ": " + sol.summary.message) << "); load stepping: " << steps
        << " steps, reached lambda = " << lambda;
    if (lambda >= 1.0 && last.converged()) {
      sol.x = x;
      sol.summary = last;
    } else {
      sol.summary.status = last.status == SolveStatus::Converged ? SolveStatus::MaxIterations : last.status;
    }
    sol.summary.message = msg.str() + (sol.summary.message.empty() ? "" : "; " + sol.summary.message);
  }
  sol.summary.iterations = iterations;
  if (options.check_stability && sol.summary.converged())
    sol.stability = stability_of(rod, sol.x, options.tolerance);
  sol.summary.wall_time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sol;
}

VecX refine_solution(const RodSolution& solution, const RodDiscretization& finer) {
  const CollocationRod& rod = *solution.rod;
  require(finer.formulation == rod.discretization().formulation,
          "refine_solution: the formulation must stay the same (",
          to_string(rod.discretization().formulation), ")");
  // Interpolation of the solution's spline at the Greville abscissae of the new basis: exact (up to
  // round-off) when the new space contains the old one (knot insertion), otherwise accurate to the
  // interpolation error, which is all an initial guess needs.
  const CollocationRod target(rod.model(), finer);
  const std::vector<double> tau = target.knots().greville();
  const int n_old = rod.num_control_points(), cp = rod.control_point_size();
  MatX points(cp, n_old);
  for (int i = 0; i < n_old; ++i)
    points.col(i) = solution.x.segment(solution.variables.control_point_offset + i * cp, cp);
  const SplineCurve curve(rod.knots(), points);
  const int n = target.num_control_points();
  MatX values(n, cp);
  for (int j = 0; j < n; ++j) values.row(j) = curve.evaluate(tau[j]).transpose();
  SparseLu lu;
  require(lu.compute(collocation_matrix(target.knots(), tau, 0)),
          "refine_solution: Greville interpolation matrix is singular");
  const MatX refined = lu.solve(values);  // n x cp
  VecX out(n * cp);
  for (int j = 0; j < n; ++j) out.segment(j * cp, cp) = refined.row(j).transpose();
  return out;
}

}  // namespace pcr
