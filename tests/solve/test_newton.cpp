// Damped Newton: known solutions, singular and infeasible systems, fixed variables, misuse.
#define BOOST_TEST_MODULE newton
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "solve/test_problems.hpp"

using namespace pcr;
using namespace pcr::test;

namespace {

// Circle x^2 + y^2 = 4 and line y = x: analytic roots (+-sqrt 2, +-sqrt 2).
struct CircleLine {
  Problem p;
  VariableId x, y;
  ResidualId circle, line;
  CircleLine(double x0, double y0) {
    x = p.add_variable_block("x", VecX::Constant(1, x0));
    y = p.add_variable_block("y", VecX::Constant(1, y0));
    circle = p.add_residual_block(std::make_shared<CircleBlock>(x, y, 2.0));
    line = p.add_residual_block(std::make_shared<LineBlock>(y, x, 1.0, -1.0, 0.0));
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(circle_and_line_intersection) {
  CircleLine cl(1.0, 0.2);  // infeasible start
  NewtonSolver newton(cl.p);
  VecX x = cl.p.initial_values();
  const SolveSummary s = newton.solve(x);
  BOOST_TEST(s.converged(), s.brief_report());
  BOOST_TEST(s.solver == "newton");
  BOOST_TEST(s.iterations >= 1);
  BOOST_TEST(s.residual_max_abs <= 1e-10);  // NewtonOptions::tolerance default
  // J is well conditioned at the root (|J^-1| ~ 1), so |x - x*| <~ |c| <= 1e-10.
  BOOST_TEST(std::abs(x[0] - std::sqrt(2.0)) <= 1e-9);
  BOOST_TEST(std::abs(x[1] - std::sqrt(2.0)) <= 1e-9);
  BOOST_TEST(s.residual_by_kind.size() == 2u);
  BOOST_TEST(s.wall_time_seconds >= 0.0);
}

BOOST_AUTO_TEST_CASE(fixed_variable_and_inactive_block) {
  CircleLine cl(1.0, 1.0);
  cl.p.set_residual_active(cl.line, false);
  cl.p.fix_variable(cl.x, VecX::Constant(1, 1.0));  // then y = sqrt(4 - 1)
  NewtonSolver newton(cl.p);
  VecX x = VecX::Constant(2, 0.5);
  x[0] = 1.0;  // the caller writes the fixed value (Newton uses the entry of x as it is)
  const SolveSummary s = newton.solve(x);
  BOOST_TEST(s.converged(), s.brief_report());
  BOOST_TEST(x[0] == 1.0);
  BOOST_TEST(std::abs(x[1] - std::sqrt(3.0)) <= 1e-9);  // as above: |x - x*| <~ |c| / |J| with |J| ~ 3.5
}

BOOST_AUTO_TEST_CASE(broyden_tridiagonal_1000) {
  Problem p = broyden_problem(1000);
  NewtonSolver newton(p);
  VecX x = p.initial_values();
  const SolveSummary s = newton.solve(x);
  BOOST_TEST(s.converged(), s.brief_report());
  // Independent check of the residual, written here from the MGH formula.
  double worst = 0.0;
  for (int i = 0; i < 1000; ++i) {
    const double left = i > 0 ? x[i - 1] : 0.0, right = i < 999 ? x[i + 1] : 0.0;
    worst = std::max(worst, std::abs((3.0 - 2.0 * x[i]) * x[i] - left - 2.0 * right + 1.0));
  }
  BOOST_TEST(worst <= 1e-10);  // NewtonOptions::tolerance default
  // Quadratic convergence from x = -1 (the MGH start): a handful of steps, far below max_iterations.
  BOOST_TEST(s.iterations <= 10);
  // Re-solving from the solution takes no step (pattern reused, nothing to do).
  const SolveSummary again = newton.solve(x);
  BOOST_TEST(again.converged());
  BOOST_TEST(again.iterations == 0);
}

BOOST_AUTO_TEST_CASE(singular_jacobian_is_reported) {
  // x + y = 1 and 2x + 2y = 2: consistent but rank 1.
  Problem p;
  const VariableId v = p.add_variable_block("v", VecX::Zero(2));
  p.add_residual_block(
      std::make_shared<LinearBlock>(v, (MatX(2, 2) << 1, 1, 2, 2).finished(), (VecX(2) << 1, 2).finished()));
  NewtonSolver newton(p);
  VecX x = p.initial_values();
  const SolveSummary s = newton.solve(x);
  BOOST_TEST((s.status == SolveStatus::Singular), s.brief_report());
  BOOST_TEST(!s.message.empty());
  BOOST_TEST(x.allFinite());
}

BOOST_AUTO_TEST_CASE(nearly_singular_jacobian_is_reported) {
  // x + y = 1, x + (1 + 1e-14) y = 2: condition number ~ 4e14, the step would be ~1e14.
  Problem p;
  const VariableId v = p.add_variable_block("v", VecX::Zero(2));
  p.add_residual_block(std::make_shared<LinearBlock>(v, (MatX(2, 2) << 1, 1, 1, 1 + 1e-14).finished(),
                                                     (VecX(2) << 1, 2).finished()));
  NewtonSolver newton(p);
  VecX x = p.initial_values();
  const SolveSummary s = newton.solve(x);
  BOOST_TEST((s.status == SolveStatus::Singular), s.brief_report());
}

BOOST_AUTO_TEST_CASE(system_without_real_root_is_not_converged) {
  Problem p;
  const VariableId v = p.add_variable_block("x", VecX::Constant(1, 1.0));
  p.add_residual_block(std::make_shared<SquarePlusOne>(v));
  NewtonSolver newton(p);
  VecX x = p.initial_values();
  const SolveSummary s = newton.solve(x);
  BOOST_TEST(!s.converged(), s.brief_report());
  BOOST_TEST(s.residual_max_abs >= 1.0);  // x^2 + 1 >= 1 everywhere
  BOOST_TEST(x.allFinite());
}

BOOST_AUTO_TEST_CASE(non_finite_residual_is_reported_as_diverged) {
  Problem p;
  const VariableId v = p.add_variable_block("x", VecX::Constant(1, -1.0));  // sqrt(-1): NaN
  p.add_residual_block(std::make_shared<SquareRootBlock>(v));
  NewtonSolver newton(p);
  VecX x = p.initial_values();
  const SolveSummary s = newton.solve(x);
  BOOST_TEST((s.status == SolveStatus::Diverged), s.brief_report());
  BOOST_TEST(std::isinf(s.residual_max_abs));  // a NaN row counts as an infinite violation
  // From x = 1 the same block converges to x = 4 (sqrt(4) = 2).
  x[0] = 1.0;
  const SolveSummary ok = newton.solve(x);
  BOOST_TEST(ok.converged(), ok.brief_report());
  BOOST_TEST(std::abs(x[0] - 4.0) <= 1e-9);  // |dx| = |c| / |c'| = 4 |c| <= 4e-10
}

BOOST_AUTO_TEST_CASE(max_iterations_is_reported) {
  Problem p = broyden_problem(20);
  NewtonOptions options;
  options.max_iterations = 1;  // one step from x = -1 cannot reach 1e-10
  NewtonSolver newton(p, options);
  VecX x = p.initial_values();
  const SolveSummary s = newton.solve(x);
  BOOST_TEST((s.status == SolveStatus::MaxIterations), s.brief_report());
  BOOST_TEST(s.iterations == 1);
}

BOOST_AUTO_TEST_CASE(jacobian_budget_is_reported_and_per_solve) {
  Problem p = broyden_problem(20);
  NewtonSolver newton(p);  // fresh Jacobian every iteration (no reuse): Jacobians = iterations
  VecX x = p.initial_values();
  // From x = -1 the full solve needs more than two Newton steps to reach 1e-10 (quadratic convergence
  // from |r| ~ 1: about 5), so a budget of 2 Jacobians must stop it after exactly 2 iterations.
  const SolveSummary s = newton.solve(x, 50, 2);
  BOOST_TEST((s.status == SolveStatus::MaxIterations), s.brief_report());
  BOOST_TEST(s.iterations == 2);
  BOOST_TEST(s.message.find("2 Jacobian evaluations") != std::string::npos, s.message);
  BOOST_TEST(s.jacobian_evaluations == 2);
  BOOST_TEST(std::isfinite(s.residual_max_abs));
  // The budget holds for that solve only: the next one uses the options again and converges.
  const SolveSummary rest = newton.solve(x);
  BOOST_TEST(rest.converged(), rest.brief_report());
  BOOST_CHECK_THROW(newton.solve(x, 10, -1), InputError);
}

BOOST_AUTO_TEST_CASE(rejects_problems_newton_cannot_solve) {
  Problem objective = hs071_problem();  // objective, bounds, inequality
  BOOST_CHECK_THROW(NewtonSolver{objective}, InputError);
  CircleLine non_square(1.0, 1.0);
  non_square.p.set_residual_active(non_square.line, false);
  BOOST_CHECK_THROW(NewtonSolver{non_square.p}, InputError);
  Problem q;
  const VariableId x = q.add_variable_block("x", VecX::Constant(1, 1.0));
  auto block = std::make_shared<SquarePlusOne>(x);
  block->set_row_bounds(VecX::Constant(1, 0.0), VecX::Constant(1, 2.0));
  q.add_residual_block(block);
  BOOST_CHECK_THROW(NewtonSolver{q}, InputError);
  Problem bounded;
  const VariableId b = bounded.add_variable_block("b", VecX::Constant(1, 0.5), VecX::Zero(1), VecX::Ones(1));
  bounded.add_residual_block(std::make_shared<SquarePlusOne>(b));
  BOOST_CHECK_THROW(NewtonSolver{bounded}, InputError);
  // A structural change after construction is validated at the next solve.
  CircleLine later(1.0, 1.0);
  NewtonSolver newton(later.p);
  later.p.set_residual_active(later.line, false);
  VecX start = later.p.initial_values();
  BOOST_CHECK_THROW(newton.solve(start), InputError);
}

// Warm-started sequence with factorisation reuse (quasi-Newton with Broyden updates on the last LU):
// the Broyden tridiagonal system, n = 200, with x_0 fixed to values along a path and row 0 left out
// (square again). Each solve must reach the same root as a fresh Newton solve, with far fewer
// Jacobian evaluations than solves; also with the Broyden updates carried from solve to solve
// (NewtonSolver::continue_path, as the kinematics do when the path predictor extrapolated the start).
BOOST_AUTO_TEST_CASE(factorisation_reuse_along_a_path_matches_fresh_newton) {
  const int n = 200;
  Problem reused = broyden_problem(n);
  NewtonSolver fresh_newton_on_start(reused);
  VecX x = reused.initial_values();
  BOOST_REQUIRE(fresh_newton_on_start.solve(x).converged());
  reused.set_residual_active(0, false);
  reused.fix_variable(0, x.head(1));
  Problem fresh = reused, carried = reused;
  NewtonOptions reuse_options;
  reuse_options.reuse_factorization = true;
  NewtonSolver quasi(reused, reuse_options), along_path(carried, reuse_options), newton(fresh);
  VecX xq = x, xc = x, xf = x;
  int jacobian_evaluations[2] = {0, 0}, iterations[2] = {0, 0}, steps = 0;
  for (int k = 1; k <= 20; ++k) {
    const VecX x0 = VecX::Constant(1, x[0] + 0.005 * k);
    reused.fix_variable(0, x0);
    carried.fix_variable(0, x0);
    fresh.fix_variable(0, x0);
    xq[0] = xc[0] = xf[0] = x0[0];  // Newton uses the fixed values as they are in x
    along_path.continue_path();
    const SolveSummary sq = quasi.solve(xq), sc = along_path.solve(xc), sf = newton.solve(xf);
    BOOST_TEST_REQUIRE(sf.converged(), sf.brief_report());
    BOOST_TEST(sf.jacobian_evaluations == sf.iterations);  // plain Newton: one per step
    int which = 0;
    for (const auto& [s, xs] : {std::pair<const SolveSummary&, const VecX&>{sq, xq}, {sc, xc}}) {
      BOOST_TEST_REQUIRE(s.converged(), s.brief_report());
      // Both residuals <= 1e-10 (default tolerance) and |J^-1| = O(1) for this diagonally dominant
      // system (|3 - 4 x_i| >= 3 for its root x_i in [-0.6, -0.3], off-diagonals 1 and 2), so the
      // roots agree to a few times 1e-10.
      BOOST_TEST((xs - xf).lpNorm<Eigen::Infinity>() <= 1e-8);
      BOOST_TEST(s.jacobian_evaluations == std::stoi(s.message));  // "N Jacobian evaluations"
      jacobian_evaluations[which] += s.jacobian_evaluations;
      iterations[which++] += s.iterations;
    }
    ++steps;
  }
  BOOST_TEST_MESSAGE("along the path: fresh Jacobians "
                     << jacobian_evaluations[0] << " / " << jacobian_evaluations[1] << ", iterations "
                     << iterations[0] << " / " << iterations[1] << " (updates dropped / carried)");
  BOOST_TEST(jacobian_evaluations[0] < steps / 2);
  BOOST_TEST(jacobian_evaluations[1] < steps / 2);
}
