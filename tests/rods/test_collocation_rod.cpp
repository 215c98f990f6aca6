// Collocation rods: every residual block's Jacobian against finite differences, the model and
// discretisation checks, post-processing, refinement, and Newton against Ipopt.
#define BOOST_TEST_MODULE collocation_rod
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/rods/collocation_rod.hpp"
#include "pcr/rods/rod_end.hpp"
#include "pcr/rods/rod_solve.hpp"
#include "pcr/solve/bordered_block_lu.hpp"
#include "pcr/solve/free_jacobian.hpp"
#include "pcr/solve/jacobian_check.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "rod_fixtures.hpp"

using namespace pcr;

namespace {

RodModel loaded_rod(RodEndKind base, RodEndKind tip) {
  RodModel m = test::cantilever(0.7, Vec3(3e3, 2e3, 5e3), Vec3(2.0, 1.5, 1.2));
  m.base.kind = base;
  m.tip.kind = tip;
  m.base.orientation = quat_from_rotation_vector(Vec3(0.1, -0.2, 0.05));
  m.tip.position = Vec3(0.1, 0.05, 0.6);
  m.tip.orientation = quat_from_rotation_vector(Vec3(0.3, 0.1, -0.2));
  m.tip.force = Vec3(0.3, -0.2, 0.1);
  m.tip.moment = Vec3(0.05, 0.1, -0.02);
  m.base.force = Vec3(-0.1, 0.2, 0.0);
  m.base.moment = Vec3(0.02, 0.0, 0.03);
  m.mass_per_length = 0.2;
  m.loads.gravity = Vec3(0, -9.81, 0);
  m.loads.moment_per_length = Vec3(0.01, 0.02, -0.01);
  m.intrinsic.curvature = Vec3(0.3, -0.1, 0.2);
  m.intrinsic.shear_extension = Vec3(0.001, 0.0, 0.002);
  return m;
}

// loaded_rod without distributed loads (gravity, moment per length): what the condensed form takes.
RodModel end_loaded_rod(RodEndKind base, RodEndKind tip) {
  RodModel m = loaded_rod(base, tip);
  m.loads.gravity.setZero();
  m.loads.moment_per_length.setZero();
  return m;
}

}  // namespace

BOOST_AUTO_TEST_CASE(every_block_jacobian_matches_finite_differences) {
  // All pairings with one clamped end, both formulations (the mixed one with both point sets: its
  // blocks differ), free length (so dr/dL is checked too), at a randomly perturbed, non-unit-quaternion
  // state.
  const RodEndKind kinds[] = {RodEndKind::Clamped, RodEndKind::Collar, RodEndKind::Spherical,
                              RodEndKind::Free};
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  // The condensed form three times: with the distributed loads (its rows read the integral of p, summed
  // over the control points on a short rod, 3 elements, or from the running integrals T on a long one,
  // 40 elements: more than kMaxBandedCondensedPoints) and without.
  const RodDiscretization discretizations[] = {{RodFormulation::Primal, 3, 3},
                                               {RodFormulation::Mixed, 3, 3, MixedPoints::Midpoints},
                                               {RodFormulation::Mixed, 3, 3, MixedPoints::Greville},
                                               {RodFormulation::Condensed, 3, 3},
                                               {RodFormulation::Condensed, 3, 40},
                                               {RodFormulation::Condensed, 3, 4}};
  for (const RodDiscretization& d : discretizations) {
    const RodFormulation f = d.formulation;
    const bool load_free = f == RodFormulation::Condensed && d.elements == 4;
    const auto model = load_free ? end_loaded_rod : loaded_rod;
    for (RodEndKind other : kinds) {
      for (bool clamped_base : {true, false}) {
        RodModel m = clamped_base ? model(RodEndKind::Clamped, other) : model(other, RodEndKind::Clamped);
        m.base.position = Vec3(0.05, -0.1, 0.2);  // moment point c (condensed) away from the origin
        m.intrinsic.varying = [](double s, Vec3& eps0, Vec3& kappa0) {
          eps0[0] += 1e-3 * s;
          kappa0 += Vec3(0.2 * s, -0.1 * s * s, 0.0);
        };
        CollocationRod rod(m, d);
        Problem problem;
        rod.add_to_problem(problem, {}, 1.0, /*free_length=*/true);
        VecX x = problem.initial_values();
        for (int i = 0; i < x.size(); ++i) x[i] += noise(rng);
        // Default checker tolerances 1e-6 abs + 1e-6 rel: central differences with relative step
        // 1e-6 have truncation ~1e-12 and round-off ~1e-10 on these O(1)..O(1e3) residuals.
        const JacobianCheckResult r = check_problem_jacobian(problem, x);
        BOOST_TEST(r.passed, to_string(f)
                                 << " (" << to_string(d.mixed_points) << ") base " << to_string(m.base.kind)
                                 << " tip " << to_string(m.tip.kind) << ": " << r.to_string());
        BOOST_TEST(r.entries_checked > 0);
        // The pattern comes from structural_mask (whole blocks at once): it must answer as
        // structural_nonzero entry by entry (which the check above tests against finite differences).
        int mismatches = 0;
        for (ResidualId b = 0; b < problem.num_residual_blocks(); ++b) {
          const ResidualBlock& block = problem.residual(b);
          for (size_t k = 0; k < block.variables().size(); ++k) {
            const int size = problem.variable(block.variables()[k]).size;
            std::vector<char> mask(static_cast<size_t>(block.num_rows()) * size, 2);
            block.structural_mask(static_cast<int>(k), size, mask.data());
            for (int row = 0; row < block.num_rows(); ++row)
              for (int c = 0; c < size; ++c)
                if ((mask[row * size + c] != 0) != block.structural_nonzero(static_cast<int>(k), row, c) ||
                    mask[row * size + c] == 2)
                  ++mismatches;
          }
        }
        BOOST_TEST(mismatches == 0);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(square_system_in_every_formulation) {
  const RodDiscretization discretizations[] = {{RodFormulation::Primal, 4, 5},
                                               {RodFormulation::Mixed, 4, 5, MixedPoints::Midpoints},
                                               {RodFormulation::Mixed, 4, 5, MixedPoints::Greville},
                                               {RodFormulation::Condensed, 4, 5}};
  for (const RodDiscretization& d : discretizations) {
    CollocationRod rod(end_loaded_rod(RodEndKind::Clamped, RodEndKind::Free), d);
    Problem problem;
    rod.add_to_problem(problem);
    const int unknowns = rod.configuration_size();  // L is fixed
    BOOST_TEST(unknowns == rod.num_control_points() * rod.control_point_size() +
                               (d.formulation == RodFormulation::Condensed ? 6 : 0));
    BOOST_TEST(problem.num_rows() == unknowns);
    BOOST_TEST(rod.num_equations({}) == unknowns);
    BOOST_TEST(rod.num_equations({false, false}) == unknowns - 14);
  }
}

BOOST_AUTO_TEST_CASE(bad_discretisation_and_model_are_rejected_with_the_value) {
  const RodModel good = test::cantilever(1.0, Vec3(1e3, 1e3, 1e3), Vec3(1, 1, 1));
  try {
    CollocationRod rod(good, {RodFormulation::Mixed, 1, 4});
    BOOST_FAIL("degree 1 accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("degree") != std::string::npos);
    BOOST_TEST(std::string(e.what()).find("1") != std::string::npos);
  }
  BOOST_CHECK_THROW(CollocationRod(good, {RodFormulation::Mixed, 3, 0}), InputError);
  RodModel bad = good;
  bad.length = -2.0;
  try {
    CollocationRod rod(bad, {});
    BOOST_FAIL("negative length accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("length") != std::string::npos);
    BOOST_TEST(std::string(e.what()).find("-2") != std::string::npos);
  }
  bad = good;
  bad.bending_torsion_stiffness[2] = 0.0;
  BOOST_CHECK_THROW(CollocationRod(bad, {}), InputError);
  bad = good;
  bad.base.kind = RodEndKind::Free;
  BOOST_CHECK_THROW(CollocationRod(bad, {}), InputError);  // free at both ends: not determined
  bad = good;
  bad.base.kind = RodEndKind::Collar;
  bad.tip.kind = RodEndKind::Collar;
  BOOST_CHECK_THROW(CollocationRod(bad, {}), InputError);  // free twist gauge
}

BOOST_AUTO_TEST_CASE(gravity_loaded_cantilever_converges_to_global_equilibrium) {
  // Global balance n(0) = n(L) + integral_0^L f ds = F_tip + f L (from n' + f = 0) holds for the exact
  // solution. The primal form and the mixed form at Greville points enforce n' + f = 0 only at the
  // n - 2 interior points, so the base force carries the discretisation error and must converge to
  // the balance under refinement. The mixed form at midpoints collocates n' + f = 0 at n - 1 points:
  // n' is a spline of degree p - 1 with n - 1 coefficients, so the constant -f is reproduced exactly
  // and the balance holds to round-off (1e-12 relative: |n| ~ 1 N from residuals solved to 1e-10).
  // The condensed form has n(s) = n(0) - f s by construction: exact as well.
  RodModel m = test::cantilever(0.5, Vec3(1e5, 1e5, 2e5), Vec3(0.5, 0.5, 0.4));
  m.mass_per_length = 0.05;
  m.loads.gravity = Vec3(0, 0, -9.81);
  m.base.orientation = quat_from_rotation_vector(Vec3(M_PI / 2, 0, 0));  // horizontal rod along -y
  m.tip.force = Vec3(0.1, 0.0, -0.2);
  const Vec3 total = m.distributed_force() * m.length + m.tip.force;
  const RodDiscretization discretizations[] = {{RodFormulation::Primal, 4, 8},
                                               {RodFormulation::Mixed, 4, 8, MixedPoints::Greville},
                                               {RodFormulation::Mixed, 4, 8, MixedPoints::Midpoints},
                                               {RodFormulation::Condensed, 4, 8}};
  for (RodDiscretization d : discretizations) {
    const std::string label = std::string(to_string(d.formulation)) + " (" + to_string(d.mixed_points) + ")";
    const bool exact = d.formulation == RodFormulation::Condensed ||
                       (d.formulation == RodFormulation::Mixed && d.mixed_points == MixedPoints::Midpoints);
    double previous = INFINITY;
    for (int elements : {8, 16, 32}) {
      RodSolveOptions o;
      d.elements = elements;
      o.discretization = d;
      const RodSolution sol = solve_rod(m, o);
      BOOST_REQUIRE_MESSAGE(sol.summary.converged(), sol.summary.brief_report());
      const double error = (sol.base().force - total).norm() / total.norm();
      // Degree 4: at least a factor 4 per halving (order >= 2 of 4 expected; measured >= 4).
      if (exact)
        BOOST_TEST(error < 1e-12, label << " " << elements << " elements: relative balance error " << error);
      else
        BOOST_TEST(error < previous / 4,
                   label << " " << elements << " elements: relative balance error " << error);
      previous = error;
      // The tip load itself is an end condition and holds to the solver tolerance.
      BOOST_TEST((sol.tip().force - m.tip.force).norm() < 1e-8 * total.norm());
    }
    // Measured at 32 elements: 2.5e-6 (mixed, Greville), 2e-4 (primal, which also locks at this
    // slenderness).
    BOOST_TEST(previous < (d.formulation == RodFormulation::Primal ? 1e-3 : 1e-5));
  }
}

BOOST_AUTO_TEST_CASE(newton_and_ipopt_agree) {
  RodModel m = test::cantilever(1.0, Vec3(1e4, 1e4, 1e4), Vec3(1, 1, 0.8));
  m.tip.force = Vec3(2.0, 0.5, -0.3);
  m.tip.moment = Vec3(0.0, 0.3, 0.2);
  for (RodFormulation f : {RodFormulation::Primal, RodFormulation::Mixed, RodFormulation::Condensed}) {
    RodSolveOptions o;
    o.discretization = {f, 4, 6};
    // Residual tolerances near each formulation's round-off floor (primal: eps K_SE |N''| ~ 1e-11).
    o.tolerance = f == RodFormulation::Primal ? 1e-10 : 1e-13;
    const RodSolution newton = solve_rod(m, o);
    o.solver = SolverKind::Ipopt;
    const RodSolution ipopt = solve_rod(m, o);
    BOOST_REQUIRE_MESSAGE(newton.summary.converged(), newton.summary.brief_report());
    BOOST_REQUIRE_MESSAGE(ipopt.summary.converged(), ipopt.summary.brief_report());
    // Both solve the same square system to 1e-12: their solutions agree to about cond(J) * 1e-12;
    // the issue asks for 1e-10 on the centerline.
    double worst = 0.0;
    for (double s = 0.0; s <= 1.0; s += 0.05)
      worst = std::max(worst, (newton.at(s).position - ipopt.at(s).position).norm());
    BOOST_TEST(worst < 1e-10, to_string(f) << " worst centerline difference " << worst);
  }
}

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

BOOST_AUTO_TEST_CASE(refinement_carries_the_solution_as_initial_guess) {
  RodModel m = test::cantilever(1.0, Vec3(1e4, 1e4, 1e4), Vec3(1, 1, 0.8));
  m.tip.force = Vec3(3.0, 0.0, 0.0);
  RodSolveOptions o;
  o.discretization = {RodFormulation::Mixed, 3, 4};
  const RodSolution coarse = solve_rod(m, o);
  BOOST_REQUIRE(coarse.summary.converged());
  RodSolveOptions fine = o;
  fine.discretization = {RodFormulation::Mixed, 3, 12};
  const VecX guess = refine_solution(coarse, fine.discretization);
  // Pure h-refinement (4 -> 12 elements, same degree): the new space contains the old spline, so the
  // transferred curve is the same up to round-off.
  CollocationRod fine_rod(m, fine.discretization);
  Problem problem;
  const RodVariables vars = fine_rod.add_to_problem(problem, {}, 1.0, false, -1, &guess);
  const VecX x = problem.initial_values();
  for (double s = 0.0; s <= 1.0; s += 0.1)
    BOOST_TEST((fine_rod.state_at(x, vars, s).position - coarse.at(s).position).norm() < 1e-13);
  // Cold: from the stress-free shape (the coarse shooting start is a guess of its own, tested in
  // shooting_start_reaches_the_same_solution).
  fine.shooting_start = false;
  const RodSolution warm = solve_rod(m, fine, &guess);
  const RodSolution cold = solve_rod(m, fine);
  BOOST_REQUIRE(warm.summary.converged() && cold.summary.converged());
  BOOST_TEST(warm.summary.iterations < cold.summary.iterations);
  // p-refinement (degree 3 -> 5): interpolation at the new Greville points; the guess is close.
  const VecX elevated = refine_solution(coarse, {RodFormulation::Mixed, 5, 8});
  const RodSolution warm5 = solve_rod(m, {{RodFormulation::Mixed, 5, 8}}, &elevated);
  RodSolveOptions stress_free_start;
  stress_free_start.shooting_start = false;
  stress_free_start.discretization = {RodFormulation::Mixed, 5, 8};
  const RodSolution cold5 = solve_rod(m, stress_free_start);
  BOOST_REQUIRE(warm5.summary.converged() && cold5.summary.converged());
  BOOST_TEST(warm5.summary.iterations < cold5.summary.iterations);
  // Condensed form: the constant force and moment carry over with the control points.
  o.discretization = {RodFormulation::Condensed, 3, 4};
  const RodSolution coarse_c = solve_rod(m, o);
  BOOST_REQUIRE(coarse_c.summary.converged());
  const VecX guess_c = refine_solution(coarse_c, {RodFormulation::Condensed, 3, 12});
  BOOST_TEST((guess_c.tail(6) - coarse_c.x.segment(coarse_c.variables.wrench_offset, 6)).norm() == 0.0);
  const RodSolution warm_c = solve_rod(m, {{RodFormulation::Condensed, 3, 12}}, &guess_c);
  stress_free_start.discretization = {RodFormulation::Condensed, 3, 12};
  const RodSolution cold_c = solve_rod(m, stress_free_start);
  BOOST_REQUIRE(warm_c.summary.converged() && cold_c.summary.converged());
  BOOST_TEST(warm_c.summary.iterations < cold_c.summary.iterations);
}

BOOST_AUTO_TEST_CASE(centerline_sampling_gives_the_positions_and_stretches_of_the_full_states) {
  // sample_centerline (robot results) against sample() (full states) on a bent, stretched rod in every
  // formulation: the same sums of the same basis values, so equal to round-off (values of order 1 m
  // and 1: 1e-14).
  RodModel m = test::cantilever(0.5, Vec3(1e2, 1e2, 2e2), Vec3(0.5, 0.5, 0.4));
  m.tip.force = Vec3(3.0, -1.0, 20.0);
  m.tip.moment = Vec3(0.0, 0.2, 0.1);
  for (RodFormulation f : {RodFormulation::Primal, RodFormulation::Mixed, RodFormulation::Condensed}) {
    RodSolveOptions o;
    o.discretization = {f, 4, 6};
    const RodSolution sol = solve_rod(m, o);
    BOOST_REQUIRE_MESSAGE(sol.summary.converged(), sol.summary.brief_report());
    const std::vector<BasisDerivatives> bases = sol.rod->sample_basis(11);
    const std::vector<RodState> states = sol.rod->sample(sol.x, sol.variables, bases);
    std::vector<Vec3> positions;
    std::vector<double> stretches;
    sol.rod->sample_centerline(sol.x, sol.variables, bases, positions, stretches);
    BOOST_REQUIRE(positions.size() == states.size() && stretches.size() == states.size());
    for (size_t k = 0; k < states.size(); ++k) {
      BOOST_TEST((positions[k] - states[k].position).norm() < 1e-14, to_string(f) << " point " << k);
      BOOST_TEST(std::abs(stretches[k] - axial_stretch(states[k])) < 1e-14, to_string(f) << " point " << k);
    }
    // The tip load stretches the rod (v3 = 1 + N / EA): the comparison is not of ones.
    BOOST_TEST(std::abs(stretches.back() - 1.0) > 1e-3);
  }
}

BOOST_AUTO_TEST_CASE(post_processing_rejects_s_outside_the_rod) {
  RodSolveOptions o;
  const RodSolution sol = solve_rod(test::cantilever(1.0, Vec3(1e3, 1e3, 1e3), Vec3(1, 1, 1)), o);
  BOOST_CHECK_THROW(sol.at(1.5), InputError);
  BOOST_CHECK_THROW(sol.at(-0.1), InputError);
}

BOOST_AUTO_TEST_CASE(stress_free_configuration_follows_the_intrinsic_shape) {
  // Constant intrinsic curvature (1.5, 0, 0.8) /m over L = 2 m from a turned base: the stress-free rod
  // is the closed-form curve of rod_fixtures.hpp (R(0) = I there), moved to the base frame.
  RodModel m = test::cantilever(2.0, Vec3(1e4, 1e4, 1e4), Vec3(1, 1, 0.8));
  m.intrinsic.curvature = Vec3(1.5, 0.0, 0.8);
  m.base.position = Vec3(0.1, -0.2, 0.3);
  m.base.orientation = quat_from_rotation(rotation_x(0.4));
  const Mat3 R0 = rotation_x(0.4);
  const CollocationRod rod(m, {RodFormulation::Mixed, 5, 16});
  const VecX x0 = rod.stress_free_configuration();
  Problem problem;
  const RodVariables v = rod.add_to_problem(problem, {}, 1.0, false, -1, &x0);
  const VecX x = problem.initial_values();
  for (double s : {0.0, 0.37, 1.0, 1.61, 2.0}) {
    const RodState st = rod.state_at(x, v, s);
    const Vec3 exact = m.base.position + R0 * test::constant_curvature_position(m.intrinsic.curvature, s);
    const Mat3 exact_R = R0 * test::constant_curvature_rotation(m.intrinsic.curvature, s);
    // Midpoint steps of L / (64 (n - 1)) ~ 1.5e-3 m (error ~1e-6 m) and interpolation of a curve turning
    // by |kappa| L = 3.4 rad with degree 5, 16 elements (~1e-7): 1e-5 m.
    BOOST_TEST((st.position - exact).norm() <= 1e-5, "s = " << s << ": " << st.position.transpose());
    BOOST_TEST((st.rotation - exact_R).norm() <= 1e-5, "s = " << s);
  }
  // Unloaded, the stress-free shape is the solution up to the discretisation: Newton from it takes a
  // few steps and no load stepping, and lands on the same curve to the collocation error (R1, a 2 pi
  // circle, has 8.4e-5 m at degree 5 with 8 elements in bench_all; this curve turns 3.4 rad over 16
  // elements): 5e-5 m.
  const RodSolution sol = solve_rod(m, RodSolveOptions{{RodFormulation::Mixed, 5, 16}});
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  BOOST_TEST(sol.load_steps == 0);
  BOOST_TEST(sol.summary.iterations <= 3);
  BOOST_TEST((sol.tip().position -
              (m.base.position + R0 * test::constant_curvature_position(m.intrinsic.curvature, 2.0)))
                 .norm() <= 5e-5);
  // A straight rod's stress-free configuration is the straight one.
  const CollocationRod straight(test::cantilever(1.0, Vec3(1e4, 1e4, 1e4), Vec3(1, 1, 0.8)),
                                {RodFormulation::Mixed, 5, 4});
  BOOST_TEST((straight.stress_free_configuration() - straight.straight_configuration()).norm() == 0.0);
}

namespace {

// A rod clamped at both ends, the tip frame at the end of a circular arc of `turns` full turns in the
// y-z plane (body curvature kappa = 2 pi turns / L about e1): the arc is an exact equilibrium (pure
// bending, n = 0, m = EI kappa constant), and, with EI = 1, EA = 1e4, the straight rod is far from it.
RodModel clamped_arc(double turns, Vec3& kappa, RodEndKind tip = RodEndKind::Clamped) {
  const double L = 1.0;
  RodModel m = test::cantilever(L, Vec3(1e4, 1e4, 1e4), Vec3(1, 1, 1));
  kappa = Vec3(2 * M_PI * turns / L, 0, 0);
  m.tip.kind = tip;
  m.tip.position = test::constant_curvature_position(kappa, L);
  m.tip.orientation = quat_from_rotation_vector(L * kappa);
  return m;
}

double arc_centerline_error(const RodSolution& sol, const Vec3& kappa) {
  double error = 0.0;
  for (const RodState& st : sol.rod->sample(sol.x, sol.variables, 101))
    error = std::max(error, (st.position - test::constant_curvature_position(kappa, st.s)).norm());
  return error;
}

}  // namespace

BOOST_AUTO_TEST_CASE(clamped_ends_far_from_the_straight_rod_are_reached_by_continuation) {
  // From the straight rod the direct Newton solve fails (0.25-0.75 turns) or lands on an inadmissible
  // state (0.9, 1 turn: inverted or collapsed, v3 <= 0); the continuation moves the tip frame from the
  // straight rod's along the arcs (rod_solve.cpp, MovingEnds).
  // A collar at the tip (axis along the arc's tangent, free in torsion) has the same arc as its
  // equilibrium: the end moment EI kappa e1 is normal to the tangent.
  const std::pair<double, RodEndKind> cases[] = {{0.25, RodEndKind::Clamped}, {0.5, RodEndKind::Clamped},
                                                 {0.75, RodEndKind::Clamped}, {0.9, RodEndKind::Clamped},
                                                 {1.0, RodEndKind::Clamped},  {0.5, RodEndKind::Collar},
                                                 {0.9, RodEndKind::Collar}};
  for (const auto& [turns, tip] : cases) {
    Vec3 kappa;
    const RodModel m = clamped_arc(turns, kappa, tip);
    RodSolveOptions o;
    o.discretization = {RodFormulation::Mixed, 6, 8};
    const RodSolution sol = solve_rod(m, o);
    BOOST_TEST_REQUIRE(sol.summary.converged(),
                       turns << " turns, " << to_string(tip) << ": " << sol.summary.message);
    // Measured 1.1e-9 .. 1.6e-6 L, growing with the curvature (degree 6, 8 elements); bound 1e-5 L.
    // The other equilibria that solves from the straight rod reached before missed by 0.2-0.35 L.
    const double error = arc_centerline_error(sol, kappa);
    BOOST_TEST(error < 1e-5, turns << " turns, " << to_string(tip) << ": centerline error " << error);
    // Pure bending: |m| = EI kappa = kappa (EI = 1), n = 0 along the whole rod. Measured up to 4.9e-6 kappa
    // (|m| - kappa) and 3.1e-5 kappa (|n|, in N with EI / L^2 = 1 N) at 1 turn, both 50-90x smaller with
    // 16 elements (discretisation error); bounds 2e-5 kappa and 1e-4 kappa.
    for (const RodState& st : sol.rod->sample(sol.x, sol.variables, 5)) {
      BOOST_TEST(std::abs(st.moment.norm() - kappa.norm()) < 2e-5 * kappa.norm(),
                 turns << " turns, s = " << st.s);
      BOOST_TEST(st.force.norm() < 1e-4 * kappa.norm(), turns << " turns, s = " << st.s);
    }
  }
}

BOOST_AUTO_TEST_CASE(a_collapsed_rod_is_not_reported_as_converged) {
  // One full turn: both clamped ends at the origin with R = I. Newton from the straight rod converges in
  // one step to the rod compressed to a point (v3 = 0 everywhere: an exact equilibrium of the
  // extensible model). It must be reported as a failure, not as converged.
  Vec3 kappa;
  const RodModel m = clamped_arc(1.0, kappa);
  RodSolveOptions o;
  o.discretization = {RodFormulation::Mixed, 6, 8};
  o.load_stepping = false;
  const RodSolution direct = solve_rod(m, o);
  BOOST_TEST(!direct.summary.converged());
  BOOST_TEST(direct.summary.message.find("inadmissible") != std::string::npos, direct.summary.message);
  // With continuation (the default) the loop is found (previous test).
  o.load_stepping = true;
  const RodSolution loop = solve_rod(m, o);
  BOOST_TEST_REQUIRE(loop.summary.converged(), loop.summary.message);
  for (const RodState& st : loop.rod->sample(loop.x, loop.variables, 21))
    BOOST_TEST(1.0 + st.shear_extension_body[2] > 0.99);  // |n| ~ 0: v3 = 1 up to round-off
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
