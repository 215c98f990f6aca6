// Obstacles on links that actuated joints move (docs/contact.md, "Obstacles on moving links"): the
// obstacle follows the link at the inputs of each solve, the contact rows take the joint values as
// variables (FD-checked), and the rod's shape is that of the same obstacle fixed to the world where the
// link puts it. Obstacles on passive links or on two moving links are rejected with a clear message.
#define BOOST_TEST_MODULE moving_obstacles
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/solve/jacobian_check.hpp"
#include "robot_fixtures.hpp"

using namespace pcr;

namespace {

// A horizontal steel cantilever (0.5 m, radius 1 mm, along +x from the origin) under gravity and a
// 0.1 N tip load (free sag about 0.2 m), meshed finely enough for the contact to be resolved, with a
// contact rod element naming `obstacles`. `extra` holds links, joints and obstacles.
std::string cantilever_xml(const std::string& extra, const std::string& obstacles) {
  return R"(<?xml version="1.0"?>
<robot name="moving_floor">
  <link name="base"/>
  <pcr_gravity xyz="0 0 -9.81"/>
)" + extra +
         R"(
  <pcr_rod name="beam">
    <start link="base" xyz="0 0 0" rpy="0 1.570796326795 0" coupling="clamped"/>
    <end coupling="free" force="0 0 -0.1" moment="0 0 0"/>
    <material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>
    <section type="circle" radius="0.001"/>
    <length value="0.5"/>
    <discretization degree="4" elements="24"/>
    <contact obstacles=")" +
         obstacles + R"("/>
  </pcr_rod>
</robot>
)";
}

// A link `lifter` on an actuated prismatic joint along z (default -0.3 m: far below the rod) carrying a
// floor (normal +z through its origin).
const std::string kPrismaticFloor = R"(
  <link name="lifter"/>
  <joint name="lift" type="prismatic">
    <parent link="base"/><child link="lifter"/>
    <origin xyz="0 0 0" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-0.4" upper="0.0" effort="10" velocity="1"/>
  </joint>
  <pcr_joint name="lift" default="-0.3"/>
  <pcr_obstacle name="floor" type="half_space" link="lifter" xyz="0 0 0" normal="0 0 1"/>
)";

// A link `tilter` on an actuated revolute joint about y through (0.5, 0, -0.03) (default 0), carrying a
// floor through the joint's origin with normal +z: turned by theta, its normal is (sin theta, 0, cos theta)
// (the plane z = -0.03 - tan(theta) (x - 0.5), below the clamp for |theta| <= 0.05).
const std::string kRevoluteFloor = R"(
  <link name="tilter"/>
  <joint name="tilt" type="revolute">
    <parent link="base"/><child link="tilter"/>
    <origin xyz="0.5 0 -0.03" rpy="0 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-0.5" upper="0.5" effort="10" velocity="1"/>
  </joint>
  <pcr_joint name="tilt" default="0"/>
  <pcr_obstacle name="floor" type="half_space" link="tilter" xyz="0 0 0" normal="0 0 1"/>
)";

std::shared_ptr<const RobotModel> model_of(const std::string& xml) {
  return std::make_shared<const RobotModel>(parse_robot_model(xml, "moving_floor.urdf"));
}

std::string vector_text(const Vec3& v) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "%.17g %.17g %.17g", v[0], v[1], v[2]);
  return buffer;
}

// The same cantilever with the floor fixed to the world through `point` with unit normal `normal`.
RobotSolution world_floor_solution(const Vec3& point, const Vec3& normal) {
  const auto model =
      model_of(cantilever_xml(R"(<pcr_obstacle name="floor" type="half_space" xyz=")" + vector_text(point) +
                                  R"(" normal=")" + vector_text(normal) + R"("/>)",
                              "floor"));
  ForwardKinematics fk(model);
  return fk.solve(VecX(0));
}

// Largest distance between the centerlines of two solutions of the same rod [m].
double centerline_distance(const RobotSolution& a, const RobotSolution& b) {
  BOOST_TEST_REQUIRE(a.rods[0].centerline.size() == b.rods[0].centerline.size());
  double d = 0.0;
  for (size_t i = 0; i < a.rods[0].centerline.size(); ++i)
    d = std::max(d, (a.rods[0].centerline[i] - b.rods[0].centerline[i]).norm());
  return d;
}

}  // namespace

// Reference: the floor fixed to the world at the pose the link reaches. The two discrete systems have the
// same solution (the contact rows differ only by the rotation of the force rows), so the shapes agree to
// the solver's tolerance: 1e-9 m (Newton stops at |r| ~ 1e-10 in scaled rows on a 0.5 m rod).
BOOST_AUTO_TEST_CASE(floor_on_a_prismatic_joint_gives_the_shape_of_the_world_fixed_floor) {
  const auto model = model_of(cantilever_xml(kPrismaticFloor, "floor"));
  ForwardKinematics fk(model);
  for (double lift : {-0.01, -0.025}) {
    const RobotSolution moving = fk.solve(VecX::Constant(1, lift));
    BOOST_TEST_REQUIRE((moving.summary.status == SolveStatus::Converged), moving.summary.message);
    const RobotSolution fixed = world_floor_solution(Vec3(0, 0, lift), Vec3::UnitZ());
    BOOST_TEST_REQUIRE((fixed.summary.status == SolveStatus::Converged));
    BOOST_TEST(centerline_distance(moving, fixed) < 1e-9, "lift " << lift);
    // The rod lies on the floor (the free sag is 39 mm): the same contact force as on the fixed floor
    // (1e-8 N of the 0.22 N of weight and load), and the gap read at the moved floor (1e-9 m as the shape).
    BOOST_TEST_REQUIRE(moving.contacts.size() == 1u);
    BOOST_TEST(moving.contacts[0].force.z() > 0.01);
    BOOST_TEST((moving.contacts[0].force - fixed.contacts[0].force).norm() < 1e-8);
    BOOST_TEST(std::abs(moving.contacts[0].min_gap - fixed.contacts[0].min_gap) < 1e-9);
  }
}

BOOST_AUTO_TEST_CASE(floor_on_a_revolute_joint_gives_the_shape_of_the_world_fixed_floor) {
  const auto model = model_of(cantilever_xml(kRevoluteFloor, "floor"));
  ForwardKinematics fk(model);
  for (double theta : {0.04, -0.05}) {
    const RobotSolution moving = fk.solve(VecX::Constant(1, theta));
    BOOST_TEST_REQUIRE((moving.summary.status == SolveStatus::Converged), moving.summary.message);
    const RobotSolution fixed =
        world_floor_solution(Vec3(0.5, 0, -0.03), Vec3(std::sin(theta), 0, std::cos(theta)));
    BOOST_TEST_REQUIRE((fixed.summary.status == SolveStatus::Converged));
    BOOST_TEST(centerline_distance(moving, fixed) < 1e-9, "theta " << theta);
    BOOST_TEST(moving.contacts[0].force.norm() > 0.01);
    BOOST_TEST((moving.contacts[0].force - fixed.contacts[0].force).norm() < 1e-8);
  }
}

// Every Jacobian of the assembly, the joint value columns of the wrapped contact rows included, against
// central differences (jacobian_check.hpp defaults: 1e-6 relative step and tolerances), at the solved
// state with active contact and at a perturbed state with random multipliers, for both joints.
BOOST_AUTO_TEST_CASE(contact_rows_on_a_moving_link_match_finite_differences) {
  for (const std::string& floor : {kPrismaticFloor, kRevoluteFloor}) {
    const auto model = model_of(cantilever_xml(floor, "floor"));
    ForwardKinematics fk(model);
    const double input = floor == kPrismaticFloor ? -0.02 : 0.03;
    BOOST_TEST_REQUIRE((fk.solve(VecX::Constant(1, input)).summary.status == SolveStatus::Converged));
    const Problem& problem = fk.assembly().problem();
    VecX x = fk.state();
    JacobianCheckResult r = check_problem_jacobian(problem, x);
    BOOST_TEST(r.passed, r.to_string());
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int i = 0; i < x.size(); ++i) x[i] += 1e-4 * unit(rng);
    const RodContactVariables* contact = fk.assembly().rod_contact(0);
    BOOST_TEST_REQUIRE(contact != nullptr);
    for (int offset : contact->multiplier_offsets) x[offset] = 0.5 + 0.4 * unit(rng);
    r = check_problem_jacobian(problem, x);
    BOOST_TEST(r.passed, r.to_string());
  }
}

// (An obstacle on a platform is rejected: tests/contact, obstacles_on_links_fixed_to_the_world.)
BOOST_AUTO_TEST_CASE(obstacles_on_passive_links_or_on_two_moving_links_are_rejected) {
  auto message = [](const std::string& xml) {
    try {
      ForwardKinematics fk(model_of(xml));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // Two floors on two different moving links.
  const std::string second = R"(
  <link name="lifter2"/>
  <joint name="lift2" type="prismatic">
    <parent link="base"/><child link="lifter2"/>
    <origin xyz="0 0 0" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-0.4" upper="0.0" effort="10" velocity="1"/>
  </joint>
  <pcr_joint name="lift2" default="-0.3"/>
  <pcr_obstacle name="floor2" type="half_space" link="lifter2" xyz="0 0 0" normal="0 0 1"/>
)";
  const std::string two = message(cantilever_xml(kPrismaticFloor + second, "floor floor2"));
  BOOST_TEST(two.find("one moving link only") != std::string::npos, two);
  // A world-fixed obstacle beside one on a moving link.
  const std::string mixed = message(cantilever_xml(
      kPrismaticFloor + R"(<pcr_obstacle name="wall" type="half_space" xyz="0 0 -0.3" normal="0 0 1"/>)",
      "floor wall"));
  BOOST_TEST(mixed.find("'wall' does not move with link 'lifter'") != std::string::npos, mixed);
  // A passive joint moves the floor (a link mass under gravity makes the passive joint valid).
  std::string passive = kPrismaticFloor;
  passive.replace(passive.find(R"(default="-0.3")"), 14, R"(passive="true" stiffness="100" rest="-0.3")");
  passive.replace(passive.find(R"(<link name="lifter"/>)"), 21,
                  R"(<link name="lifter"><inertial><origin xyz="0 0 0"/><mass value="0.1"/>)"
                  R"(<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>)");
  const std::string p = message(cantilever_xml(passive, "floor"));
  BOOST_TEST(p.find("the link moves (a passive joint moves it)") != std::string::npos, p);
}

namespace {

// models/planar_post.urdf with its post carried by the platform: the post's ends given in the platform
// frame (the platform starts at (0, 0, 0.3), unrotated, so the declared world post is where it starts),
// and `extra` added before the first rod (loads, obstacles).
std::string planar_post_xml(const std::string& post, const std::string& extra = "") {
  std::string xml = test::model_text("planar_post");
  const std::string declared =
      R"(<pcr_obstacle name="post" type="capsule" xyz="-0.0147 -0.02 0.1436" end="-0.0147 0.02 0.1436" radius="0.02"/>)";
  BOOST_TEST_REQUIRE(xml.find(declared) != std::string::npos);
  xml.replace(xml.find(declared), declared.size(), post + extra);
  return xml;
}

const std::string kPostOnPlatform =
    R"(<pcr_obstacle name="post" type="capsule" link="platform" xyz="-0.0147 -0.02 -0.1564" end="-0.0147 0.02 -0.1564" radius="0.02"/>)";

}  // namespace

// A post carried by the platform: the rod's contact force acts back on the platform. Reference: the same
// robot with the post fixed to the world where the platform carried it and the reaction applied to the
// platform as a dead load, a problem of world-fixed contact and loads only. The reaction is -F (F the
// rod's contact resultant) through the post's axis point in the robot's plane: every cell's force is
// normal to the post through its axis, and the planar robot lies in y = 0, so the resultant has no moment
// about (-0.0147, 0, -0.1564) in the platform frame. Both solves meet to the solver's tolerance: 1e-9 m
// (poses, centerlines) and 1e-8 N (forces of ~0.15 N).
BOOST_AUTO_TEST_CASE(post_on_the_platform_pushes_the_platform_back) {
  const auto model = model_of(planar_post_xml(kPostOnPlatform));
  ForwardKinematics fk(model);
  const RobotSolution a = fk.solve(model->default_input_values());
  BOOST_TEST_REQUIRE((a.summary.status == SolveStatus::Converged), a.summary.message);
  BOOST_TEST_REQUIRE(a.contacts.size() == 1u);
  const Vec3 F = a.contacts[0].force;
  BOOST_TEST(F.norm() > 0.05);
  // The platform's force balance from the reported values: its weight, the rods' tip forces n(L) (the
  // force the platform exerts on each rod is n(L)) and the contact's reaction -F (1e-9 N: the solver's
  // residual on forces of ~0.5 N).
  const Vec3 weight = model->platforms()[0].mass * Vec3(0, 0, -9.81);
  Vec3 tips = Vec3::Zero();
  for (const RodResult& rod : a.rods) tips += rod.tip_force;
  BOOST_TEST((weight - tips - F).norm() < 1e-9, (weight - tips - F).transpose());

  const Pose& platform = a.platforms[0];
  const Vec3 x0 = platform.transform_point(Vec3(-0.0147, -0.02, -0.1564));
  const Vec3 x1 = platform.transform_point(Vec3(-0.0147, 0.02, -0.1564));
  const std::string world_post = R"(<pcr_obstacle name="post" type="capsule" xyz=")" + vector_text(x0) +
                                 R"(" end=")" + vector_text(x1) + R"(" radius="0.02"/>)";
  const std::string reaction = R"(<pcr_load link="platform" xyz="-0.0147 0 -0.1564" force=")" +
                               vector_text(-F) + R"(" torque="0 0 0"/>)";
  const auto reference_model = model_of(planar_post_xml(world_post, reaction));
  ForwardKinematics reference(reference_model);
  const RobotSolution b = reference.solve(reference_model->default_input_values());
  BOOST_TEST_REQUIRE((b.summary.status == SolveStatus::Converged), b.summary.message);
  BOOST_TEST((a.platforms[0].position - b.platforms[0].position).norm() < 1e-9);
  BOOST_TEST(std::abs(std::abs(a.platforms[0].orientation.dot(b.platforms[0].orientation)) - 1.0) < 1e-12);
  for (size_t r = 0; r < a.rods.size(); ++r)
    for (size_t i = 0; i < a.rods[r].centerline.size(); ++i)
      BOOST_TEST((a.rods[r].centerline[i] - b.rods[r].centerline[i]).norm() < 1e-9);
  BOOST_TEST((b.contacts[0].force - F).norm() < 1e-8);
}

// The platform balance with the contact reaction and the wrapped contact rows on the platform's pose
// against central differences (jacobian_check.hpp defaults), at the solution and at a perturbed state.
BOOST_AUTO_TEST_CASE(platform_contact_rows_match_finite_differences) {
  const auto model = model_of(planar_post_xml(kPostOnPlatform));
  ForwardKinematics fk(model);
  BOOST_TEST_REQUIRE((fk.solve(model->default_input_values()).summary.status == SolveStatus::Converged));
  const Problem& problem = fk.assembly().problem();
  VecX x = fk.state();
  JacobianCheckResult r = check_problem_jacobian(problem, x);
  BOOST_TEST(r.passed, r.to_string());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < x.size(); ++i) x[i] += 1e-4 * unit(rng);
  const RodContactVariables* contact = fk.assembly().rod_contact(1);
  BOOST_TEST_REQUIRE(contact != nullptr);
  for (int offset : contact->multiplier_offsets) x[offset] = 0.5 + 0.4 * unit(rng);
  r = check_problem_jacobian(problem, x);
  BOOST_TEST(r.passed, r.to_string());
}

BOOST_AUTO_TEST_CASE(concentrated_contact_on_a_platform_is_rejected) {
  std::string post = kPostOnPlatform;
  post.replace(post.find(R"(radius="0.02"/>)"), 15, R"(radius="0.02" contact="point"/>)");
  try {
    ForwardKinematics fk(model_of(planar_post_xml(post)));
    BOOST_FAIL("concentrated contact with an obstacle on a platform was accepted");
  } catch (const InputError& e) {
    BOOST_TEST(
        std::string(e.what()).find("obstacle 'post' on link 'platform': the link moves") != std::string::npos,
        e.what());
  }
}

// IK with the post on the platform: the platform pose reached by FK at other inputs gives those inputs
// back (1e-7 m: the IK's tolerance on the targets, as for the world-fixed post in tests/contact) and the
// same contact force (relative 1e-6).
BOOST_AUTO_TEST_CASE(ik_with_the_post_on_the_platform_recovers_the_inputs) {
  const auto model = model_of(planar_post_xml(kPostOnPlatform));
  ForwardKinematics fk(model);
  VecX u = model->default_input_values();
  u += Vec3(0.001, 0.002, 0.001);
  const RobotSolution moved = fk.solve(u);
  BOOST_TEST_REQUIRE((moved.summary.status == SolveStatus::Converged), moved.summary.message);
  BOOST_TEST_REQUIRE(!moved.contacts[0].intervals.empty());
  LinkTarget target;
  target.link = "platform";
  target.components = {{true, false, true, false, true, false}};
  InverseKinematics ik(model, {target});
  const RobotSolution back = ik.solve({moved.platforms[0]});
  BOOST_TEST_REQUIRE(back.summary.converged(), back.summary.message);
  for (int i = 0; i < 3; ++i) BOOST_TEST(std::abs(back.inputs[i] - u[i]) < 1e-7, "input " << i);
  BOOST_TEST((back.contacts[0].force - moved.contacts[0].force).norm() <
             1e-6 * (1.0 + moved.contacts[0].force.norm()));
}
