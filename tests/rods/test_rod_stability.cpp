// Stability indicator of solve_rod (sign of det J against the unloaded state) on the clamped-free
// column of scene R4 (P_cr = pi^2 EI / (4 L^2)): below P_cr the straight column is stable, above it the
// straight column is unstable and the buckled one (reached here through a lateral imperfection) is
// stable (Timoshenko & Gere, Theory of Elastic Stability, §2.1 and §2.7). The section is stiffer about
// d2 (EI2 = 2 EI1) so that only one mode becomes critical at P_cr = pi^2 EI1 / (4 L^2), bending about
// d1 = x, which moves the tip along y: with a circular section two modes cross zero together and det J
// keeps its sign (the documented limit of the indicator).
#define BOOST_TEST_MODULE rod_stability
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "pcr/rods/rod_solve.hpp"
#include "rods/rod_fixtures.hpp"

using namespace pcr;

namespace {

constexpr double kLength = 1.0, kEI = 1.0;
const double kPcr = M_PI * M_PI * kEI / (4.0 * kLength * kLength);

// Column along +z clamped at the origin; EA L^2 / EI = 1e4 (nearly inextensible, like the elastica).
RodModel column(double second_bending_stiffness) {
  return test::cantilever(kLength, Vec3::Constant(1e4), Vec3(kEI, second_bending_stiffness, 2.0 * kEI));
}

// Dead tip load: compression lambda P_cr, lateral forces lateral * P along y (the weak direction) and
// lateral_x * P along x.
RodSolution solve_column(RodFormulation form, double lambda, double lateral,
                         double second_bending_stiffness = 2.0 * kEI, double lateral_x = 0.0) {
  RodModel m = column(second_bending_stiffness);
  const double P = lambda * kPcr;
  m.tip.force = Vec3(lateral_x * P, lateral * P, -P);
  RodSolveOptions o;
  o.discretization = {form, 5, 8};
  o.check_stability = true;
  return solve_rod(m, o);
}

}  // namespace

BOOST_AUTO_TEST_CASE(straight_column_below_and_above_the_euler_load) {
  for (RodFormulation form : {RodFormulation::Mixed, RodFormulation::Primal}) {
    const RodSolution below = solve_column(form, 0.95, 0.0);
    BOOST_TEST_REQUIRE(below.summary.converged(), below.summary.brief_report());
    BOOST_TEST(std::abs(below.tip().position.x()) <= 1e-12);  // straight: no lateral load, no imperfection
    BOOST_TEST(to_string(below.stability) == std::string("sign_kept"));

    const RodSolution above = solve_column(form, 1.05, 0.0);
    BOOST_TEST_REQUIRE(above.summary.converged(), above.summary.brief_report());
    BOOST_TEST(std::abs(above.tip().position.x()) <= 1e-12);  // the straight (trivial) branch
    BOOST_TEST(to_string(above.stability) == std::string("unstable"));
  }
}

BOOST_AUTO_TEST_CASE(buckled_column_is_stable_and_the_near_straight_one_is_not) {
  // Imperfection along the weak direction, 5 % of P. At 1.05 P_cr the direct solve fails and load
  // stepping follows the branch connected to the unloaded state: bent towards the imperfection, further
  // than the post-buckled elastica (delta / L = 0.38) because the imperfection adds to it: stable.
  const double elastica = test::clamped_free_elastica_deflection(1.05) * kLength;
  const RodSolution buckled = solve_column(RodFormulation::Mixed, 1.05, 0.05);
  BOOST_TEST_REQUIRE(buckled.summary.converged(), buckled.summary.brief_report());
  BOOST_TEST(buckled.tip().position.y() >= elastica);
  BOOST_TEST(to_string(buckled.stability) == std::string("sign_kept"));
  // At 1.5 P_cr Newton converges directly, from the straight guess, to a small deflection against the
  // imperfection (the linear beam-column deflection H (tan kL - kL) / (P k) is negative above P_cr):
  // the unstable branch of the imperfect bifurcation.
  const RodSolution against = solve_column(RodFormulation::Mixed, 1.5, 0.05);
  BOOST_TEST_REQUIRE(against.summary.converged(), against.summary.brief_report());
  BOOST_TEST(against.tip().position.y() < 0.0);
  BOOST_TEST(std::abs(against.tip().position.y()) <= 0.5 * elastica);
  BOOST_TEST(to_string(against.stability) == std::string("unstable"));
  // Imperfection along the strong direction x (critical load 2 P_cr there): bent along x, but above the
  // weak direction's P_cr the column is unstable in y.
  const RodSolution strong = solve_column(RodFormulation::Mixed, 1.05, 0.0, 2.0 * kEI, 0.05);
  BOOST_TEST_REQUIRE(strong.summary.converged(), strong.summary.brief_report());
  BOOST_TEST(strong.tip().position.x() > 0.0);
  BOOST_TEST(to_string(strong.stability) == std::string("unstable"));
}

BOOST_AUTO_TEST_CASE(a_double_critical_mode_keeps_the_sign) {
  // Circular section (EI1 = EI2): both bending modes cross zero at P_cr, det J changes sign twice.
  const RodSolution above = solve_column(RodFormulation::Mixed, 1.05, 0.0, kEI);
  BOOST_TEST_REQUIRE(above.summary.converged(), above.summary.brief_report());
  BOOST_TEST(to_string(above.stability) == std::string("sign_kept"));
  // Above the second critical load of the stiffer-section column (2 P_cr): two crossings as well.
  const RodSolution above_both = solve_column(RodFormulation::Mixed, 2.1, 0.0);
  BOOST_TEST_REQUIRE(above_both.summary.converged(), above_both.summary.brief_report());
  BOOST_TEST(to_string(above_both.stability) == std::string("sign_kept"));
}

BOOST_AUTO_TEST_CASE(not_checked_unless_asked) {
  RodModel m = column(2.0 * kEI);
  m.tip.force = Vec3(0.0, 0.0, -0.5 * kPcr);
  const RodSolution s = solve_rod(m);
  BOOST_TEST_REQUIRE(s.summary.converged());
  BOOST_TEST(to_string(s.stability) == std::string("not_checked"));
}
