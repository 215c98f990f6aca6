// Robot model and URDF loader: every model in models/ against independently computed values, forward
// kinematics against hand-composed transforms, the documented example. One malformed-model case per
// validation rule: test_model_rejections.cpp (same executable).
#define BOOST_TEST_MODULE robot_model
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "model_xml.hpp"
#include "pcr/core/error.hpp"
#include "pcr/math/dense_decompositions.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/platform_hold_check.hpp"
#include "pcr/robots/urdf_loader.hpp"

using namespace pcr;
using test::robot;
using test::RodXml;

namespace {

std::string model(const std::string& file) {
  return std::string(PCR_MODEL_DIR) + "/" + file;
}

// Values written with 12 decimals in the model files: rounding error <= 5e-13 per coordinate.
constexpr double kWritten = 1e-11;
// Pure double arithmetic on O(1) numbers (compositions of a few rotations).
constexpr double kRoundoff = 1e-12;

// R5 hole pattern (docs/benchmarks.md, Scenes), computed here independently of the model file.
Vec3 r5_point(int i, bool platform) {
  const double alpha1 = 100.0, alpha2 = 120.0 - alpha1, R_hp = 0.087;
  const double a = platform ? alpha1 : alpha2, b = platform ? alpha2 : alpha1;
  const double theta_deg = (-a + ((i + 1) - (i + 1) % 2) * a + (i - i % 2) * b) / 2.0;
  const double theta = theta_deg * M_PI / 180.0;
  return Vec3(R_hp * std::cos(theta), R_hp * std::sin(theta), 0.0);
}

void check_pose(const Pose& actual, const Vec3& position, const Mat3& rotation, double tolerance) {
  BOOST_TEST((actual.position - position).norm() <= tolerance,
             "position " << actual.position.transpose() << " expected " << position.transpose());
  BOOST_TEST((actual.rotation() - rotation).norm() <= tolerance, "rotation\n"
                                                                     << actual.rotation() << "\nexpected\n"
                                                                     << rotation);
}

}  // namespace

// ------------------------------------------------------------------------------------------------ Pose
BOOST_AUTO_TEST_CASE(pose_compose_inverse_rpy) {
  const Pose a = Pose::from_xyz_rpy(Vec3(0.1, -0.2, 0.3), Vec3(0.3, -0.4, 1.2));
  const Pose b = Pose::from_xyz_rpy(Vec3(-1.0, 0.5, 2.0), Vec3(-2.0, 0.7, -0.1));
  // (a * b): R = Ra Rb, p = pa + Ra pb.
  const Mat3 Ra = rotation_from_rpy(0.3, -0.4, 1.2), Rb = rotation_from_rpy(-2.0, 0.7, -0.1);
  check_pose(a * b, Vec3(0.1, -0.2, 0.3) + Ra * Vec3(-1.0, 0.5, 2.0), Ra * Rb, kRoundoff);
  check_pose(a * a.inverse(), Vec3::Zero(), Mat3::Identity(), kRoundoff);
  check_pose(a.inverse() * a, Vec3::Zero(), Mat3::Identity(), kRoundoff);
  BOOST_TEST((a.transform_point(Vec3(1, 2, 3)) - (Vec3(0.1, -0.2, 0.3) + Ra * Vec3(1, 2, 3))).norm() <
             kRoundoff);
  // rpy inverts from_xyz_rpy for pitch inside (-pi/2, pi/2); at pitch = pi/2 the rotation is still
  // reproduced.
  BOOST_TEST((a.rpy() - Vec3(0.3, -0.4, 1.2)).norm() < kRoundoff);
  BOOST_TEST((b.rpy() - Vec3(-2.0, 0.7, -0.1)).norm() < kRoundoff);
  const Pose lock = Pose::from_xyz_rpy(Vec3::Zero(), Vec3(0.4, M_PI / 2, 0.1));
  const Vec3 rpy = lock.rpy();
  // Near gimbal lock asin loses half the digits: 1e-7 ~ sqrt(machine epsilon).
  BOOST_TEST((rotation_from_rpy(rpy[0], rpy[1], rpy[2]) - lock.rotation()).norm() < 1e-7);
}

// ------------------------------------------------------------------------------------------------ models
BOOST_AUTO_TEST_CASE(stewart_gough_r5a) {
  const RobotModel m = load_robot_model(model("stewart_gough.urdf"));
  BOOST_TEST(m.rods().size() == 6u);
  BOOST_TEST(m.platforms().size() == 1u);
  BOOST_TEST(m.inputs().size() == 6u);
  BOOST_TEST(m.links()[m.base_link()].name == "base");
  BOOST_TEST((m.gravity() - Vec3(0, 0, -9.81)).norm() == 0.0);
  const Platform& platform = m.platforms()[0];
  BOOST_TEST(platform.name == "platform");
  BOOST_TEST(platform.mass == 0.1);
  BOOST_TEST(platform.center_of_mass.norm() == 0.0);
  check_pose(platform.initial_pose, Vec3(0, 0, 0.4), Mat3::Identity(), kRoundoff);
  const double r = 0.001, E = 200e9, G = 80e9;
  const double A = M_PI * r * r, I = M_PI * std::pow(r, 4) / 4.0;
  for (int i = 0; i < 6; ++i) {
    const RodElement& rod = m.rods()[i];
    BOOST_TEST(rod.name == "leg" + std::to_string(i));
    BOOST_TEST(m.rod_index(rod.name) == i);
    BOOST_TEST(m.links()[rod.start.link].name == "base");
    BOOST_TEST(m.links()[rod.end.link].name == "platform");
    BOOST_TEST((rod.start.coupling == RodEndKind::Clamped && rod.end.coupling == RodEndKind::Collar));
    check_pose(rod.start.frame, r5_point(i, false), Mat3::Identity(), kWritten);
    check_pose(rod.end.frame, r5_point(i, true), Mat3::Identity(), kWritten);
    // World frames at the initial configuration: base holes at z = 0, platform points at z = 0.4.
    BOOST_TEST((rod.rod.base.position - r5_point(i, false)).norm() < kWritten);
    BOOST_TEST((rod.rod.tip.position - (r5_point(i, true) + Vec3(0, 0, 0.4))).norm() < kWritten);
    // Stiffness of a solid circle (1e-12 relative: a few roundings in products of doubles).
    BOOST_TEST(std::abs(rod.rod.shear_extension_stiffness[2] / (E * A) - 1.0) < kRoundoff);
    BOOST_TEST(std::abs(rod.rod.shear_extension_stiffness[0] / (G * A) - 1.0) < kRoundoff);
    BOOST_TEST(std::abs(rod.rod.bending_torsion_stiffness[0] / (E * I) - 1.0) < kRoundoff);
    BOOST_TEST(std::abs(rod.rod.bending_torsion_stiffness[2] / (G * 2.0 * I) - 1.0) < kRoundoff);
    BOOST_TEST(std::abs(rod.rod.mass_per_length / (8000.0 * A) - 1.0) < kRoundoff);
    BOOST_TEST((rod.rod.loads.gravity - Vec3(0, 0, -9.81)).norm() == 0.0);
    BOOST_TEST(rod.rod.length == 0.45);
    const ActuationInput& input = m.inputs()[m.input_index(rod.name)];
    BOOST_TEST((input.kind == ActuationInput::Kind::RodLength && input.index == i));
    BOOST_TEST(input.lower == 0.2);
    BOOST_TEST(input.upper == 0.8);
    BOOST_TEST(input.default_value == 0.45);
  }
  BOOST_TEST(m.platform_unknown_count() == 7);
  BOOST_TEST(m.platform_equation_count() == 7);
  // Rigid-rod constraint matrix: 6 collars x 5 constraints, rank 6 (the platform is held).
  const MatX C = coupling_constraint_matrix(m, m.default_joint_values(), m.initial_platform_poses());
  BOOST_TEST(C.rows() == 30);
  BOOST_TEST(C.cols() == 6);
  // Smallest singular value ~ lever arm 0.087 m times O(1): far from the 1e-9 rank threshold.
  BOOST_TEST(singular_values(C)[5] > 1e-3);
}

BOOST_AUTO_TEST_CASE(stewart_gough_r5b) {
  const RobotModel m = load_robot_model(model("stewart_gough_teleop.urdf"));
  BOOST_TEST(m.rods().size() == 6u);
  BOOST_TEST(m.gravity().norm() == 0.0);
  BOOST_TEST(m.platforms()[0].mass == 0.0);
  const Vec3 target(0, 0.02, 0.48);
  check_pose(m.platforms()[0].initial_pose, target, Mat3::Identity(), kRoundoff);
  const double r = 0.00065, E = 207e9, G = E / (2.0 * (1.0 + 0.305));
  const double A = M_PI * r * r;
  for (int i = 0; i < 6; ++i) {
    const RodElement& rod = m.rods()[i];
    check_pose(rod.start.frame, r5_point(i, false), Mat3::Identity(), kWritten);
    check_pose(rod.end.frame, r5_point(i, true), Mat3::Identity(), kWritten);
    BOOST_TEST(std::abs(rod.rod.shear_extension_stiffness[2] / (E * A) - 1.0) < kRoundoff);
    BOOST_TEST(std::abs(rod.rod.shear_extension_stiffness[0] / (G * A) - 1.0) < kRoundoff);
    // A rod with vertical tangents at both ends is longer than the chord between its ends, by the
    // S-curve excess ~ 0.6 (d / h)^2 < 1 % for offsets d < 0.07 m over h = 0.48 m.
    const double chord = (target + r5_point(i, true) - r5_point(i, false)).norm();
    BOOST_TEST(rod.length_default > chord);
    BOOST_TEST(rod.length_default < 1.01 * chord);
  }
}

BOOST_AUTO_TEST_CASE(planar_three_rod) {
  const RobotModel m = load_robot_model(model("planar_three_rod.urdf"));
  BOOST_TEST(m.rods().size() == 3u);
  BOOST_TEST(m.platforms().size() == 1u);
  BOOST_TEST(m.inputs().size() == 3u);
  for (const RodElement& rod : m.rods()) {
    BOOST_TEST((rod.start.coupling == RodEndKind::Clamped && rod.end.coupling == RodEndKind::Spherical));
    // Straight and stress-free at the defaults: tip = base + L d3(base), same frame at both ends, in y = 0.
    const Vec3 d3 = rotation_matrix(rod.rod.base.orientation).col(2);
    BOOST_TEST((rod.rod.tip.position - rod.rod.base.position - rod.rod.length * d3).norm() < kWritten);
    BOOST_TEST((rotation_matrix(rod.rod.tip.orientation) - rotation_matrix(rod.rod.base.orientation)).norm() <
               kRoundoff);
    BOOST_TEST(std::abs(rod.rod.base.position.y()) + std::abs(rod.rod.tip.position.y()) + std::abs(d3.y()) ==
               0.0);
  }
  // The three platform attachment points are not collinear (a triangle).
  const Vec3 a = m.rods()[0].end.frame.position, b = m.rods()[1].end.frame.position,
             c = m.rods()[2].end.frame.position;
  BOOST_TEST((b - a).cross(c - a).norm() > 1e-4);
}

BOOST_AUTO_TEST_CASE(two_stage) {
  const RobotModel m = load_robot_model(model("two_stage.urdf"));
  BOOST_TEST(m.rods().size() == 6u);
  BOOST_TEST(m.platforms().size() == 2u);
  BOOST_TEST(m.inputs().size() == 6u);
  const int p1 = m.platform_index("platform1"), p2 = m.platform_index("platform2");
  // platform2's floating origin is relative to platform1 (0.25 + 0.25).
  check_pose(m.platforms()[p1].initial_pose, Vec3(0, 0, 0.25), Mat3::Identity(), kRoundoff);
  check_pose(m.platforms()[p2].initial_pose, Vec3(0, 0, 0.5), Mat3::Identity(), kRoundoff);
  for (const RodElement& rod : m.rods()) {
    const bool lower = rod.name.compare(0, 5, "lower") == 0;
    BOOST_TEST(m.carrying_platform(rod.start.link) == (lower ? -1 : p1));
    BOOST_TEST(m.carrying_platform(rod.end.link) == (lower ? p1 : p2));
    // Straight and vertical at the defaults.
    BOOST_TEST((rod.rod.tip.position - rod.rod.base.position - Vec3(0, 0, 0.25)).norm() < kWritten);
  }
  BOOST_TEST(m.platform_unknown_count() == 14);
}

BOOST_AUTO_TEST_CASE(cantilever) {
  const RobotModel m = load_robot_model(model("cantilever.urdf"));
  BOOST_TEST(m.rods().size() == 1u);
  BOOST_TEST(m.platforms().empty());
  BOOST_TEST(m.inputs().empty());
  const RodElement& rod = m.rods()[0];
  BOOST_TEST(rod.end.link == -1);
  BOOST_TEST((rod.rod.tip.kind == RodEndKind::Free && rod.rod.base.kind == RodEndKind::Clamped));
  BOOST_TEST((rod.rod.tip.force - Vec3(0, 0, -0.1)).norm() == 0.0);
  BOOST_TEST(!rod.length_actuated);
  BOOST_TEST(rod.rod.length == 0.5);
  // Tangent along +x: pitch written as pi/2 to 12 decimals.
  BOOST_TEST((rotation_matrix(rod.rod.base.orientation).col(2) - Vec3::UnitX()).norm() < kWritten);
  BOOST_TEST((rod.formulation == RodFormulationHint::Mixed && rod.degree == 4 && rod.elements == 8));
}

BOOST_AUTO_TEST_CASE(slider_actuated) {
  const RobotModel m = load_robot_model(model("slider_actuated.urdf"));
  BOOST_TEST(m.rods().size() == 3u);
  BOOST_TEST(m.inputs().size() == 3u);
  BOOST_TEST(m.joint_value_count() == 3);
  for (int i = 0; i < 3; ++i) {
    const std::string name = "slider" + std::to_string(i);
    const ActuationInput& input = m.inputs()[m.input_index(name)];
    BOOST_TEST((input.kind == ActuationInput::Kind::JointValue && m.joints()[input.index].name == name));
    BOOST_TEST(input.lower == -0.05);
    BOOST_TEST(input.upper == 0.15);
    BOOST_TEST(input.default_value == 0.02);
    const RodElement& rod = m.rods()[i];
    BOOST_TEST(!rod.length_actuated);
    // Rod base on the slider: (0.1 cos a, 0.1 sin a, 0.05 + 0.02), straight up to the platform at 0.42.
    const double angle = (90.0 + 120.0 * i) * M_PI / 180.0;
    BOOST_TEST((rod.rod.base.position - Vec3(0.1 * std::cos(angle), 0.1 * std::sin(angle), 0.07)).norm() <
               kWritten);
    BOOST_TEST((rod.rod.tip.position - rod.rod.base.position - Vec3(0, 0, 0.35)).norm() < kWritten);
  }
  BOOST_TEST(m.loads().size() == 1u);
  BOOST_TEST(m.carrying_platform(m.loads()[0].link) == 0);
  BOOST_TEST((m.loads()[0].force - Vec3(0, 0, -0.2)).norm() == 0.0);
}

// ------------------------------------------------------------------------------------------------ FK
BOOST_AUTO_TEST_CASE(forward_kinematics_by_hand) {
  const std::string tree = R"(<link name="base"/><link name="arm"/><link name="slide"/><link name="tip"/>
<link name="platform"/><link name="tool"/>
<joint name="turn" type="revolute"><parent link="base"/><child link="arm"/>
  <origin xyz="1 0 0" rpy="0 0 1.5707963267948966"/><axis xyz="0 0 2"/>
  <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
<joint name="push" type="prismatic"><parent link="arm"/><child link="slide"/>
  <origin xyz="0 1 0" rpy="0 0 0"/><axis xyz="1 0 0"/><limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>
<joint name="weld" type="fixed"><parent link="slide"/><child link="tip"/>
  <origin xyz="0 0 1" rpy="1.5707963267948966 0 0"/></joint>
<joint name="float" type="floating"><parent link="base"/><child link="platform"/>
  <origin xyz="0 0 0.3" rpy="0 0 0"/></joint>
<joint name="mount" type="fixed"><parent link="platform"/><child link="tool"/>
  <origin xyz="0 0 0.1" rpy="0 0 3.141592653589793"/></joint><link name="wheel"/>
<joint name="spin" type="continuous"><parent link="tip"/><child link="wheel"/>
  <origin xyz="0 0 0.5" rpy="0 0 0"/><axis xyz="0 1 0"/></joint>
)";
  const RobotModel m = parse_robot_model(robot(RodXml().str(), tree));
  BOOST_TEST(m.joint_value_count() == 3);
  BOOST_TEST(m.joints()[m.joint_index("turn")].value_index == 0);
  BOOST_TEST(m.joints()[m.joint_index("push")].value_index == 1);
  BOOST_TEST(m.joints()[m.joint_index("spin")].value_index == 2);
  BOOST_TEST(m.inputs().size() == 3u);  // the rod has a fixed length; the three moving joints are inputs
  const ActuationInput& spin = m.inputs()[m.input_index("spin")];
  BOOST_TEST((std::isinf(spin.lower) && spin.lower < 0 && std::isinf(spin.upper) && spin.upper > 0));
  const double theta = 0.3, d = 0.2, phi = -2.5;
  VecX q(3);
  q << theta, d, phi;
  const Pose platform = Pose::from_xyz_rpy(Vec3(0.5, -0.2, 0.7), Vec3(0.1, 0.2, 0.3));
  const std::vector<Pose> platforms{platform};
  // arm: Trans(1,0,0) Rz(pi/2) Rz(theta) (the axis is normalised).
  const double alpha = M_PI / 2 + theta;
  check_pose(m.link_pose(m.link_index("arm"), q, platforms), Vec3(1, 0, 0), rotation_z(alpha), kRoundoff);
  // slide: arm * Trans(0,1,0) * Trans(d,0,0) -> (1,0,0) + Rz(alpha) (d, 1, 0).
  const Vec3 p_slide(1.0 + d * std::cos(alpha) - std::sin(alpha), d * std::sin(alpha) + std::cos(alpha), 0.0);
  check_pose(m.link_pose(m.link_index("slide"), q, platforms), p_slide, rotation_z(alpha), kRoundoff);
  // tip: slide * Trans(0,0,1) Rx(pi/2).
  check_pose(m.link_pose(m.link_index("tip"), q, platforms), p_slide + Vec3(0, 0, 1),
             rotation_z(alpha) * rotation_x(M_PI / 2), kRoundoff);
  // wheel: tip * Trans(0,0,0.5) * Ry(phi).
  const Mat3 R_tip = rotation_z(alpha) * rotation_x(M_PI / 2);
  check_pose(m.link_pose(m.link_index("wheel"), q, platforms),
             p_slide + Vec3(0, 0, 1) + R_tip * Vec3(0, 0, 0.5), R_tip * rotation_y(phi), kRoundoff);
  // tool on the platform: P * Trans(0,0,0.1) Rz(pi); the platform pose is the given world pose.
  const Mat3 Rp = rotation_from_rpy(0.1, 0.2, 0.3);
  check_pose(m.link_pose(m.link_index("platform"), q, platforms), platform.position, Rp, kRoundoff);
  check_pose(m.link_pose(m.link_index("tool"), q, platforms), platform.position + Rp * Vec3(0, 0, 0.1),
             Rp * rotation_z(M_PI), kRoundoff);
  BOOST_TEST(m.carrying_platform(m.link_index("tool")) == 0);
  BOOST_TEST(m.carrying_platform(m.link_index("tip")) == -1);
  check_pose(m.link_pose(m.base_link(), q, platforms), Vec3::Zero(), Mat3::Identity(), 0.0);
  // Defaults: 0 lies inside both limits.
  BOOST_TEST(m.default_joint_values().norm() == 0.0);
  // Size checks.
  BOOST_CHECK_THROW(m.link_pose(0, VecX::Zero(2), platforms), InputError);
  BOOST_CHECK_THROW(m.link_pose(0, q, {}), InputError);
  BOOST_CHECK_THROW(m.link_pose(17, q, platforms), InputError);
}

BOOST_AUTO_TEST_CASE(lookups_throw_for_unknown_names) {
  const RobotModel m = load_robot_model(model("stewart_gough.urdf"));
  BOOST_TEST(m.link_index("platform") == m.platforms()[0].link);
  BOOST_TEST(m.joint_index("platform_pose") == m.platforms()[0].joint);
  BOOST_TEST(m.platform_index("platform") == 0);
  for (const char* name : {"leg6", "base_plate"}) {
    BOOST_CHECK_THROW(m.rod_index(name), InputError);
    BOOST_CHECK_THROW(m.link_index(name), InputError);
    BOOST_CHECK_THROW(m.joint_index(name), InputError);
    BOOST_CHECK_THROW(m.input_index(name), InputError);
  }
  BOOST_CHECK_THROW(m.platform_index("base"), InputError);
  try {
    m.rod_index("leg6");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("'leg6'") != std::string::npos);
  }
  BOOST_TEST(kinematic_constraint_count(RodEndKind::Clamped) == 6);
  BOOST_TEST(kinematic_constraint_count(RodEndKind::Collar) == 5);
  BOOST_TEST(kinematic_constraint_count(RodEndKind::Spherical) == 3);
  BOOST_TEST(kinematic_constraint_count(RodEndKind::Free) == 0);
}

BOOST_AUTO_TEST_CASE(documented_example_loads) {
  // The annotated example of docs/model_format.md must stay a valid model.
  std::ifstream file(std::string(PCR_MODEL_DIR) + "/../docs/model_format.md");
  BOOST_REQUIRE(file.good());
  std::stringstream text;
  text << file.rdbuf();
  const std::string doc = text.str();
  const std::size_t begin = doc.find("```xml\n"), end = doc.find("```", begin + 7);
  BOOST_REQUIRE(begin != std::string::npos && end != std::string::npos);
  const RobotModel m = parse_robot_model(doc.substr(begin + 7, end - begin - 7), "model_format.md");
  BOOST_TEST(m.rods().size() == 3u);
  BOOST_TEST(m.inputs().size() == 3u);
  BOOST_TEST(m.platforms()[0].mass == 0.05);
  BOOST_TEST((m.platforms()[0].center_of_mass - Vec3(0, 0, 0.01)).norm() == 0.0);
  BOOST_TEST(m.loads().size() == 1u);
  BOOST_TEST((m.rods()[2].formulation == RodFormulationHint::Mixed && m.rods()[2].degree == 4));
}
