// The condensed formulation of a collocation rod: equal to the mixed midpoint scheme without
// distributed loads; under loads, the integral of p carried in local unknowns (rows that read a window
// of p + 1 control points), the structured LU and the end quantities' Jacobians.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "pcr/rods/collocation_rod.hpp"
#include "pcr/rods/rod_end.hpp"
#include "pcr/rods/rod_solve.hpp"
#include "pcr/solve/bordered_block_lu.hpp"
#include "pcr/solve/free_jacobian.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "rod_fixtures.hpp"

namespace pcr {
namespace {

using test::end_loaded_rod;
using test::loaded_rod;

}  // namespace

BOOST_AUTO_TEST_CASE(condensed_form_equals_the_mixed_midpoint_scheme) {
  // Without distributed loads the mixed midpoint rows n' = 0 and (m + p x n)' = 0 at the n - 1
  // midpoints make the derivatives of the splines n and m + p x n (degree p - 1, n - 1 coefficients)
  // vanish at n - 1 points, hence everywhere: n and m + p x n are constant, which the condensed form
  // imposes exactly; both then collocate the same constitutive rows at the same points. So a root of
  // one system maps to a root of the other: mixed -> condensed keeps P, Q and takes n, h = m + (p - c) x n
  // at the base; condensed -> mixed sets N_i = n, M_i = h - (P_i - c) x n (the spline h - (p - c) x n,
  // by the partition of unity). Each solved to residual 1e-13; the mapped state's residual must be at
  // that level too (1e-11: the mapping is exact algebra, the margin is for the residual rows' scales).
  // (Solved independently, the two can reach different equilibria, e.g. a spherical tip.)
  const RodEndKind kinds[] = {RodEndKind::Clamped, RodEndKind::Collar, RodEndKind::Spherical,
                              RodEndKind::Free};
  for (RodEndKind other : kinds) {
    RodModel m = end_loaded_rod(RodEndKind::Clamped, other);
    const Vec3 offset(0.3, -0.2, 0.1);  // the moment point c (the base) away from the origin
    m.base.position += offset;
    m.tip.position = offset + Vec3(0.05, -0.1, 0.65);  // loaded_rod's (0.1, 0.05, 0.6): no convergence
    RodSolveOptions o;
    o.tolerance = 1e-13;
    o.discretization = {RodFormulation::Mixed, 4, 5, MixedPoints::Midpoints};
    const RodSolution mixed = solve_rod(m, o);
    o.discretization = {RodFormulation::Condensed, 4, 5};
    const RodSolution condensed = solve_rod(m, o);
    const std::string label = std::string("tip ") + to_string(other);
    BOOST_REQUIRE_MESSAGE(mixed.summary.converged(), label << ": " << mixed.summary.brief_report());
    BOOST_REQUIRE_MESSAGE(condensed.summary.converged(), label << ": " << condensed.summary.brief_report());
    const CollocationRod& mixed_rod = *mixed.rod;
    const CollocationRod& condensed_rod = *condensed.rod;
    const int n = condensed_rod.num_control_points();
    const Vec3 c = condensed_rod.moment_point();

    VecX to_condensed(condensed_rod.configuration_size());
    for (int i = 0; i < n; ++i) to_condensed.segment<7>(7 * i) = mixed.x.segment<7>(13 * i);
    const RodState base = mixed.base();
    to_condensed.segment<3>(7 * n) = base.force;
    to_condensed.segment<3>(7 * n + 3) = base.moment + (base.position - c).cross(base.force);

    const VecX& w = condensed.x;
    const Vec3 force = w.segment<3>(condensed.variables.wrench_offset);
    const Vec3 h = w.segment<3>(condensed.variables.wrench_offset + 3);
    VecX to_mixed(mixed_rod.configuration_size());
    for (int i = 0; i < n; ++i) {
      const Vec3 P = w.segment<3>(7 * i);
      to_mixed.segment<7>(13 * i) = w.segment<7>(7 * i);
      to_mixed.segment<3>(13 * i + 7) = force;
      to_mixed.segment<3>(13 * i + 10) = h - (P - c).cross(force);
    }
    const std::pair<const CollocationRod*, const VecX*> mapped[] = {{&condensed_rod, &to_condensed},
                                                                    {&mixed_rod, &to_mixed}};
    for (const auto& [rod, x0] : mapped) {
      Problem problem;
      rod->add_to_problem(problem, {}, 1.0, false, -1, x0);
      VecX r;
      problem.evaluate_residuals(problem.initial_values(), r);
      BOOST_TEST(r.lpNorm<Eigen::Infinity>() < 1e-11,
                 label << ": residual of the " << to_string(rod->discretization().formulation)
                       << " system at the other's root: " << r.lpNorm<Eigen::Infinity>());
    }
  }
}

BOOST_AUTO_TEST_CASE(condensed_form_with_loads_carries_the_integral_of_p_in_local_unknowns) {
  // Under distributed loads each control point of a long rod carries T_i = sum_{j<i} w_j P_j, w_j =
  // integral_0^1 N_j (collocation_rod.hpp). At the solution: T against that sum over the solution's P
  // (basis_integrals, checked in test_basis), and n, m along the rod (state_at) against the closed-form
  // balance with I(u) = sum over all control points of J_j(u) P_j (independent of T). The T rows are linear,
  // (T_{i+1} - T_i - w_i P_i) / L0, solved to the residual tolerance 1e-12: T within n 1e-12 L0 (1e-10 L0
  // asserted), and m, which reads L (I - c u) x f, within L0 |f| 1e-10 L0 (1e-9 M0 asserted, M0 >= L0^2 |f|
  // here); n does not read I.
  const RodModel m = loaded_rod(RodEndKind::Clamped, RodEndKind::Free);
  RodSolveOptions o;
  o.tolerance = 1e-12;
  o.discretization = {RodFormulation::Condensed, 4, 40};  // 44 > kMaxBandedCondensedPoints
  const RodSolution sol = solve_rod(m, o);
  BOOST_REQUIRE_MESSAGE(sol.summary.converged(), sol.summary.brief_report());
  const CollocationRod& rod = *sol.rod;
  BOOST_REQUIRE(rod.condensed_with_loads());
  BOOST_TEST(rod.control_point_size() == 10);
  const collocation::PointLayout& layout = rod.point_layout();
  const int n = rod.num_control_points(), cp = rod.control_point_size();
  auto P = [&](int j) {
    return Vec3(sol.x.segment<3>(sol.variables.control_point_offset + j * cp + layout.p));
  };
  const VecX w = basis_integrals(rod.knots(), 1.0);
  Vec3 sum = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    const Vec3 T = sol.x.segment<3>(sol.variables.control_point_offset + i * cp + layout.integral);
    BOOST_TEST((T - sum).norm() < 1e-10 * m.length, "T_" << i << " off by " << (T - sum).norm());
    sum += w[i] * P(i);
  }
  const Vec3 c = rod.moment_point(), f = m.distributed_force(), l = m.loads.moment_per_length;
  const Vec3 n0 = sol.x.segment<3>(sol.variables.wrench_offset),
             h = sol.x.segment<3>(sol.variables.wrench_offset + 3);
  for (double s : {0.0, 0.13, 0.35, 0.5, 0.61, 0.7}) {
    const double u = s / m.length;
    const VecX J = basis_integrals(rod.knots(), u);
    Vec3 I = Vec3::Zero();
    for (int j = 0; j < n; ++j) I += J[j] * P(j);
    const RodState st = sol.at(s);
    const Vec3 force = n0 - f * s;
    const Vec3 moment = h - (st.position - c).cross(force) - l * s - (m.length * (I - c * u)).cross(f);
    BOOST_TEST((st.force - force).norm() < 1e-13 * rod.force_scale(), "s = " << s);  // round-off of u L vs s
    BOOST_TEST((st.moment - moment).norm() < 1e-9 * rod.moment_scale(),
               "s = " << s << ": " << (st.moment - moment).norm());
  }
}

BOOST_AUTO_TEST_CASE(condensed_form_with_loads_has_local_rows_and_a_size_linear_in_the_elements) {
  // Every row of a condensed rod under loads reads a window of at most p + 1 consecutive control points
  // (summing I(u) over every control point below u filled the rod's Jacobian below the diagonal), so the
  // Jacobian's nonzeros grow linearly with the element count: doubling E = 40 -> 80 doubles them up to the
  // constant end blocks (ratio (80 + p) / (40 + p) = 1.91 for the per-point part; asserted in [1.75, 2.05],
  // where a dense lower triangle would give about 3.7). A rod's end quantities (RodEndEvaluator at the tip)
  // read the end control point, the wrench and L. Such rods, with more than kMaxBandedCondensedPoints
  // control points, keep their group: the structured LU (BorderedBlockLu) moves the wrench's 6 columns, read
  // by every row, to its border, and Newton with it reaches the root of Newton with the general sparse LU in
  // as many iterations (the two LUs differ by round-off, amplified in the steps by cond(J); 1e-8 relative
  // leaves room for cond(J) up to about 1e7 at eps = 2.2e-16 and residuals <= 1e-10). A short rod (8
  // elements) keeps the summed integral (7 unknowns per point) and its group.
  const RodModel m = loaded_rod(RodEndKind::Clamped, RodEndKind::Free);
  const int p = 4;
  long nonzeros[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const CollocationRod rod(m, {RodFormulation::Condensed, p, 40 * (k + 1)});  // 44 and 84 points
    Problem problem;
    const RodVariables vars = rod.add_to_problem(problem, {}, 1.0, false, 0);
    nonzeros[k] = problem.jacobian_nonzeros();
    // The control point of each column (-1: the wrench, L), and per row of the Jacobian's pattern the
    // window of control points it reads.
    std::vector<int> point_of_column(problem.num_variables(), -1);
    for (size_t i = 0; i < vars.control_points.size(); ++i) {
      const auto& block = problem.variable(vars.control_points[i]);
      std::fill_n(point_of_column.begin() + block.offset, block.size, static_cast<int>(i));
    }
    VecX c;
    Eigen::SparseMatrix<double, Eigen::RowMajor> pattern;
    problem.evaluate_residuals_and_jacobian(problem.initial_values(), c, pattern);
    int widest = 0;
    for (int row = 0; row < pattern.rows(); ++row) {
      int lo = 1 << 30, hi = -1;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(pattern, row); it; ++it) {
        const int point = point_of_column[it.col()];
        if (point >= 0) lo = std::min(lo, point), hi = std::max(hi, point);
      }
      widest = std::max(widest, hi - lo);
    }
    BOOST_TEST(widest <= p);
    const RodEndEvaluator tip(rod, vars, true);
    BOOST_TEST(tip.variables().size() == 3u);
    BOOST_TEST(tip.variables()[0] == vars.control_points.back());
    // Its Jacobians against central differences (step 1e-6: truncation ~1e-12, round-off ~1e-10 on
    // values of order 1; 1e-7 asserted) at a perturbed state with a nonzero wrench and T.
    VecX x = problem.initial_values();
    for (int i = 0; i < x.size(); ++i) x[i] += 0.01 * std::sin(1.0 + i);
    std::vector<VecX> blocks;
    for (VariableId v : tip.variables())
      blocks.push_back(x.segment(problem.variable(v).offset, problem.variable(v).size));
    auto evaluate = [&](std::vector<MatX>* J) {
      std::vector<const double*> values;
      for (const VecX& b : blocks) values.push_back(b.data());
      RodEndVector y;
      tip.evaluate(values.data(), y, J);
      return y;
    };
    std::vector<MatX> J;
    evaluate(&J);
    double worst = 0.0;
    for (size_t k = 0; k < blocks.size(); ++k)
      for (int c = 0; c < blocks[k].size(); ++c) {
        const double h = 1e-6, saved = blocks[k][c];
        blocks[k][c] = saved + h;
        const RodEndVector plus = evaluate(nullptr);
        blocks[k][c] = saved - h;
        const RodEndVector minus = evaluate(nullptr);
        blocks[k][c] = saved;
        worst = std::max(worst, ((plus - minus) / (2 * h) - J[k].col(c)).lpNorm<Eigen::Infinity>());
      }
    BOOST_TEST(worst < 1e-7);
    BOOST_TEST(rod.control_point_size() == 10);
    BOOST_TEST(problem.variable(vars.wrench).group == 0);
    BOOST_TEST(problem.variable(vars.control_points[0]).group == 0);
    BorderedBlockLu lu;
    const FreeJacobian jacobian = free_jacobian(problem, problem.initial_values());
    BOOST_REQUIRE_MESSAGE(lu.analyze_pattern(jacobian.matrix, jacobian.groups), lu.error_message());
    BOOST_TEST(lu.wide_columns() == collocation::kWrenchSize);
    NewtonOptions structured, general;
    structured.linear_solver = NewtonLinearSolver::BorderedBlocks;
    general.linear_solver = NewtonLinearSolver::Sparse;
    structured.tolerance = general.tolerance = 1e-10;
    NewtonSolver a(problem, structured), b(problem, general);
    VecX xa = problem.initial_values(), xb = xa;
    const SolveSummary sa = a.solve(xa), sb = b.solve(xb);
    BOOST_TEST_REQUIRE(sa.converged(), sa.brief_report());
    BOOST_TEST_REQUIRE(sb.converged(), sb.brief_report());
    BOOST_TEST(std::string(a.factorization_kind()) == "bordered blocks");
    BOOST_TEST(sa.iterations == sb.iterations);
    BOOST_TEST((xa - xb).lpNorm<Eigen::Infinity>() <= 1e-8 * (1.0 + xb.lpNorm<Eigen::Infinity>()));
  }
  const CollocationRod short_rod(m, {RodFormulation::Condensed, p, 8});
  Problem problem;
  const RodVariables vars = short_rod.add_to_problem(problem, {}, 1.0, false, 0);
  BOOST_TEST(short_rod.control_point_size() == 7);
  BOOST_TEST(problem.variable(vars.wrench).group == 0);
  const double ratio = static_cast<double>(nonzeros[1]) / nonzeros[0];
  BOOST_TEST(ratio >= 1.75);
  BOOST_TEST(ratio <= 2.05);
}

}  // namespace pcr
