// Robots with rods pinned at both ends by the shooting reference (part of the test_shooting_joints
// module): a planar robot with massless rods against the rigid-truss solution, a tripod with revolute
// starts against the same with passive pins.
#include <boost/test/unit_test.hpp>

#include <Eigen/LU>
#include <cmath>
#include <string>

#include "joint_robots.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/shooting/shooting_robot_solver.hpp"
#include "robot_fixtures.hpp"
#include "shooting_robots/joint_checks.hpp"

using namespace pcr;
using namespace pcr::test_robots;
using test::tight_shooting;

// ---- (c) planar robot pinned at both ends --------------------------------------------------------------
namespace {

// The rigid-body statics of planar_pinned(massless rods): each rod a straight two-force member of
// axial force N_i = EA eps_i (tension > 0) and length L_i (1 + eps_i) between its pins (exact for a
// Cosserat rod without distributed loads whose end moments vanish: n = N d3, m = 0,
// v = (0, 0, 1 + N / EA)). Unknowns the platform's x, z, rotation phi about y and the strains eps_1..3;
// equations the three lengths and the platform's in-plane balance relative to its weight W (moment
// relative to W x 0.1 m). Solved here by Newton with a central-difference Jacobian from the initial pose.
struct Truss {
  Pose pose;
  Vec3 axial;
};
Truss solve_truss(const RobotModel& m, const VecX& lengths) {
  const double EA = m.rods()[0].rod.shear_extension_stiffness[2];
  const Platform& platform = m.platforms()[0];
  const Vec3 weight = platform.mass * m.gravity();
  const double W = weight.norm();
  auto equations = [&](const Eigen::Matrix<double, 6, 1>& x, Pose* pose, Vec3* axial) {
    Pose P;
    P.position = Vec3(x[0], 0.0, x[1]);
    P.orientation = quat_from_rotation(rotation_y(x[2]));
    Eigen::Matrix<double, 6, 1> r;
    Vec3 F = weight, M = (P.rotation() * platform.center_of_mass).cross(weight);
    for (int i = 0; i < 3; ++i) {
      const RodElement& e = m.rods()[i];
      // The pin's origin (the start attachment does not move with the pin angle).
      const Vec3 B =
          m.attachment_pose(e.start, m.default_joint_values(), m.initial_platform_poses()).position;
      const Vec3 end = P.transform_point(e.end.frame.position);
      const Vec3 d = end - B;
      const double N = EA * x[3 + i];
      r[i] = (d.norm() - lengths[i] * (1.0 + x[3 + i])) / lengths[i];
      F -= N * d.normalized();  // the rod pulls the platform towards its base when in tension
      M -= (end - P.position).cross(N * d.normalized());
    }
    r[3] = F.x() / W;
    r[4] = F.z() / W;
    r[5] = M.y() / (0.1 * W);
    if (pose) *pose = P;
    if (axial) *axial = EA * x.tail<3>();
    return r;
  };
  Eigen::Matrix<double, 6, 1> x;
  x << 0.0, m.platforms()[0].initial_pose.position.z(), 0.0, 0.0, 0.0, 0.0;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const Eigen::Matrix<double, 6, 1> r = equations(x, nullptr, nullptr);
    if (r.cwiseAbs().maxCoeff() < 1e-15) break;
    Eigen::Matrix<double, 6, 6> J;
    for (int j = 0; j < 6; ++j) {
      Eigen::Matrix<double, 6, 1> xp = x, xm = x;
      const double h = j < 3 ? 1e-7 : 1e-9;  // m / rad, strain
      xp[j] += h;
      xm[j] -= h;
      J.col(j) = (equations(xp, nullptr, nullptr) - equations(xm, nullptr, nullptr)) / (2 * h);
    }
    x -= J.fullPivLu().solve(r);
  }
  Truss t;
  const Eigen::Matrix<double, 6, 1> r = equations(x, &t.pose, &t.axial);
  BOOST_REQUIRE_MESSAGE(r.cwiseAbs().maxCoeff() < 1e-14, "truss Newton: residual " << r.transpose());
  return t;
}

}  // namespace

BOOST_AUTO_TEST_CASE(pinned_planar_robot_with_massless_rods_is_a_truss) {
  const auto model = planar_pinned(true);
  ShootingRobotSolver shooting(model, tight_shooting());
  for (double move : {0.0, 0.01}) {
    VecX lengths = model->default_input_values();
    lengths[0] += move;
    lengths[2] -= 0.5 * move;
    const RobotSolution s = shooting.fk(lengths);
    require_converged(s, "planar FK move " + std::to_string(move));
    const Truss t = solve_truss(*model, lengths);
    // Both solve the same exact equations: shooting to a scaled residual of 1e-12 (L_s = 0.5 m,
    // F_s ~ 1.6 N from EI / L^2) with Dormand-Prince at 1e-12 per step; the truss to 1e-15. Poses to
    // 1e-10 m / rad, axial forces to 1e-9 N.
    BOOST_TEST_MESSAGE("move " << move << ": pose difference " << position_difference(s.platforms[0], t.pose)
                               << " m, axial forces " << t.axial.transpose() << " N");
    BOOST_TEST(position_difference(s.platforms[0], t.pose) < 1e-10);
    BOOST_TEST(angle_difference(s.platforms[0], t.pose) < 1e-10);
    for (int i = 0; i < 3; ++i) {
      BOOST_TEST(std::abs(s.rods[i].axial_force - t.axial[i]) < 1e-9, model->rods()[i].name);
      // Straight rods in the plane, no moment anywhere (pins about y; nothing out of the plane).
      BOOST_TEST(s.rods[i].base_moment.norm() + s.rods[i].tip_moment.norm() < 1e-11);
      for (const Vec3& p : s.rods[i].centerline) BOOST_TEST(std::abs(p.y()) < 1e-12);
    }
  }
}

BOOST_AUTO_TEST_CASE(tripod_with_revolute_starts_equals_passive_pins) {
  // Bent rods (their weight, the platform's off-centre weight; no closed form): revolute starts against
  // passive revolute joints carrying massless links to which the rods are clamped, the same mechanics
  // with other unknowns: poses to 1e-9 m / rad and wrenches to 1e-8 of the largest as for the 6-RUS-like
  // robot.
  const auto pinned = tripod_pinned(false), passive = tripod_pinned(true);
  ShootingRobotSolver a(pinned, tight_shooting()), b(passive, tight_shooting());
  const RobotSolution sa = a.fk(VecX(0)), sb = b.fk(VecX(0));
  require_converged(sa, "revolute starts");
  require_converged(sb, "passive pins");
  BOOST_TEST(position_difference(sa.platforms[0], sb.platforms[0]) < 1e-9);
  BOOST_TEST(angle_difference(sa.platforms[0], sb.platforms[0]) < 1e-9);
  double size = 0.0, diff = 0.0;
  for (int i = 0; i < 3; ++i) {
    size = std::max({size, sa.rods[i].base_force.norm(), sa.rods[i].base_moment.norm()});
    diff = std::max({diff, (sa.rods[i].base_force - sb.rods[i].base_force).norm(),
                     (sa.rods[i].base_moment - sb.rods[i].base_moment).norm()});
  }
  BOOST_TEST(diff < 1e-8 * size, "wrenches differ by " << diff << " of " << size);
  check_platform_balance(*pinned, sa, 1e-10);
  // The pins turn (the platform sinks and tilts) and pass no moment about their axes (residual rows
  // 1e-12 x M_s).
  BOOST_REQUIRE(sb.passive_joints.size() == 3);
  BOOST_TEST(sb.passive_joints.cwiseAbs().maxCoeff() > 1e-4, "pin angles " << sb.passive_joints.transpose());
  for (int i = 0; i < 3; ++i) {
    const RodElement& e = pinned->rods()[i];
    const Vec3 pin = e.start.frame.rotation() * e.start.axis;
    BOOST_TEST(std::abs(sa.rods[i].base_moment.dot(pin)) < 1e-11, e.name);
  }
}
