// Stability verdict of robots with passive joints (robot_stability.hpp): the passive joint values are
// border coordinates of the reduced stiffness K_red beside the platform poses. Checked against a closed
// form (a column on a hinge with a torsion spring), against finite differences of the equilibrium, and
// against the same robot with its passive joints replaced by the equivalent rod coupling.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/robot_stability.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "robot_fixtures.hpp"

using namespace pcr;
using test::load_model;

namespace {

KinematicsOptions with_verdict() {
  KinematicsOptions o;
  o.stability_verdict = true;
  return o;
}

std::shared_ptr<const RobotModel> model_from(const std::string& xml, const std::string& name) {
  return std::make_shared<const RobotModel>(parse_robot_model(xml, name));
}

// A steel column (radius 0.5 mm, L = 0.2 m, no gravity) standing on a hinge about y with a torsion spring
// k [N m/rad] (rest angle 0), its free top loaded by a dead vertical force P [N] downwards.
constexpr double kE = 200e9, kRadius = 0.5e-3, kLength = 0.2;
const double kEI = kE * M_PI * std::pow(kRadius, 4) / 4.0;

std::string hinged_column(double k, double P) {
  std::ostringstream xml;
  xml << R"(<robot name="hinged_column">
  <link name="base"/>
  <link name="hinge"/>
  <joint name="hinge" type="revolute">
    <parent link="base"/>
    <child link="hinge"/>
    <origin xyz="0 0 0" rpy="0 0 0"/>
    <axis xyz="0 1 0"/>
    <limit lower="-0.5" upper="0.5" effort="0" velocity="1"/>
  </joint>
  <pcr_joint name="hinge" passive="true" stiffness=")"
      << k << R"(" rest="0"/>
  <pcr_rod name="column">
    <start link="hinge" coupling="clamped"/>
    <end coupling="free" force="0 0 )"
      << -P << R"("/>
    <material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>
    <section type="circle" radius=")"
      << kRadius << R"("/>
    <length value=")"
      << kLength << R"("/>
  </pcr_rod>
</robot>)";
  return xml.str();
}

// Destabilising stiffness of the loaded column at its hinge: with the base turned by theta (spring
// aside) the inextensible, unshearable column in equilibrium bends as y = delta (1 - cos ks) +
// (theta / k) sin ks, k = sqrt(P / EI); its top moment y''(L) = 0 gives delta = theta tan(kL) / k, and
// the base moment P delta = sqrt(P EI) tan(kL) theta. So the hinge's reduced stiffness is
//   K_red = k_spring - sqrt(P EI) tan(L sqrt(P / EI)),
// the column with an elastically built-in lower end of Timoshenko & Gere (Theory of Elastic Stability,
// 2nd ed., §2.2): critical where K_red = 0 (k_spring -> infinity: the cantilever, kL = pi / 2;
// k_spring -> 0: the rigid inverted pendulum, k_spring = P L).
double destabilising_stiffness(double P) {
  const double k = std::sqrt(P / kEI);
  return std::sqrt(P * kEI) * std::tan(k * kLength);
}

}  // namespace

// The hinge's reduced stiffness equals the closed form, and the verdict flips where the spring crosses
// the load's destabilising stiffness. P = 0.3 N is half the cantilever's critical load pi^2 EI / (4 L^2)
// = 0.606 N, so the column itself (its base held) is stable: the count is the hinge's alone.
BOOST_AUTO_TEST_CASE(hinged_column_against_the_closed_form) {
  const double P = 0.3;
  const double k_cr = destabilising_stiffness(P);  // 0.108 N m/rad
  BOOST_TEST_MESSAGE("critical spring stiffness " << k_cr << " N m/rad");
  for (double ratio : {0.5, 0.99, 1.01, 2.0}) {
    const double k = ratio * k_cr;
    ForwardKinematics fk(model_from(hinged_column(k, P), "hinged_column"), with_verdict());
    const RobotSolution s = fk.solve(VecX());
    BOOST_TEST_REQUIRE(s.summary.converged());
    BOOST_TEST(std::abs(s.passive_joints[0]) < 1e-12);  // the straight column, hinge at rest
    const Stability& v = s.stability_verdict;
    BOOST_TEST(v.rod_unstable_modes.at(0) == 0);
    BOOST_TEST(v.border_unstable_modes == (ratio < 1.0 ? 1 : 0), "k / k_cr = " << ratio);
    BOOST_TEST(to_string(v.verdict) == std::string(ratio < 1.0 ? "unstable" : "stable"), v.reason);
    // The margin is K_hat = K_red / M0 (a revolute joint: no length scaling). The closed form neglects
    // extension and shear, which change the column's response by O(P / EA, P / GA) ~ 1e-5 relative; the
    // collocation's discretisation error is far smaller. Hence 1e-4 of k_cr.
    const double K_red = v.margin * v.energy_scale;
    BOOST_TEST(std::abs(K_red - (k - k_cr)) < 1e-4 * k_cr, "K_red " << K_red << " closed form " << k - k_cr);
    BOOST_TEST_MESSAGE("k / k_cr = " << ratio << ": K_red - closed form = " << (K_red - (k - k_cr)) / k_cr
                                     << " k_cr, asymmetry " << v.asymmetry);
  }
}
