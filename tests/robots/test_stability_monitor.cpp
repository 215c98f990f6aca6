// FK stability monitoring (KinematicsOptions::check_stability, RobotSolution::jacobian_sign): a column
// fed through the base past its Euler buckling length.
//
// Model: one steel rod with a 2 mm x 1 mm rectangular section, clamped upright at the base, fed through
// it (input: its length L), its upper end clamped to a free platform under a dead load F downwards.
// Clamped-free Euler column: it buckles in its weak plane at F = pi^2 E I_min / (4 L^2), i.e. at the length
//   L_cr = (pi / 2) sqrt(E I_min / F);
// the strong plane follows at 2 L_cr (I_max = 4 I_min), the weak plane's second mode at 3 L_cr. Axial
// and shear strains shift these by F / (E A) ~ 1e-5 relative, the 8-element discretisation by less than
// that (test_rod_stability: R4 at 1e-4): negligible against the 10 % steps of the paths below.
#define BOOST_TEST_MODULE stability_monitor
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "robot_fixtures.hpp"

using namespace pcr;

namespace {

// The fed column (robot_fixtures.hpp): load kLoad, Euler length kEulerLength.
constexpr double kLoad = test::kFedColumnLoad;  // N
const double kEulerLength = test::fed_column_euler_length();
using test::fed_column;

KinematicsOptions monitored() {
  KinematicsOptions o;
  o.check_stability = true;
  return o;
}

double tip_offset(const RobotSolution& s) {
  return s.rods[0].centerline.back().head<2>().norm();
}

// The paths: L / L_cr (or z / L_cr) = 0.55, 0.65, ..., 1.45.
std::vector<double> path_ratios() {
  std::vector<double> ratios;
  for (int k = 0; k < 10; ++k) ratios.push_back(0.55 + 0.1 * k);
  return ratios;
}

// Solves along the path (solve(ratio) converged, with the caller's checks) and asserts that the sign of
// det J changes between 0.95 and 1.05 (across L_cr) and at no other step.
void expect_one_change_across_euler_length(const std::function<RobotSolution(double)>& solve) {
  int changes = 0;
  for (double ratio : path_ratios()) {
    const RobotSolution s = solve(ratio);
    BOOST_TEST(s.jacobian_sign != 0);
    const bool crossed = ratio > 1.0 && ratio - 0.1 < 1.0;
    BOOST_TEST(s.jacobian_sign_changed == crossed, "ratio " << ratio);
    changes += s.jacobian_sign_changed;
  }
  BOOST_TEST(changes == 1);
}

}  // namespace

// Without imperfection the straight column is an equilibrium at every length, and the warm-started FK
// stays on it past L_cr, where it is unstable: the sign of det J must change between the two solves
// that bracket L_cr and at no other step.
BOOST_AUTO_TEST_CASE(straight_column_flags_the_buckling_length) {
  ForwardKinematics fk(fed_column(0.0), monitored());
  expect_one_change_across_euler_length([&](double ratio) {
    const RobotSolution s = fk.solve(VecX::Constant(1, ratio * kEulerLength));
    BOOST_REQUIRE_MESSAGE(s.summary.converged(), "L / L_cr = " << ratio << ": " << s.summary.brief_report());
    // Still straight (1e-9 m: round-off of the solve, far below any buckled shape's millimetres).
    BOOST_TEST(tip_offset(s) < 1e-9, "L / L_cr = " << ratio << ": tip offset " << tip_offset(s));
    return s;
  });
}

// With a lateral load (an imperfection) there is no bifurcation: the column bends more and more along the
// load, its equilibria stay stable and the sign of det J never changes. A 5 % load bends it enough before
// L_cr that the warm steps follow this branch.
BOOST_AUTO_TEST_CASE(imperfect_column_keeps_the_sign) {
  ForwardKinematics fk(fed_column(5e-2 * kLoad), monitored());
  int sign = 0;
  for (double ratio : path_ratios()) {
    const RobotSolution s = fk.solve(VecX::Constant(1, ratio * kEulerLength));
    BOOST_REQUIRE_MESSAGE(s.summary.converged(), "L / L_cr = " << ratio << ": " << s.summary.brief_report());
    BOOST_TEST(!s.jacobian_sign_changed, "L / L_cr = " << ratio);
    if (sign == 0) sign = s.jacobian_sign;
    BOOST_TEST(s.jacobian_sign == sign);
    // Past L_cr the column is bent: the clamped-free elastica's tip offset is 2 k / K(k) L with
    // K(k) = (pi / 2) L / L_cr (complete elliptic integral), 0.73 L at 1.15 L_cr and 0.79 L at 1.45 L_cr;
    // half the length shows the path followed the bent branch.
    if (ratio > 1.1) BOOST_TEST(tip_offset(s) > 0.5 * ratio * kEulerLength, "L / L_cr = " << ratio);
  }
}

// With a 0.1 % lateral load, past L_cr three equilibria lie near the path: bent along the load (stable),
// nearly straight (unstable) and bent against it (stable). A warm step across L_cr starts from an almost
// straight column and may land on the nearly straight one. Whichever it reaches, the sign must tell:
// changed from the first (stable, L < L_cr) solve exactly when the column is nearly straight (tip offset
// below 0.1 L; the bent ones are beyond 0.38 L at L >= 1.05 L_cr, see above).
BOOST_AUTO_TEST_CASE(sign_tells_the_nearly_straight_branch) {
  ForwardKinematics fk(fed_column(1e-3 * kLoad), monitored());
  int first_sign = 0, straight_after_cr = 0;
  for (double ratio : path_ratios()) {
    const double length = ratio * kEulerLength;
    const RobotSolution s = fk.solve(VecX::Constant(1, length));
    BOOST_REQUIRE_MESSAGE(s.summary.converged(), "L / L_cr = " << ratio << ": " << s.summary.brief_report());
    if (first_sign == 0) first_sign = s.jacobian_sign;
    const bool nearly_straight = tip_offset(s) < 0.1 * length;
    const bool unstable_expected = ratio > 1.0 && nearly_straight;
    BOOST_TEST((s.jacobian_sign != first_sign) == unstable_expected,
               "L / L_cr = " << ratio << ": tip offset " << tip_offset(s) / length << " L");
    straight_after_cr += unstable_expected;
  }
  BOOST_TEST_MESSAGE("nearly straight solves past L_cr: " << straight_after_cr);
}

// IK of the platform height along the same lengths: the straight column reaches every height, and the
// sign of the FK system at the IK solution changes where the column passes L_cr.
BOOST_AUTO_TEST_CASE(inverse_kinematics_flags_the_buckling_length) {
  LinkTarget height;
  height.link = "platform";
  height.mode = LinkTarget::Mode::Position;
  height.components = {{false, false, true, false, false, false}};
  InverseKinematics ik(fed_column(0.0), {height}, monitored());
  BOOST_REQUIRE(ik.square());
  expect_one_change_across_euler_length([&](double ratio) {
    Pose target;
    target.position = Vec3(0, 0, ratio * kEulerLength);
    const RobotSolution s = ik.solve({target});
    BOOST_REQUIRE_MESSAGE(s.summary.converged(), "z / L_cr = " << ratio << ": " << s.summary.brief_report());
    // Straight: the length is the height plus the axial shortening F L / (E A) = 2.5e-6 L.
    const double z = target.position.z();
    BOOST_TEST(std::abs(s.inputs[0] - z) < 1e-5 * z, "z / L_cr = " << ratio << ": length " << s.inputs[0]);
    return s;
  });
}

// Not asked: nothing computed, nothing claimed.
BOOST_AUTO_TEST_CASE(unmonitored_solves_report_no_sign) {
  ForwardKinematics fk(fed_column(0.0));
  const RobotSolution s = fk.solve(VecX::Constant(1, 1.2 * kEulerLength));
  BOOST_REQUIRE(s.summary.converged());
  BOOST_TEST(s.jacobian_sign == 0);
  BOOST_TEST(!s.jacobian_sign_changed);
}
