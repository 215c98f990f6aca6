// Damped Newton: known solutions, singular and infeasible systems, fixed variables, misuse, the pattern
// analysis solvers share. The Newton loop on small dense systems: test_newton_loop.cpp (same executable).
#define BOOST_TEST_MODULE newton
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

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

// A tolerance no double-precision point meets: on the line y = x (exact in doubles) the circle's
// residual x^2 + y^2 - 4 is at least 8.9e-16 in magnitude (2 fl(sqrt 2)^2 = 4 + 8.9e-16: no double
// squares to 2), and off it the line's residual y - x is at least 1 ulp of sqrt 2, 2.2e-16. Against a
// tolerance of 2e-16 Newton reports convergence to the round-off: every row above the tolerance within
// 2 eps sum_j |J_ij x_j| (circle 2 eps (2 x^2 + 2 y^2) = 16 eps, line 2 eps (|x| + |y|) = 5.7 eps) and
// within 10 x the tolerance (kRoundOffTolerances). Against 1e-18 that is 890 x the tolerance: not
// converged.
BOOST_AUTO_TEST_CASE(converged_to_the_round_off_of_the_residuals) {
  const double eps = std::numeric_limits<double>::epsilon();
  CircleLine cl(1.0, 0.2);
  NewtonOptions o;
  o.tolerance = 2e-16;
  NewtonSolver newton(cl.p, o);
  VecX x = cl.p.initial_values();
  const SolveSummary s = newton.solve(x);
  BOOST_TEST(s.converged(), s.brief_report());
  BOOST_TEST(s.residual_max_abs > o.tolerance);
  BOOST_TEST(s.residual_max_abs <= kRoundOffTolerances * o.tolerance);
  BOOST_TEST(s.residual_round_off >= 5.0 * eps);  // the smaller row bound, to rounding of the Jacobian
  BOOST_TEST(s.residual_round_off <= 16.0 * eps * (1.0 + 1e-6));
  BOOST_TEST(s.residual_max_abs <= s.residual_round_off);
  BOOST_TEST(s.message.find("round-off") != std::string::npos, s.message);
  // Within 2 units in the last place of sqrt 2 (|J^-1| ~ 1/4 times the residual's round-off).
  BOOST_TEST(std::abs(x[0] - std::sqrt(2.0)) <= 4.5e-16);
  BOOST_TEST(std::abs(x[1] - std::sqrt(2.0)) <= 4.5e-16);
  // Far below the round-off the solve is not converged, and says why.
  CircleLine strict(1.0, 0.2);
  o.tolerance = 1e-18;
  NewtonSolver strict_newton(strict.p, o);
  VecX y = strict.p.initial_values();
  const SolveSummary t = strict_newton.solve(y);
  BOOST_TEST(!t.converged(), t.brief_report());
  BOOST_TEST(t.residual_round_off == 0.0);
  BOOST_TEST(!t.message.empty());
  // At the default tolerance the same solve converges within it and reports no round-off bound.
  CircleLine plain(1.0, 0.2);
  NewtonSolver plain_newton(plain.p);
  VecX z = plain.p.initial_values();
  const SolveSummary u = plain_newton.solve(z);
  BOOST_TEST(u.converged(), u.brief_report());
  BOOST_TEST(u.residual_round_off == 0.0);
}

// Rows at their round-off bound above 10 x the tolerance, by hand (residuals_within_round_off). A balance
// of two forces of 2e4 N, r = 1e3 (x0 - x1): bound 2 eps 4e7 = 1.78e-8 above r = 3e-9; accepted when
// the forces are large against their scale (ones: 2e4; a force scale 0.3 N: 6.7e4; either way up to
// 10 x 1e-10 x that), refused when the same values are of their natural size (scale 1e5: 1e-9 < 3e-9).
// A stiff row of unknowns of natural size, r = 1e9 (x0 - x1) at x = 0.5: bound 4.4e-7, refused. A
// residual above its bound is refused whatever the scale.
BOOST_AUTO_TEST_CASE(round_off_above_ten_tolerances_accepted_for_large_unknowns_only) {
  const double eps = std::numeric_limits<double>::epsilon();
  const auto row = [](double a) {
    Eigen::SparseMatrix<double, Eigen::RowMajor> J(1, 2);
    J.insert(0, 0) = a;
    J.insert(0, 1) = -a;
    J.makeCompressed();
    return J;
  };
  const VecX forces = VecX::Constant(2, 2e4), r = VecX::Constant(1, 3e-9);
  const double tolerance = 1e-10;
  double bound = -1.0;
  for (const VecX& scale : {VecX(VecX::Ones(2)), VecX(VecX::Constant(2, 0.3))}) {
    BOOST_TEST(residuals_within_round_off(row(1e3), forces, scale, r, tolerance, bound));
    BOOST_TEST(bound == 2.0 * eps * 4e7);  // exact: 1e3 x 2e4 twice, and powers of 2
  }
  BOOST_TEST(!residuals_within_round_off(row(1e3), forces, VecX::Constant(2, 1e5), r, tolerance, bound));
  BOOST_TEST(
      !residuals_within_round_off(row(1e9), VecX::Constant(2, 0.5), VecX::Ones(2), r, tolerance, bound));
  BOOST_TEST(!residuals_within_round_off(row(1e3), forces, VecX::Ones(2), VecX::Constant(1, 2e-8), tolerance,
                                         bound));
  BOOST_TEST(!residuals_within_round_off(row(1e3), forces, VecX::Ones(3), r, tolerance, bound));  // sizes
  BOOST_TEST(!residuals_within_round_off(row(1e3), forces, VecX(), r, tolerance, bound));
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

// A fixed variable takes its value from x as passed in, not from the Problem's stored value: with x
// fixed in the Problem at 1 but x[0] = 1.2 passed in, the root is y = sqrt(4 - 1.44) = 1.6, and x[0]
// stays 1.2.
BOOST_AUTO_TEST_CASE(fixed_variable_keeps_the_value_passed_in) {
  CircleLine cl(1.0, 1.0);
  cl.p.set_residual_active(cl.line, false);
  cl.p.fix_variable(cl.x, VecX::Constant(1, 1.0));
  NewtonSolver newton(cl.p);
  VecX x(2);
  x << 1.2, 1.0;
  const SolveSummary s = newton.solve(x);
  BOOST_TEST_REQUIRE(s.converged(), s.brief_report());
  BOOST_TEST(x[0] == 1.2);
  BOOST_TEST(std::abs(x[1] - 1.6) <= 1e-9);  // |dy| <~ |c| / |2 y| with |c| <= 1e-10
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

// A solver leaves its analysis of the structure to the next solver over the problem when it ends; the
// next one takes it and iterates bit for bit as a solver over a copy made before any solve (which has
// nothing left by a predecessor: the same analysis from the process-wide cache, newton_pattern_cache.hpp),
// and as a third solver made while the second is alive (nothing left to take).
BOOST_AUTO_TEST_CASE(a_solver_takes_the_pattern_analysis_its_predecessor_left) {
  Problem p = broyden_problem(40);
  for (VariableId v = 0; v < 40; ++v) p.set_variable_group(v, v < 20 ? 0 : 1);
  const Problem own = p;
  NewtonOptions o;
  o.linear_solver = NewtonLinearSolver::BorderedBlocks;
  VecX x_first = p.initial_values();
  SolveSummary s_first;
  {
    NewtonSolver first(p, o);
    s_first = first.solve(x_first);
  }
  BOOST_TEST(s_first.converged(), s_first.brief_report());
  NewtonSolver second(p, o), third(p, o), independent(own, o);
  VecX x_second = p.initial_values(), x_third = p.initial_values(), x_independent = own.initial_values();
  const SolveSummary s_second = second.solve(x_second);
  const SolveSummary s_third = third.solve(x_third);
  const SolveSummary s_independent = independent.solve(x_independent);
  for (const NewtonSolver* s : {&second, &third, &independent})
    BOOST_TEST(std::string(s->factorization_kind()) == "bordered blocks");
  for (const SolveSummary& s : {s_second, s_third, s_independent})
    BOOST_TEST(s.iterations == s_first.iterations);
  BOOST_TEST((x_second.array() == x_first.array()).all());
  BOOST_TEST((x_third.array() == x_first.array()).all());
  BOOST_TEST((x_independent.array() == x_first.array()).all());
}

// Problems of one structure built apart (here with other row scales: the same pattern, other values)
// share one analysis, kept process-wide (newton_pattern_cache.hpp); a problem of another structure (other
// variable groups, the same nonzeros) gets its own. Each still reaches the root its sparse-LU solve
// reaches: within 1e-8, a bound from the Newton tolerance 1e-10 on the residual and |J^-1| <= 10 on
// the Broyden system (rows 3 - 2 x_i on the diagonal, -1 and -2 beside it, |x_i| < 1 at the root), twice.
BOOST_AUTO_TEST_CASE(problems_of_one_structure_share_the_pattern_analysis) {
  auto solve = [](double odd_row_scale, int first_group_size, NewtonLinearSolver linear_solver,
                  std::string& kind) {
    Problem p = broyden_problem(40, odd_row_scale);
    for (VariableId v = 0; v < 40; ++v) p.set_variable_group(v, v < first_group_size ? 0 : 1);
    NewtonOptions o;
    o.linear_solver = linear_solver;
    NewtonSolver newton(p, o);
    VecX x = p.initial_values();
    const SolveSummary s = newton.solve(x);
    BOOST_TEST(s.converged(), s.brief_report());
    kind = newton.factorization_kind();
    return x;
  };
  std::string kind;
  for (double scale : {1.0, 2.0, 0.5}) {
    for (int first_group_size : {20, 10, 20}) {
      const VecX blocks = solve(scale, first_group_size, NewtonLinearSolver::BorderedBlocks, kind);
      BOOST_TEST(kind == "bordered blocks");
      const VecX sparse = solve(scale, first_group_size, NewtonLinearSolver::Sparse, kind);
      BOOST_TEST(kind == "sparse");
      BOOST_TEST((blocks - sparse).lpNorm<Eigen::Infinity>() <= 1e-8);
    }
  }
}
