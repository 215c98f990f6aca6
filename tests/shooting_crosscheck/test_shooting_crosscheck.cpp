// Single rods solved by the two independent methods of pcr: isogeometric collocation (mixed form,
// fine discretisation, Newton to a tight residual) and shooting (Dormand-Prince 5(4) at 1e-12, Newton
// on the base wrench). Both converge to the exact solution of the same RodModel, so their centerlines
// must agree to the sum of their (tiny) discretisation errors: asserted at 1e-8 L over 201 points.
//
// Measured max differences / L (collocation tolerance 1e-12, shooting Dormand-Prince rel = abs = 1e-12,
// residual 1e-12); they fall by ~2^7 per halving of the elements at degree 6, so they are the
// collocation discretisation error, and shooting is the more accurate of the two at these settings:
//   cantilever   p6 e16 1.1e-7, p6 e32 1.0e-9, p6 e64 7.3e-12, p8 e32 1.2e-12
//   precurved    p6 e16 9.7e-8, p6 e32 6.6e-10, p6 e64 4.7e-12, p8 e32 9.1e-13
//   spring       p8 e48 8.2e-9, p8 e96 7.9e-12
// The gravity cantilever and a rod under distributed force and moment are also solved in the condensed
// form (n, m from the closed-form balance): 1.3e-12 and 8.5e-13, as the mixed form.
#define BOOST_TEST_MODULE shooting_crosscheck
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "pcr/math/so3.hpp"
#include "pcr/rods/rod_solve.hpp"
#include "rods/rod_fixtures.hpp"
#include "shooting_crosscheck/shooting_centerline.hpp"

using namespace pcr;

namespace {

/// Max over 201 points of |p_collocation(s) - p_shooting(s)| / L.
double centerline_difference(const RodModel& m, const RodDiscretization& d) {
  RodSolveOptions o;
  o.discretization = d;
  o.tolerance = 1e-12;
  const RodSolution col = solve_rod(m, o);
  BOOST_REQUIRE_MESSAGE(col.summary.converged(), m.name << " collocation: " << col.summary.brief_report());
  std::vector<double> s;
  for (int i = 0; i <= 200; ++i) s.push_back(m.length * i / 200.0);
  const test::ShootingCenterline sh = test::shooting_centerline(m, s, 1e-12);
  BOOST_REQUIRE_MESSAGE(sh.converged, m.name << " shooting: " << sh.report);
  double worst = 0.0;
  for (size_t i = 0; i < s.size(); ++i)
    worst = std::max(worst, (col.at(s[i]).position - sh.points[i]).norm());
  return worst / m.length;
}

// 1e-8 L: the agreement requirement; the measured differences (header comment) are smaller.
constexpr double kAgreement = 1e-8;

// Horizontal steel wire (E 200 GPa, G 80 GPa, 8000 kg/m^3, radius 1 mm, L = 1 m) clamped with d3 = e_x,
// sagging under its weight: w L^3 / EI = 1.57, a large deflection.
RodModel steel_cantilever() {
  RodModel m = test::cantilever(1.0, Vec3::Ones(), Vec3::Ones());
  m.name = "steel cantilever";
  m.set_material_and_section(Material{200e9, 80e9, 8000}, CrossSection::circle(1e-3));
  m.base.orientation = quat_from_rotation(rotation_y(M_PI / 2));
  m.loads.gravity = Vec3(0, 0, -9.81);
  return m;
}

}  // namespace

BOOST_AUTO_TEST_CASE(gravity_loaded_steel_cantilever) {
  const RodModel m = steel_cantilever();
  // Mixed, and condensed (n, m from the closed-form balance with the integral of p): both against
  // shooting.
  for (RodFormulation f : {RodFormulation::Mixed, RodFormulation::Condensed}) {
    const double d = centerline_difference(m, {f, 8, 32});
    BOOST_TEST_MESSAGE("steel cantilever, " << to_string(f) << ": max centerline difference " << d << " L");
    BOOST_TEST(d < kAgreement, to_string(f) << ": " << d);
  }
}

BOOST_AUTO_TEST_CASE(distributed_force_and_moment) {
  // A cantilever (EI = 1, EA = GA = 1e3, L = 1) under a distributed force and moment in the world frame
  // (q L^3 / EI = 2 and l L^2 / EI = 0.5) with a tip force: the condensed form's -l s and integral
  // terms against shooting; the mixed form as the baseline.
  RodModel m = test::cantilever(1.0, Vec3(1e3, 1e3, 1e3), Vec3(1.0, 1.0, 0.8));
  m.name = "distributed loads";
  m.loads.force_per_length = Vec3(2.0, 0.0, -0.5);
  m.loads.moment_per_length = Vec3(0.0, 0.5, 0.2);
  m.tip.force = Vec3(0.0, 0.3, 0.0);
  for (RodFormulation f : {RodFormulation::Mixed, RodFormulation::Condensed}) {
    const double d = centerline_difference(m, {f, 8, 32});
    BOOST_TEST_MESSAGE("distributed loads, " << to_string(f) << ": max centerline difference " << d << " L");
    BOOST_TEST(d < kAgreement, to_string(f) << ": " << d);
  }
}

BOOST_AUTO_TEST_CASE(condensed_and_mixed_discretisation_errors_under_gravity) {
  // Under a distributed load the condensed form is not the mixed midpoint scheme (its m is the exact
  // closed-form balance, not a spline): its discretisation error against shooting, coarse meshes of the
  // steel cantilever above. Measured ratios condensed / mixed 0.97-1.006 (p = 4..6, E = 2..8) and 0.49
  // at p = 6, E = 8; asserted: no worse than 1.1x the mixed error (10 % above the largest ratio).
  const RodModel m = steel_cantilever();
  for (int p : {4, 5, 6})
    for (int e : {2, 4, 8}) {
      const double dm = centerline_difference(m, {RodFormulation::Mixed, p, e});
      const double dc = centerline_difference(m, {RodFormulation::Condensed, p, e});
      BOOST_TEST_MESSAGE("p " << p << " E " << e << ": mixed " << dm << " L, condensed " << dc << " L");
      BOOST_TEST(dc <= 1.1 * dm, "p " << p << " E " << e << ": condensed " << dc << " against mixed " << dm);
    }
}

BOOST_AUTO_TEST_CASE(condensed_form_with_running_integrals_keeps_the_bound_on_finer_meshes) {
  // The condensed form under loads carries the integral of p in local unknowns (collocation_rod.hpp);
  // its error against shooting on finer meshes than above, where the sum over every control point cost
  // most, with errors still well above the round-off of both methods (1e-12 L): within the bound above,
  // 1.1x the mixed error.
  // Measured ratios condensed / mixed: 1.0001 (p = 3, E = 40 and 64), 0.97 (p = 4, E = 40 and 64).
  const RodModel m = steel_cantilever();
  // (More than kMaxBandedCondensedPoints control points: the running integrals.)
  const RodDiscretization meshes[] = {{RodFormulation::Condensed, 3, 40},
                                      {RodFormulation::Condensed, 3, 64},
                                      {RodFormulation::Condensed, 4, 40},
                                      {RodFormulation::Condensed, 4, 64}};
  for (const RodDiscretization& condensed : meshes) {
    RodDiscretization mixed = condensed;
    mixed.formulation = RodFormulation::Mixed;
    const double dm = centerline_difference(m, mixed);
    const double dc = centerline_difference(m, condensed);
    BOOST_TEST_MESSAGE("p " << condensed.degree << " E " << condensed.elements << ": mixed " << dm
                            << " L, condensed " << dc << " L");
    BOOST_TEST(dc <= 1.1 * dm, "p " << condensed.degree << " E " << condensed.elements << ": condensed " << dc
                                    << " against mixed " << dm);
  }
}

BOOST_AUTO_TEST_CASE(precurved_rod_with_tip_load) {
  // Constant intrinsic curvature kappa0 = (0, 2, 0.5) (a 2 rad arc with twist when unloaded), shear and
  // extension compliant (K_SE = 1e3 EI / L^2), and a tip force and moment that bend it back.
  RodModel m = test::cantilever(1.0, Vec3(1e3, 1e3, 2e3), Vec3(1.0, 1.5, 0.8));
  m.name = "precurved rod";
  m.intrinsic.curvature = Vec3(0.0, 2.0, 0.5);
  m.tip.force = Vec3(1.0, 0.5, -2.0);
  m.tip.moment = Vec3(0.3, -0.4, 0.1);
  const double d = centerline_difference(m, {RodFormulation::Mixed, 8, 32});
  BOOST_TEST_MESSAGE("precurved rod: max centerline difference " << d << " L");
  BOOST_TEST(d < kAgreement);
}

BOOST_AUTO_TEST_CASE(helical_spring_at_large_load) {
  // Weeger et al. 2017 §7 spring (set-up of test_rod_validation.cpp helical_spring_small_load_stiffness):
  // stress-free helix kappa0 = (k, 0, tau), radius R = 0.01, pitch angle 20 deg, 3 coils, pulled along
  // its axis by a force through the axis (dead force at the wire tip + the moment of the arm to the
  // axis). Large load: F = 2 R / compliance, i.e. a linear-theory extension of twice the coil radius
  // (~30 % of the spring's height), far outside the linear range.
  const test::HelicalSpring spring = test::helical_spring(20.0);
  RodModel m = spring.model(1e6, 2.0 * spring.radius / spring.compliance);
  m.name = "helical spring";
  const double d = centerline_difference(m, {RodFormulation::Mixed, 8, 96});
  BOOST_TEST_MESSAGE("helical spring: max centerline difference " << d << " L");
  BOOST_TEST(d < kAgreement);
}
