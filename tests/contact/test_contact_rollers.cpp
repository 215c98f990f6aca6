// Rollers (finite cylinders, frictionless: docs/contact.md): the gap function in its four regions, a roller
// against the infinite cylinder it is a piece of, and the shipped models/planar_rollers.urdf by FK and IK.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "contact_fixtures.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/solve/jacobian_check.hpp"

using namespace pcr;

namespace {

// Centre (0.1, 0, 0), axis y, radius 0.02, length 0.04.
Obstacle roller() {
  Obstacle o;
  o.name = "roller";
  o.shape = ObstacleShape::Roller;
  o.position = Vec3(0.1, 0, 0);
  o.direction = Vec3::UnitY();
  o.radius = 0.02;
  o.length = 0.04;
  return o;
}

}  // namespace

BOOST_AUTO_TEST_CASE(roller_gap_in_its_four_regions) {
  const Obstacle o = roller();
  const double r = 0.001;
  // Values from the geometry (obstacle.hpp), exact up to round-off (1e-15 m).
  const auto gap = [&](const Vec3& p) { return obstacle_gap(o, p, r).gap; };
  BOOST_TEST(gap(Vec3(0.1, 0.01, 0.03)) == 0.03 - 0.02 - r, boost::test_tools::tolerance(1e-12));  // side
  BOOST_TEST(gap(Vec3(0.11, 0.05, 0.0)) == 0.05 - 0.02 - r, boost::test_tools::tolerance(1e-12));  // end face
  BOOST_TEST(gap(Vec3(0.1, -0.05, 0.05)) == std::hypot(0.03, 0.03) - r,
             boost::test_tools::tolerance(1e-12));                                             // rim
  BOOST_TEST(gap(Vec3(0.1, 0.015, 0.01)) == -0.005 - r, boost::test_tools::tolerance(1e-12));  // inside
  // d g / d p = nu and d nu / d p against central differences in each region (h = 1e-6: truncation
  // O(h^2 / d^2) ~ 1e-8 at distances >= 0.01 m, round-off 1e-16 / h = 1e-10).
  for (const Vec3& p : {Vec3(0.09, 0.01, 0.03), Vec3(0.11, 0.05, 0.003), Vec3(0.104, -0.05, 0.05),
                        Vec3(0.1, 0.012, 0.004), Vec3(0.125, 0.0, -0.01)}) {
    const ObstacleGap g = obstacle_gap(o, p, r);
    const double h = 1e-6;
    for (int c = 0; c < 3; ++c) {
      Vec3 dp = Vec3::Zero();
      dp[c] = h;
      const ObstacleGap gp = obstacle_gap(o, p + dp, r), gm = obstacle_gap(o, p - dp, r);
      BOOST_TEST(std::abs((gp.gap - gm.gap) / (2 * h) - g.normal[c]) < 1e-7, p.transpose()
                                                                                 << " d g / d p_" << c);
      BOOST_TEST(((gp.normal - gm.normal) / (2 * h) - g.normal_derivative.col(c)).norm() < 1e-6,
                 p.transpose() << " d nu / d p_" << c);
    }
  }
}

BOOST_AUTO_TEST_CASE(roller_contact_rows_jacobian_matches_finite_differences) {
  // The midpoint contact rows with three rollers that the cantilever along +x (0.3 m) passes beside their
  // side, end face and rim, at a perturbed state with positive multipliers (as test_contact_rods.cpp).
  const CollocationRod rod(test::steel_cantilever(0.3, Vec3(0, 0, -9.81), Vec3(0, 0, -0.01)),
                           test::contact_discretization(4, 6));
  Obstacle side = roller(), face = roller(), rim = roller();
  side.position = Vec3(0.05, 0, -0.03);
  face.position = Vec3(0.15, 0.04, 0.0);
  rim.position = Vec3(0.25, 0.035, -0.03);
  RodContactOptions options{{side, face, rim}, test::kRadius};
  Problem problem;
  const RodVariables vars = rod.add_to_problem(problem);
  const RodContactVariables contact = add_rod_contact(problem, rod, vars, options);
  VecX x = problem.initial_values();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < x.size(); ++i) x[i] += 1e-3 * unit(rng);
  for (int offset : contact.multiplier_offsets)
    for (int k = 0; k < 3; ++k) x[offset + k] = 0.5 + 0.4 * unit(rng);
  const JacobianCheckResult r = check_problem_jacobian(problem, x);
  BOOST_TEST(r.passed, r.to_string());
}

BOOST_AUTO_TEST_CASE(a_roller_is_its_cylinder_where_the_rod_lies_on_its_side) {
  // The cantilever wrapped on a drum by a tip load (test_contact_references.cpp: centerline radius
  // 10.001 m, P = 0.2 N) on a roller 0.1 m long around the rod's plane: the rod touches only the side, so
  // the discrete problem is the same as with the infinite cylinder, and so is its solution (to the
  // round-off of two solves, 1e-12 m).
  const double L = 0.2, rho = 10.001;
  const CollocationRod rod(test::steel_cantilever(L, Vec3::Zero(), Vec3(0, 0, -0.2)),
                           test::contact_discretization(4, 16));
  Obstacle drum = roller();
  drum.shape = ObstacleShape::Cylinder;
  drum.position = Vec3(0, 0, -rho);
  drum.radius = rho - test::kRadius;
  Obstacle piece = drum;
  piece.shape = ObstacleShape::Roller;
  piece.length = 0.1;
  RodContactOptions cylinder{{drum}, test::kRadius}, finite{{piece}, test::kRadius};
  const auto a = test::solve_rod(rod, &cylinder), b = test::solve_rod(rod, &finite);
  BOOST_TEST_REQUIRE(a->summary.converged());
  BOOST_TEST_REQUIRE(b->summary.converged());
  for (double s : {0.05, 0.1, 0.2})
    BOOST_TEST((rod.state_at(a->x, a->vars, s).position - rod.state_at(b->x, b->vars, s).position).norm() <
               1e-12);
  const auto ca = read_rod_contact(rod, a->vars, a->contact, a->x),
             cb = read_rod_contact(rod, b->vars, b->contact, b->x);
  BOOST_TEST((ca[0].force - cb[0].force).norm() < 1e-12);
  BOOST_TEST(cb[0].force.z() > 0.19);  // the drum carries the load P = 0.2 N (to a cell's share)
}

BOOST_AUTO_TEST_CASE(planar_rollers_model_fk_and_ik) {
  // models/planar_rollers.urdf: at the default inputs the pre-curved middle rod lies on the right roller;
  // moved to the left by IK it leaves it and is guided by the left one. Frictionless rollers push along
  // their radius: the right one to -x, the left one to +x. The IK target is met by the FK at the IK's
  // inputs to 1e-7 m (both systems solved to 1e-10, well conditioned; the bound of test_kinematics).
  auto model = std::make_shared<const RobotModel>(
      load_robot_model(std::string(PCR_MODEL_DIR) + "/planar_rollers.urdf"));
  ForwardKinematics fk(model);
  const RobotSolution home = fk.solve(model->default_input_values());
  BOOST_TEST_REQUIRE(home.summary.converged(), home.summary.message);
  BOOST_TEST_REQUIRE(home.contacts.size() == 2u);
  BOOST_TEST(home.contacts[0].obstacle == "right_roller");
  BOOST_TEST(!home.contacts[0].intervals.empty());
  BOOST_TEST(home.contacts[0].force.x() < 0.0);
  BOOST_TEST(home.contacts[1].intervals.empty());
  BOOST_TEST(!home.contact_gaps[0].penetrates(), home.summary.message);

  LinkTarget target;
  target.link = "platform";
  target.components = {{true, false, true, false, true, false}};
  InverseKinematics ik(model, {target});
  Pose goal;
  goal.position = Vec3(-0.018, 0, 0.283);
  const RobotSolution left = ik.solve({goal});
  BOOST_TEST_REQUIRE(left.summary.converged(), left.summary.message);
  BOOST_TEST(left.contacts[0].intervals.empty());
  BOOST_TEST_REQUIRE(!left.contacts[1].intervals.empty());
  BOOST_TEST(left.contacts[1].force.x() > 0.0);
  BOOST_TEST(!left.contact_gaps[0].penetrates(), left.summary.message);
  const RobotSolution again = fk.solve(left.inputs);
  BOOST_TEST_REQUIRE(again.summary.converged(), again.summary.message);
  BOOST_TEST((again.platforms[0].position - goal.position).norm() < 1e-7);
}
