// The shooting integrator and solver mechanics (part of the test_shooting module): tangents against
// finite differences, RK4's order, dense output, warm starts, bad input, non-convergence and
// integration failure.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/rods/shooting/rod_integrator.hpp"
#include "pcr/rods/shooting/rod_shooting.hpp"
#include "shooting/shooting_fixtures.hpp"

using namespace pcr;
using namespace pcr::shooting_test;

// ---- tangents (variational equations) against central finite differences ---------------------------
BOOST_AUTO_TEST_CASE(tangents_match_finite_differences) {
  RodModel rod = test::cantilever(1.0, Vec3(30, 40, 100), Vec3(1.0, 2.0, 1.5));
  rod.loads.force_per_length = Vec3(0.3, -1.0, 0.5);
  rod.loads.moment_per_length = Vec3(0.1, 0.0, -0.2);
  rod.intrinsic.curvature = Vec3(0.5, 0.2, 0.1);
  const RodOde ode(rod);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  RodStateWithTangents Y;
  for (int i = 0; i < Y.size(); ++i) Y.data()[i] = normal(rng);
  Y.col(0).segment<4>(RodStateIndex::q).normalize();
  IntegratorOptions o;
  o.method = IntegratorMethod::RK4;  // fixed steps: the tangents are the exact derivative of the map
  o.rk4_steps = 50;
  RodStateWithTangents Y1 = Y;
  BOOST_TEST_REQUIRE(integrate_rod(ode, 0.0, 1.0, Y1, o).success);
  const Quat q1 = Y1.col(0).segment<4>(RodStateIndex::q);
  for (int j = 1; j <= kRodTangentCount; ++j) {
    const double eps = 1e-6;
    RodStateVector a = Y.col(0) + eps * Y.col(j), b = Y.col(0) - eps * Y.col(j);
    integrate_rod(ode, 0.0, 1.0, a, o);
    integrate_rod(ode, 0.0, 1.0, b, o);
    const RodStateVector fd = (a - b) / (2 * eps);
    // Central differences: truncation eps^2 |y'''| ~ 1e-12 x O(10), roundoff 1e-16 / eps ~ 1e-10,
    // relative to the tangent's size (~ 10): 1e-8.
    const double tol = 1e-8 * Y1.col(j).norm();
    BOOST_TEST(max_abs(fd.segment<3>(RodStateIndex::p) - Y1.col(j).segment<3>(RodStateIndex::p)) < tol);
    BOOST_TEST(max_abs(fd.segment<3>(RodStateIndex::n) - Y1.col(j).segment<3>(RodStateIndex::n)) < tol);
    BOOST_TEST(max_abs(fd.segment<3>(RodStateIndex::m) - Y1.col(j).segment<3>(RodStateIndex::m)) < tol);
    // Orientation: compare dR (the radial part of dq is a gauge, normalised away after each step).
    const Mat3 dR_fd =
        (rotation_matrix(a.segment<4>(RodStateIndex::q)) - rotation_matrix(b.segment<4>(RodStateIndex::q))) /
        (2 * eps);
    Mat3 R1;
    QuatRotationJacobian dR;
    rotation_matrix_derivatives(q1, R1, dR);
    Mat3 dR_tangent = Mat3::Zero();
    for (int k = 0; k < 4; ++k) dR_tangent += dR[k] * Y1(RodStateIndex::q + k, j);
    BOOST_TEST((dR_fd - dR_tangent).cwiseAbs().maxCoeff() < tol);
  }
}

// ---- RK4 converges with order 4 --------------------------------------------------------------------------
BOOST_AUTO_TEST_CASE(rk4_error_decreases_as_n_to_the_minus_4) {
  // Precurved, gravity-loaded, tip-loaded cantilever (no closed form): reference by Dormand-Prince at
  // tolerance 1e-13.
  RodModel rod = test::cantilever(1.0, Vec3(1e3, 1e3, 2e3), Vec3(1.0, 1.0, 0.8));
  rod.intrinsic.curvature = Vec3(1.0, 0.0, 0.5);
  rod.loads.force_per_length = Vec3(0.0, -2.0, 0.0);
  rod.tip.force = Vec3(1.5, 0.0, 0.0);
  ShootingOptions ref_options = tight_options();
  ref_options.integration_relative_tolerance = 1e-13;
  ref_options.integration_absolute_tolerance = 1e-15;
  ref_options.tolerance = 1e-13;
  const ShootingSolution ref = solve_rod_shooting(rod, ref_options);
  BOOST_TEST_REQUIRE(ref.summary.converged(), ref.summary.brief_report());
  std::vector<double> errors;
  for (int N : {10, 20, 40, 80, 160}) {
    ShootingOptions o = ref_options;
    o.integrator = IntegratorMethod::RK4;
    o.rk4_steps = N;
    const ShootingSolution sol = solve_rod_shooting(rod, o);
    BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
    const double error = (sol.tip.p - ref.tip.p).norm();
    errors.push_back(error);
    BOOST_TEST_MESSAGE("RK4 N = " << N << ": tip error " << error);
  }
  for (size_t i = 0; i + 1 < errors.size(); ++i) {
    const double order = std::log2(errors[i] / errors[i + 1]);
    // Classical RK4 has order 4; +-0.3 allows the pre-asymptotic range at N = 10.
    BOOST_TEST(std::abs(order - 4.0) < 0.3,
               "order between N = " << (10 << i) << " and " << (20 << i) << ": " << order);
  }
}

// ---- dense output ---------------------------------------------------------------------------------------
BOOST_AUTO_TEST_CASE(dense_output_matches_stored_steps_and_a_direct_integration) {
  RodModel rod = test::cantilever(1.0, Vec3(100, 100, 100), Vec3(1, 1, 1));
  rod.tip.force = Vec3(2.0, 0.0, 0.0);
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged());
  BOOST_TEST_REQUIRE(sol.s.size() == sol.states.size());
  BOOST_TEST(sol.s.front() == 0.0);
  BOOST_TEST(sol.s.back() == 1.0);
  for (size_t i = 0; i < sol.s.size(); i += 7)
    BOOST_TEST(max_abs(sol.at(sol.s[i]).p - sol.states[i].p) == 0.0);
  // At s = 0.37: integrate the ODE directly from the base with tight Dormand-Prince up to 0.37.
  const RodOde ode(rod);
  RodStateVector y = sol.base.to_vector();
  IntegratorOptions o;
  o.relative_tolerance = 1e-13;
  o.absolute_tolerance = 1e-15;
  integrate_rod(ode, 0.0, 0.37, y, o);
  BOOST_TEST(max_abs(sol.at(0.37).p - y.head<3>()) < kTightIntegration);
  const auto samples = sol.sample({0.9, 0.1});
  BOOST_TEST(samples.size() == 2u);
  BOOST_TEST(max_abs(samples[1].p - sol.at(0.1).p) == 0.0);
  BOOST_CHECK_THROW(sol.at(1.5), InputError);
  BOOST_CHECK_THROW(sol.at(-0.1), InputError);
  // Round-off beyond the ends (s = L i / N computed by a caller) gives the end states.
  BOOST_TEST(max_abs(sol.at(1.0 + 1e-15).p - sol.states.back().p) == 0.0);
  BOOST_TEST(max_abs(sol.at(-1e-15).p - sol.states.front().p) == 0.0);
}

// ---- warm start
// --------------------------------------------------------------------------------------------
BOOST_AUTO_TEST_CASE(warm_start_needs_fewer_iterations) {
  const ShootingSolution cold = solve_rod_shooting(bisshopp_drucker(3.0), tight_options());
  const ShootingSolution near = solve_rod_shooting(bisshopp_drucker(3.05), tight_options(), &cold);
  const ShootingSolution near_cold = solve_rod_shooting(bisshopp_drucker(3.05), tight_options());
  BOOST_TEST_REQUIRE(near.summary.converged());
  BOOST_TEST_REQUIRE(near_cold.summary.converged());
  BOOST_TEST(near.summary.iterations < near_cold.summary.iterations);
  BOOST_TEST(max_abs(near.tip.p - near_cold.tip.p) < kTightIntegration);
}
// ---- bad input, non-convergence, integration failure ------------------------------------------------------
BOOST_AUTO_TEST_CASE(bad_input_throws_input_error) {
  RodModel rod = bisshopp_drucker(1.0);
  rod.length = -1.0;
  BOOST_CHECK_THROW(solve_rod_shooting(rod), InputError);
  rod = bisshopp_drucker(1.0);
  rod.bending_torsion_stiffness[2] = 0.0;
  BOOST_CHECK_THROW(solve_rod_shooting(rod), InputError);
  // No clamped end: the pairing is unsupported (free twist or rigid motion), with a message.
  rod = bisshopp_drucker(1.0);
  rod.base.kind = RodEndKind::Spherical;
  rod.tip.kind = RodEndKind::Collar;
  try {
    solve_rod_shooting(rod);
    BOOST_FAIL("spherical-collar accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("clamp") != std::string::npos, e.what());
  }
  // A universal base with a free tip: the rod could swing about the joint as a rigid body.
  rod = bisshopp_drucker(1.0);
  rod.base.kind = RodEndKind::Universal;
  try {
    solve_rod_shooting(rod);
    BOOST_FAIL("universal-free accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("rigid body") != std::string::npos, e.what());
  }
  // A universal axis along the rod tangent (no second axis), and a zero revolute axis.
  rod = bisshopp_drucker(1.0);
  rod.tip.kind = RodEndKind::Universal;
  rod.tip.axis = Vec3(0.0, 0.0, 2.0);
  try {
    solve_rod_shooting(rod);
    BOOST_FAIL("universal axis along the tangent accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("universal axis") != std::string::npos, e.what());
  }
  rod.tip.kind = RodEndKind::Revolute;
  rod.tip.axis = Vec3::Zero();
  BOOST_CHECK_THROW(solve_rod_shooting(rod), InputError);
  ShootingOptions o;
  o.integrator = IntegratorMethod::RK4;
  o.rk4_steps = 0;
  BOOST_CHECK_THROW(solve_rod_shooting(bisshopp_drucker(1.0), o), InputError);
  o = ShootingOptions();
  o.integration_relative_tolerance = -1.0;
  BOOST_CHECK_THROW(solve_rod_shooting(bisshopp_drucker(1.0), o), InputError);
  o = ShootingOptions();
  o.tolerance = 0.0;
  BOOST_CHECK_THROW(solve_rod_shooting(bisshopp_drucker(1.0), o), InputError);
  RodStateVector y = ShootingState().to_vector();
  BOOST_CHECK_THROW(integrate_rod(RodOde(bisshopp_drucker(1.0)), 1.0, 0.5, y, IntegratorOptions()),
                    InputError);
}

BOOST_AUTO_TEST_CASE(non_converging_solve_reports_status_without_nan) {
  ShootingOptions o = tight_options();
  o.max_iterations = 1;
  for (bool stepping : {false, true}) {
    o.load_stepping = stepping;
    const ShootingSolution sol = solve_rod_shooting(bisshopp_drucker(15.0), o);
    BOOST_TEST(!sol.summary.converged(), sol.summary.brief_report());
    BOOST_TEST(!sol.summary.message.empty());
    BOOST_TEST(std::isfinite(sol.summary.residual_max_abs));
    BOOST_TEST(sol.summary.residual_max_abs > o.tolerance);
    BOOST_TEST(all_finite(sol.base));
    BOOST_TEST(all_finite(sol.tip));
  }
}

BOOST_AUTO_TEST_CASE(integration_failure_is_reported) {
  ShootingOptions o = tight_options();
  o.max_integration_steps = 5;  // far too few for integration_relative_tolerance = 1e-12
  const ShootingSolution sol = solve_rod_shooting(bisshopp_drucker(2.0), o);
  BOOST_TEST(!sol.summary.converged());
  BOOST_TEST(sol.summary.message.find("max_steps") != std::string::npos, sol.summary.message);
  BOOST_TEST(all_finite(sol.base));
  BOOST_TEST(all_finite(sol.tip));
  // Minimum step guard: a step floor of half the rod cannot meet a relative tolerance of 1e-12 on a bent rod.
  IntegratorOptions io;
  io.relative_tolerance = 1e-12;
  io.min_step_fraction = 0.5;
  ShootingState bent;
  bent.m = Vec3(5, 0, 0);
  RodStateVector y = bent.to_vector();
  const IntegrationReport floor = integrate_rod(RodOde(bisshopp_drucker(2.0)), 0.0, 1.0, y, io);
  BOOST_TEST(!floor.success);
  BOOST_TEST(floor.message.find("underflow") != std::string::npos, floor.message);
  y = ShootingState().to_vector();
  io = IntegratorOptions();
  io.max_steps = 3;
  io.relative_tolerance = 1e-12;
  const IntegrationReport report = integrate_rod(RodOde(bisshopp_drucker(2.0)), 0.0, 1.0, y, io);
  BOOST_TEST(!report.success);
  BOOST_TEST(report.message.find("max_steps") != std::string::npos, report.message);
}