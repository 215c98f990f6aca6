// Robots with universal and revolute rod couplings and passive URDF joints: the coupling and passive
// joint balance blocks against finite differences (the shipped joint models, chains of 1-3 passive
// joints), the universal coupling against its construction from two passive revolute joints, closed-form
// balances (a bar on a passive hinge with a torsion spring under gravity; a passive swivel carrying a
// passive slider), FK -> IK round trips on the joint models, passive joint values in the table and JSON.
// The rank check's constraint counts and malformed joint input: test_joint_model_checks.cpp (same
// executable).
#define BOOST_TEST_MODULE joints
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <sstream>

#include "pcr/core/error.hpp"
#include "pcr/math/dense_decompositions.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/solve/jacobian_check.hpp"
#include "robot_fixtures.hpp"

using namespace pcr;
using test::kSteel;
using test::load_model;
using test::moved_inputs;
using test::tight_kinematics;

namespace {

const char* const kInertia = R"(<inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/>)";

/// A serial chain of `passive` passive joints (1..3: a revolute about y with a spring, a prismatic
/// along a skew axis with a spring, a continuous joint about a tilted axis with a spring) below an
/// actuated revolute joint 'turn' about z, links with masses off their axes, a pcr_load on the last
/// link, and a rod clamped on the last link with a free tip, under gravity.
std::string chain_model(int passive) {
  std::ostringstream x;
  x << "<?xml version=\"1.0\"?>\n<robot name=\"chain" << passive << "\">\n  <link name=\"base\"/>\n";
  x << "  <link name=\"l0\"/>\n";
  x << R"(  <joint name="turn" type="revolute"><parent link="base"/><child link="l0"/>
    <origin xyz="0 0 0.05" rpy="0 0 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="0" velocity="1"/></joint>
  <pcr_joint name="turn" default="0.3"/>
)";
  const char* joints[] = {
      R"(type="revolute"><origin xyz="0.01 0 0" rpy="0 0 0"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="0" velocity="1"/>)",
      R"(type="prismatic"><origin xyz="0.03 0 0" rpy="0 0 0"/><axis xyz="1 0 0.3"/><limit lower="-0.1" upper="0.1" effort="0" velocity="1"/>)",
      R"(type="continuous"><origin xyz="0.02 0 0.01" rpy="0.1 0 0"/><axis xyz="0.2 0 1"/>)"};
  const char* springs[] = {R"(stiffness="0.5" rest="0.1")", R"(stiffness="200")",
                           R"(stiffness="0.3" rest="-0.05")"};
  for (int i = 1; i <= passive; ++i) {
    x << "  <link name=\"l" << i << "\"><inertial><origin xyz=\"0.02 0.005 0\" rpy=\"0 0 0\"/><mass value=\""
      << 0.01 * i << "\"/>" << kInertia << "</inertial></link>\n";
    x << "  <joint name=\"j" << i << "\" " << joints[i - 1] << "<parent link=\"l" << i - 1
      << "\"/><child link=\"l" << i << "\"/></joint>\n";
    x << "  <pcr_joint name=\"j" << i << "\" passive=\"true\" " << springs[i - 1] << "/>\n";
  }
  x << "  <pcr_gravity xyz=\"0 0 -9.81\"/>\n";
  x << "  <pcr_load link=\"l" << passive
    << "\" xyz=\"0.01 0 0\" force=\"0 0.2 -0.1\" torque=\"0.001 0 0\"/>\n";
  x << "  <pcr_rod name=\"arm\"><start link=\"l" << passive << "\" rpy=\"0 1.2 0\" coupling=\"clamped\"/>"
    << "<end coupling=\"free\"/>" << kSteel
    << R"(<section type="circle" radius="0.001"/><length value="0.2"/></pcr_rod>)"
    << "\n</robot>\n";
  return x.str();
}

int count_blocks(const Problem& p, const std::string& kind) {
  int n = 0;
  for (ResidualId b = 0; b < p.num_residual_blocks(); ++b) n += p.residual(b).kind() == kind;
  return n;
}

}  // namespace

BOOST_AUTO_TEST_CASE(joint_coupling_and_passive_balance_blocks_match_finite_differences) {
  std::vector<std::pair<std::string, std::shared_ptr<const RobotModel>>> models;
  for (const char* name : {"planar_pinned", "passive_hinge", "universal_pair", "universal_passive"})
    models.emplace_back(name, load_model(name));
  for (int n = 1; n <= 3; ++n)
    models.emplace_back("chain" + std::to_string(n),
                        std::make_shared<const RobotModel>(parse_robot_model(chain_model(n), "chain.urdf")));
  std::mt19937 rng(17);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (const auto& [name, model] : models) {
    for (bool condensed : {true, false}) {  // rod ends read from the condensed and the mixed form
      KinematicsOptions o;
      o.assembly.condense_mixed_rods = condensed;
      ForwardKinematics fk(model, o);
      const RobotSolution s = fk.solve(model->default_input_values());
      BOOST_REQUIRE_MESSAGE(s.summary.converged(), name << ": " << s.summary.brief_report());
      const Problem& p = fk.assembly().problem();
      BOOST_TEST(count_blocks(p, "joint.passive_balance") ==
                 static_cast<int>(model->passive_joints().size()));
      int universal = 0, revolute = 0;
      for (const RodElement& rod : model->rods())
        for (RodEndKind kind : {rod.start.coupling, rod.end.coupling}) {
          universal += kind == RodEndKind::Universal;
          revolute += kind == RodEndKind::Revolute;
        }
      BOOST_TEST(count_blocks(p, "coupling.universal") == universal, name);
      BOOST_TEST(count_blocks(p, "coupling.revolute") == revolute, name);
      BOOST_TEST(universal + revolute + static_cast<int>(model->passive_joints().size()) > 0, name);
      // A perturbed state (relative 1e-3, quaternions no longer unit, joint values moved).
      VecX x = fk.state();
      for (int i = 0; i < x.size(); ++i) x[i] += 1e-3 * (std::abs(x[i]) + 1e-2) * noise(rng);
      // Default checker tolerances (1e-6 abs + rel; central differences with relative step 1e-6:
      // truncation ~1e-12, round-off ~1e-10 on these O(1) scaled residuals).
      const JacobianCheckResult r = check_problem_jacobian(p, x);
      BOOST_TEST(r.passed, name << (condensed ? " condensed" : " mixed") << ": " << r.to_string());
    }
  }
}

BOOST_AUTO_TEST_CASE(universal_coupling_equals_two_passive_revolute_joints) {
  // universal_passive builds each universal joint of universal_pair from two spring-less passive
  // revolute joints (x of the attachment, then y of the cross link) with the rod clamped on the yoke:
  // the yoke frame R_T R_x(t1) R_y(t2) is the universal's configuration set and the joints' zero
  // generalised forces are its two zero moment rows, so both models have the same discrete equilibria.
  // Agreement to 1e-10 m (issue requirement): both solves at 1e-12 dimensionless residual x length
  // scale 0.26 m, times the condition of the platform's response (< 1e2 here).
  const auto pair = load_model("universal_pair"), passive = load_model("universal_passive");
  const VecX u = moved_inputs(*pair, 0.05);
  ForwardKinematics fa(pair, tight_kinematics()), fb(passive, tight_kinematics());
  const RobotSolution a = fa.solve(u), b = fb.solve(u);
  BOOST_REQUIRE_MESSAGE(a.summary.converged(), a.summary.brief_report());
  BOOST_REQUIRE_MESSAGE(b.summary.converged(), b.summary.brief_report());
  const double dx = (a.platforms[0].position - b.platforms[0].position).norm();
  const double dr = so3_log(a.platforms[0].rotation().transpose() * b.platforms[0].rotation()).norm();
  BOOST_TEST(dx < 1e-10, "platform position differs by " << dx);
  BOOST_TEST(dr < 1e-10, "platform rotation differs by " << dr);
  double worst = 0.0;
  for (size_t r = 0; r < a.rods.size(); ++r)
    for (size_t k = 0; k < a.rods[r].centerline.size(); ++k)
      worst = std::max(worst, (a.rods[r].centerline[k] - b.rods[r].centerline[k]).norm());
  BOOST_TEST(worst < 1e-10, "centerlines differ by " << worst);
  BOOST_TEST_MESSAGE("universal vs two passive revolutes: platform "
                     << dx << " m, " << dr << " rad, centerlines " << worst << " m");
  // The passive joints did turn: the platform moved 5 % of the input range off the symmetric pose.
  BOOST_TEST(b.passive_joints.cwiseAbs().maxCoeff() > 1e-3);
}

BOOST_AUTO_TEST_CASE(bar_on_a_passive_hinge_with_a_torsion_spring_meets_the_moment_balance) {
  // A steel bar (radius 5 mm, L = 0.1 m) clamped along +x on a link that turns about the world y axis
  // at the origin (passive, spring k, rest angle q0), with a 4 g mass 5 cm along the bar on the link,
  // under gravity g along -z. Turning by q about +y lowers the bar; the weights' moment about +y is
  // (W L / 2 + m g d) cos q, so the equilibrium is k (q - q0) = (W L / 2 + m g d) cos q, W = rho A L g.
  // The bar's bending moves its weight by at most its tip deflection w L^4 / (8 EI) = 7.8e-7 m (w = W / L,
  // EI = 98 N m^2) across the bar, i.e. by <= 7.8e-7 sin q m along the lever: a moment error
  // <= 0.62 N x 4.4e-7 m = 2.7e-7 N m over a stiffness dM/dq >= k = 0.07 N m/rad gives |dq| <= 4e-6 rad;
  // axial and shear strain (w L / EA ~ 4e-11) are far smaller. Tolerance 1e-5 rad.
  const double k = 0.07, q0 = 0.2, L = 0.1, r = 0.005, rho = 8000, g = 9.81, m = 0.004, d = 0.05;
  std::ostringstream x;
  x << R"(<?xml version="1.0"?>
<robot name="hinge_bar">
  <link name="base"/>
  <link name="arm"><inertial><origin xyz=")"
    << d << R"( 0 0" rpy="0 0 0"/><mass value=")" << m << "\"/>" << kInertia << R"(</inertial></link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0" rpy="0 0 0"/><axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="0" velocity="1"/></joint>
  <pcr_joint name="hinge" passive="true" stiffness=")"
    << k << "\" rest=\"" << q0 << R"("/>
  <pcr_gravity xyz="0 0 -9.81"/>
  <pcr_rod name="bar"><start link="arm" rpy="0 1.5707963267948966 0" coupling="clamped"/><end coupling="free"/>)"
    << kSteel << "<section type=\"circle\" radius=\"" << r << "\"/><length value=\"" << L << R"("/></pcr_rod>
</robot>)";
  const auto model = std::make_shared<const RobotModel>(parse_robot_model(x.str(), "hinge_bar.urdf"));
  ForwardKinematics fk(model, tight_kinematics());
  const RobotSolution s = fk.solve(model->default_input_values());
  BOOST_REQUIRE_MESSAGE(s.summary.converged(), s.summary.brief_report());
  BOOST_REQUIRE(s.passive_joints.size() == 1);
  // Reference: Newton on f(q) = k (q - q0) - M cos q (f' >= k > 0: one root).
  const double M = rho * M_PI * r * r * L * g * L / 2 + m * g * d;
  double q = q0;
  for (int i = 0; i < 50; ++i) q -= (k * (q - q0) - M * std::cos(q)) / (k + M * std::sin(q));
  BOOST_TEST(std::abs(k * (q - q0) - M * std::cos(q)) < 1e-15);
  BOOST_TEST(q > 0.5);  // the weights turn the hinge well away from its rest angle
  BOOST_TEST_MESSAGE("hinge " << s.passive_joints[0] << " rad, closed form " << q << ", difference "
                              << s.passive_joints[0] - q);
  BOOST_TEST(std::abs(s.passive_joints[0] - q) < 1e-5, "hinge " << s.passive_joints[0] << " vs " << q);
  // The bar's tip lies on the line at angle q below the x axis, to its bending (7.8e-7 m) and the
  // angle error (L x 4e-6 rad): tolerance 2e-6 m.
  const Vec3 tip = s.rods[0].centerline.back();
  BOOST_TEST((tip - L * Vec3(std::cos(q), 0, -std::sin(q))).norm() < 2e-6, "tip " << tip.transpose());
}

BOOST_AUTO_TEST_CASE(continuous_and_prismatic_passive_joints_in_a_chain_balance_their_loads) {
  // A swivel (continuous, about the world z axis, spring k2, rest r2) carries a slider (prismatic along
  // the swivel link's x axis x1 = Rz(q2) e_x, 2 cm up, spring k1, rest r1); on the slider link a rod
  // clamped at its origin with a free tip loaded by a vertical force and a moment Mz about z, a
  // horizontal load F at the slider link's origin (q1 x1 + 2 cm z from the swivel axis), link masses,
  // gravity along -z. Vertical forces have no component along x1 and no moment about z, so whatever the
  // rod's deformation the balances are
  //   k1 (q1 - r1) = x1 . F = cos q2 Fx + sin q2 Fy,
  //   k2 (q2 - r2) = Mz + (q1 x1 x F) . z = Mz + q1 (cos q2 Fy - sin q2 Fx).
  // Tolerance 1e-9 (m, rad): the solve's 1e-12 dimensionless residual x the moment and force scales
  // (~1 N m, ~1 N) over the springs (0.2 N m/rad, 50 N/m) is <= 5e-12.
  const double k1 = 50, r1 = 0.01, k2 = 0.2, r2 = 0.1, Fx = 0.3, Fy = 0.2, Mz = 0.004;
  std::ostringstream x;
  x << R"(<?xml version="1.0"?>
<robot name="swivel_slider">
  <link name="base"/>
  <link name="turntable"><inertial><origin xyz="0.01 0.02 0" rpy="0 0 0"/><mass value="0.05"/>)"
    << kInertia << R"(</inertial></link>
  <link name="carriage"><inertial><origin xyz="0.01 0 0.01" rpy="0 0 0"/><mass value="0.03"/>)"
    << kInertia << R"(</inertial></link>
  <joint name="swivel" type="continuous"><parent link="base"/><child link="turntable"/>
    <origin xyz="0 0 0" rpy="0 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="slider" type="prismatic"><parent link="turntable"/><child link="carriage"/>
    <origin xyz="0 0 0.02" rpy="0 0 0"/><axis xyz="1 0 0"/><limit lower="-0.1" upper="0.1" effort="0" velocity="1"/></joint>
  <pcr_joint name="swivel" passive="true" stiffness=")"
    << k2 << "\" rest=\"" << r2 << R"("/>
  <pcr_joint name="slider" passive="true" stiffness=")"
    << k1 << "\" rest=\"" << r1 << R"("/>
  <pcr_gravity xyz="0 0 -9.81"/>
  <pcr_load link="carriage" xyz="0 0 0" force=")"
    << Fx << " " << Fy << R"( 0" torque="0 0 0"/>
  <pcr_rod name="arm"><start link="carriage" rpy="0 1.2 0" coupling="clamped"/>
    <end coupling="free" force="0 0 -0.2" moment="0 0 )"
    << Mz << "\"/>" << kSteel << R"(<section type="circle" radius="0.001"/><length value="0.2"/></pcr_rod>
</robot>)";
  const auto model = std::make_shared<const RobotModel>(parse_robot_model(x.str(), "swivel_slider.urdf"));
  BOOST_REQUIRE(model->passive_joints().size() == 2);  // file order: swivel, slider
  ForwardKinematics fk(model, tight_kinematics());
  const RobotSolution s = fk.solve(model->default_input_values());
  BOOST_REQUIRE_MESSAGE(s.summary.converged(), s.summary.brief_report());
  double q1 = r1, q2 = r2;  // fixed point (a contraction: the coupling q1 Fy / k2 ~ 0.01)
  for (int i = 0; i < 200; ++i) {
    q2 = r2 + (Mz + q1 * (std::cos(q2) * Fy - std::sin(q2) * Fx)) / k2;
    q1 = r1 + (std::cos(q2) * Fx + std::sin(q2) * Fy) / k1;
  }
  BOOST_TEST(std::abs(k2 * (q2 - r2) - Mz - q1 * (std::cos(q2) * Fy - std::sin(q2) * Fx)) < 1e-15);
  BOOST_TEST_MESSAGE("swivel " << q2 << " rad, error " << s.passive_joints[0] - q2 << "; slider " << q1
                               << " m, error " << s.passive_joints[1] - q1);
  BOOST_TEST(std::abs(s.passive_joints[0] - q2) < 1e-9, "swivel " << s.passive_joints[0] << " vs " << q2);
  BOOST_TEST(std::abs(s.passive_joints[1] - q1) < 1e-9, "slider " << s.passive_joints[1] << " vs " << q1);
}

BOOST_AUTO_TEST_CASE(fk_then_ik_round_trip_on_the_joint_models) {
  // As test_kinematics' round trip: FK at moved inputs, IK to the reached pose (the components each
  // robot's inputs control), then FK at the IK's inputs reaches the target to 1e-9 (m, rad: solver
  // tolerance 1e-10 x length scale ~0.3 m); the IK inputs equal the FK inputs to 1e-8 where the
  // targeted map is well conditioned (singular value ratio > 1e-3), and then the passive joints agree.
  const std::array<bool, 6> full{{true, true, true, true, true, true}},
      planar{{true, false, true, false, true, false}};
  const std::pair<const char*, std::array<bool, 6>> cases[] = {{"planar_pinned", planar},
                                                               {"passive_hinge", planar},
                                                               {"universal_pair", full},
                                                               {"universal_passive", full}};
  for (const auto& [name, components] : cases) {
    const auto model = load_model(name);
    ForwardKinematics fk(model);
    const VecX u = moved_inputs(*model, 0.005);
    const RobotSolution s = fk.solve(u);
    BOOST_REQUIRE_MESSAGE(s.summary.converged(), name << " FK: " << s.summary.brief_report());
    const MatX J = fk.input_jacobian();
    MatX selected(0, J.cols());
    for (int k = 0; k < 6; ++k)
      if (components[k]) {
        selected.conservativeResize(selected.rows() + 1, Eigen::NoChange);
        selected.row(selected.rows() - 1) = J.row(k);
      }
    const VecX sigma = singular_values(selected);
    const double ratio = sigma.minCoeff() / sigma.maxCoeff();
    BOOST_TEST_MESSAGE(name << ": target/input singular value ratio " << ratio);
    LinkTarget t;
    t.link = "platform";
    t.components = components;
    t.pose = s.platforms[0];
    InverseKinematics ik(model, {t});
    const RobotSolution r = ik.solve({s.platforms[0]});
    BOOST_REQUIRE_MESSAGE(r.summary.converged(),
                          name << " IK: " << r.summary.brief_report() << " " << r.summary.message);
    const RobotSolution check = fk.solve(r.inputs);
    BOOST_REQUIRE_MESSAGE(check.summary.converged(),
                          name << " FK at the IK inputs: " << check.summary.brief_report());
    const Vec3 dx = check.platforms[0].position - s.platforms[0].position;
    const Vec3 dr = so3_log(s.platforms[0].rotation().transpose() * check.platforms[0].rotation());
    for (int k = 0; k < 3; ++k) {
      if (components[k]) BOOST_TEST(std::abs(dx[k]) < 1e-9, name << " position " << k << ": " << dx[k]);
      if (components[3 + k]) BOOST_TEST(std::abs(dr[k]) < 1e-9, name << " rotation " << k << ": " << dr[k]);
    }
    if (ratio > 1e-3) {
      BOOST_TEST((r.inputs - u).lpNorm<Eigen::Infinity>() < 1e-8,
                 name << ": IK inputs " << r.inputs.transpose());
      if (s.passive_joints.size() > 0)
        BOOST_TEST((r.passive_joints - s.passive_joints).lpNorm<Eigen::Infinity>() < 1e-8, name);
    }
  }
}

BOOST_AUTO_TEST_CASE(table_and_json_list_the_passive_joint_values) {
  const auto model = load_model("passive_hinge");
  ForwardKinematics fk(model);
  const RobotSolution s = fk.solve(model->default_input_values());
  BOOST_REQUIRE(s.summary.converged());
  std::ostringstream table, json;
  write_solution_table(table, *model, s);
  write_solution_json(json, *model, s);
  char line[64];
  std::snprintf(line, sizeof line, "  %-16s %12.4f deg", "hinge", s.passive_joints[0] * 180 / M_PI);
  BOOST_TEST(table.str().find("passive joints:\n" + std::string(line)) != std::string::npos, table.str());
  BOOST_TEST(json.str().find("\"passive_joints\": {") != std::string::npos, json.str());
  BOOST_TEST(json.str().find("\"hinge\": ") != std::string::npos, json.str());
  const Joint& hinge = model->joints()[model->passive_joints()[0]];
  BOOST_REQUIRE(s.passive_joints[0] >= hinge.lower && s.passive_joints[0] <= hinge.upper);
  BOOST_TEST(json.str().find("\"passive_joints_outside_limits\": []") != std::string::npos, json.str());
  // The same solution with the hinge turned past its upper limit (the writers read the value only; FK
  // does not enforce limits): both outputs name it.
  RobotSolution past = s;
  past.passive_joints[0] = hinge.upper + 0.1;
  std::ostringstream past_table, past_json;
  write_solution_table(past_table, *model, past);
  write_solution_json(past_json, *model, past);
  BOOST_TEST(past_table.str().find("(outside its limits") != std::string::npos, past_table.str());
  const std::string text = past_json.str();
  const size_t list = text.find("\"passive_joints_outside_limits\": [");
  BOOST_REQUIRE(list != std::string::npos);
  BOOST_TEST(text.substr(list, text.find(']', list) - list).find("\"hinge\"") != std::string::npos, text);
}
