// Joint rod ends by shooting against closed forms (part of the test_shooting module): propped
// cantilever, simply supported beam, universal-spherical rod in tension and in torsion, pinned beam with
// an end moment, revolute rod in tension.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/rods/shooting/joint_ends.hpp"
#include "pcr/rods/shooting/rod_integrator.hpp"
#include "pcr/rods/shooting/rod_shooting.hpp"
#include "shooting/shooting_fixtures.hpp"

using namespace pcr;
using namespace pcr::shooting_test;

// ---- joint ends against closed forms ----------------------------------------------------------------
namespace {

// Straight rod along e3 from the origin, EI = 1, L = 1, under a small transverse load w e1 per length,
// for the Euler-Bernoulli beam formulas. kGA = 1e8 EI / L^2 makes shear negligible (relative
// EI / (kGA L^2) = 1e-8). With both ends held in position the deflection stretches the centreline by
// ~(1/2) int w'^2 ~ 5 (delta / L)^2 (delta < w L^4 / (77 EI) = 1.3e-5), an axial force of up to
// EA 5 (delta/L)^2 = 8.5e-7 N for EA = 1e3, which changes the transverse reactions (3e-4 N and up) by a
// relative N L^2 / (10 EI) < 1e-7; geometric nonlinearity is O(slope^2) < 1e-9. Bound for the
// comparisons: 1e-6 relative.
constexpr double kBeamLoad = 1e-3;
constexpr double kBeamTheory = 1e-6;
RodModel pinned_beam(RodEndKind base, RodEndKind tip) {
  RodModel rod = test::cantilever(1.0, Vec3(1e8, 1e8, 1e3), Vec3(1.0, 1.0, 1.0));
  rod.loads.force_per_length = Vec3(kBeamLoad, 0.0, 0.0);
  rod.base.kind = base;
  rod.tip.kind = tip;
  rod.tip.position = Vec3(0.0, 0.0, 1.0);
  // Pins about e2: normal to the load plane x-z.
  rod.base.axis = rod.tip.axis = Vec3::UnitY();
  return rod;
}

}  // namespace

BOOST_AUTO_TEST_CASE(propped_cantilever_matches_euler_bernoulli) {
  // Clamped at s = 0, pinned at s = L (revolute about e2): reaction at the pin 3/8 w L, at the clamp
  // 5/8 w L and w L^2 / 8, slope at the pin w L^3 / (48 EI) (Roark's Formulas for Stress and Strain,
  // beam fixed at one end and supported at the other, uniform load).
  const RodModel rod = pinned_beam(RodEndKind::Clamped, RodEndKind::Revolute);
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  const double w = kBeamLoad;
  // The pin pushes against the load: n(L) = -3/8 w L e1; the clamp: base_force = -n(0) = -5/8 w L e1.
  BOOST_TEST(std::abs(sol.tip.n.x() + 3.0 / 8.0 * w) < kBeamTheory * w, "n(L) " << sol.tip.n.transpose());
  BOOST_TEST(std::abs(sol.base_force().x() + 5.0 / 8.0 * w) < kBeamTheory * w);
  BOOST_TEST(std::abs(std::abs(sol.base_moment().y()) - w / 8.0) < kBeamTheory * w);
  // Nothing out of the load plane (the pin transmits the moments about e1, e3; they vanish here).
  // (Unknowns found to the residual tolerance 1e-12 x M_c = 1 times the map's condition, < 100.)
  BOOST_TEST(std::abs(sol.base_moment().x()) + std::abs(sol.base_moment().z()) < 1e-10);
  BOOST_TEST(std::abs(sol.tip.m.y()) < 1e-11);  // no moment about the pin: a residual row, 1e-12 x M_c = 1
  const double slope = rotation_angle_between(sol.tip.R(), Mat3::Identity());
  BOOST_TEST(std::abs(slope - w / 48.0) < kBeamTheory * w / 48.0 + kTightIntegration, "slope " << slope);
}

BOOST_AUTO_TEST_CASE(simply_supported_beam_matches_euler_bernoulli) {
  // Revolute at both ends about e2: reactions w L / 2, end slopes w L^3 / (24 EI), midspan deflection
  // 5 w L^4 / (384 EI) (Roark, simply supported beam, uniform load).
  const RodModel rod = pinned_beam(RodEndKind::Revolute, RodEndKind::Revolute);
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  const double w = kBeamLoad;
  BOOST_TEST(std::abs(sol.tip.n.x() + w / 2.0) < kBeamTheory * w);
  BOOST_TEST(std::abs(sol.base.n.x() - w / 2.0) < kBeamTheory * w);
  // The pins pass no bending moment here (to the residual tolerance 1e-12 x M_c = 1 times the map's
  // condition, < 100).
  BOOST_TEST(max_abs(sol.base.m) < 1e-10);
  for (const ShootingState* end : {&sol.base, &sol.tip}) {
    const double slope = rotation_angle_between(end->R(), Mat3::Identity());
    BOOST_TEST(std::abs(slope - w / 24.0) < kBeamTheory * w / 24.0 + kTightIntegration, "slope " << slope);
  }
  const double deflection = sol.at(0.5).p.x();
  BOOST_TEST(std::abs(deflection - 5.0 * w / 384.0) < kBeamTheory * 5.0 * w / 384.0 + kTightIntegration,
             "deflection " << deflection);
}

BOOST_AUTO_TEST_CASE(universal_spherical_rod_in_tension_is_straight_along_the_chord) {
  // Universal base (first axis e1, so b = e3 x e1 = e2) at the origin, spherical tip at l d: the rod is a
  // two-force member, straight along d with n = N d, m = 0 and stretch 1 + N / EA (an exact Cosserat
  // solution: v = (0, 0, 1 + N / EA)), and R(0) = R_x(theta1) R_y(theta2) with
  // d = (sin theta2, -sin theta1 cos theta2, cos theta1 cos theta2).
  RodModel rod = test::cantilever(1.0, Vec3(60, 70, 100), Vec3(1.0, 1.2, 0.8));
  rod.base.kind = RodEndKind::Universal;
  rod.base.axis = Vec3::UnitX();
  rod.tip.kind = RodEndKind::Spherical;
  const Vec3 d = Vec3(0.3, -0.4, 1.0).normalized();
  const double N = 2.0, stretch = 1.0 + N / 100.0;
  rod.tip.position = stretch * d;
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  const double theta2 = std::asin(d.x()), theta1 = std::atan2(-d.y(), d.z());
  const Mat3 R0 = rotation_x(theta1) * rotation_y(theta2);
  BOOST_TEST(rotation_angle_between(sol.base.R(), R0) < kTightIntegration);
  BOOST_TEST(max_abs(sol.base.n - N * d) < kTightIntegration * N);
  BOOST_TEST(max_abs(sol.base.m) < kTightIntegration);
  for (int i = 0; i <= 10; ++i) {
    const ShootingState x = sol.at(0.1 * i);
    BOOST_TEST(max_abs(x.p - 0.1 * i * stretch * d) < kTightIntegration);
    BOOST_TEST(rotation_angle_between(x.R(), R0) < kTightIntegration);
  }
}

BOOST_AUTO_TEST_CASE(universal_joint_holds_the_twist_of_a_rod_in_torsion) {
  // Universal base (first axis e1) at the origin, the rod along d = R_x(0.4) e3 to a spherical tip at d
  // that applies the torque T d: the joint transmits the torsion along t = e1 x R b = d (theta2 = 0),
  // so the rod stays straight with m = T d and twists at the rate T / GJ:
  // R(s) = R_x(0.4) R_z(T s / GJ) (exact: n = 0, u = (0, 0, T / GJ)).
  RodModel rod = test::cantilever(1.0, Vec3(60, 70, 100), Vec3(1.0, 1.2, 0.8));
  rod.base.kind = RodEndKind::Universal;
  rod.base.axis = Vec3::UnitX();
  rod.tip.kind = RodEndKind::Spherical;
  const Mat3 R0 = rotation_x(0.4);
  const Vec3 d = R0.col(2);
  const double T = 0.5, GJ = 0.8;
  rod.tip.position = d;
  rod.tip.moment = T * d;
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  BOOST_TEST(max_abs(sol.base.m - T * d) < kTightIntegration);
  BOOST_TEST(max_abs(sol.base.n) < kTightIntegration);
  BOOST_TEST(rotation_angle_between(sol.base.R(), R0) < kTightIntegration);
  BOOST_TEST(rotation_angle_between(sol.tip.R(), R0 * rotation_z(T / GJ)) < kTightIntegration);
}

BOOST_AUTO_TEST_CASE(pinned_beam_with_end_moment_matches_beam_theory) {
  // Revolute base about e2 at the origin (pin), spherical tip at L e3 loaded by the moment M e2: the
  // bending moment grows linearly from 0 at the pin to M, the section rotation is
  // psi(s) = -M L / (6 EI) + M s^2 / (2 EI L) about e2 (Roark, simply supported beam with an end couple):
  // the pin turns by -M L / (6 EI), the tip by M L / (3 EI). Bound as for pinned_beam (no distributed
  // load here; slope M L / (3 EI) = 3.3e-4, geometric nonlinearity O(slope^2) ~ 1e-7 relative; shear
  // V / kGA = 1e-11): kBeamTheory relative.
  RodModel rod = pinned_beam(RodEndKind::Revolute, RodEndKind::Spherical);
  rod.loads.force_per_length.setZero();
  const double M = 1e-3;  // EI = 1, L = 1
  rod.tip.moment = Vec3(0.0, M, 0.0);
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  const double pin = rotation_angle_between(sol.base.R(), rotation_y(-M / 6.0));
  const double tip = rotation_angle_between(sol.tip.R(), rotation_y(M / 3.0));
  BOOST_TEST(pin < kBeamTheory * M / 6.0 + kTightIntegration, "pin rotation error " << pin);
  BOOST_TEST(tip < kBeamTheory * M / 3.0 + kTightIntegration, "tip rotation error " << tip);
  // Exact statics (the tip stays at L e3): e2 . (m(L) - m(0) + L e3 x n) = 0 with m(0) . e2 = 0 gives
  // n_x = -M / L; nothing out of the plane. Residual rows 1e-12 x F_c, M_c = 1 times the map's condition
  // (< 100).
  BOOST_TEST(std::abs(sol.base.n.x() + M) < 1e-10);
  BOOST_TEST(std::abs(sol.base.n.y()) + std::abs(sol.base.m.y()) < 1e-10);
}

BOOST_AUTO_TEST_CASE(revolute_rod_in_tension_turns_rigidly_about_its_pin) {
  // Revolute base at the origin with the default axis (the end frame's x axis), spherical tip at
  // stretch R_x(theta) e3: a straight two-force member turned rigidly by theta about the pin,
  // R(s) = R_x(theta), n = N d, m = 0, stretch 1 + N / EA (exact, as for the universal rod below).
  RodModel rod = test::cantilever(1.0, Vec3(60, 70, 100), Vec3(1.0, 1.2, 0.8));
  rod.base.kind = RodEndKind::Revolute;
  rod.tip.kind = RodEndKind::Spherical;
  const double theta = 0.5, N = 2.0, stretch = 1.0 + N / 100.0;
  const Mat3 R = rotation_x(theta);
  rod.tip.position = stretch * R.col(2);
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  for (int i = 0; i <= 10; ++i) {
    const ShootingState x = sol.at(0.1 * i);
    BOOST_TEST(max_abs(x.p - 0.1 * i * stretch * R.col(2)) < kTightIntegration);
    BOOST_TEST(rotation_angle_between(x.R(), R) < kTightIntegration);
    BOOST_TEST(max_abs(x.n - N * R.col(2)) < kTightIntegration * N);
    BOOST_TEST(max_abs(x.m) < kTightIntegration);
  }
}
