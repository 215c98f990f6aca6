#pragma once
// Set-ups shared by the robot tests (and benchmarks/common): models by name, the tight settings of the
// references, inputs moved off their defaults, the fed column of the stability tests, the planar robot with
// other rod radii, the 6-RUS robot without its platform mass. No Boost.Test here: failures are
// pcr::InputError (require).
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/robot_model.hpp"
#include "pcr/robots/shooting/shooting_robot_solver.hpp"
#include "pcr/robots/urdf_loader.hpp"

namespace pcr::test {

/// models/<name>.urdf.
inline std::string model_path(const std::string& name) {
  return std::string(PCR_MODEL_DIR) + "/" + name + ".urdf";
}

/// The material element of a steel rod (E = 200 GPa, G = 80 GPa, 8000 kg/m^3).
inline constexpr const char* kSteel =
    R"(<material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>)";

/// The text of models/<name>.urdf (an InputError naming the file if it cannot be read).
inline std::string model_text(const std::string& name) {
  const std::string path = model_path(name);
  std::ifstream in(path);
  require(in.good(), path, ": cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::shared_ptr<const RobotModel> load_model(const std::string& name) {
  return std::make_shared<const RobotModel>(load_robot_model(model_path(name)));
}

/// Collocation converged to 1e-12 (max-abs of the scaled residuals), otherwise the defaults.
inline KinematicsOptions tight_kinematics() {
  KinematicsOptions o;
  o.tolerance = 1e-12;
  return o;
}

/// The shooting reference: Dormand-Prince with integration tolerances 1e-12 (relative and absolute),
/// converged to 1e-12 (scaled residual).
inline ShootingRobotOptions tight_shooting() {
  ShootingRobotOptions o;
  o.integrator = IntegratorMethod::DormandPrince;
  o.integration_relative_tolerance = 1e-12;
  o.integration_absolute_tolerance = 1e-12;
  o.tolerance = 1e-12;
  return o;
}

/// Inputs moved from the defaults by `fraction` of their range (1 where the range is unbounded) with an
/// asymmetric pattern: symmetric configurations of symmetric robots can be singular for IK (e.g. the
/// planar robot's x and rotation both depend on the left/right difference alone when left = right).
inline VecX moved_inputs(const RobotModel& m, double fraction) {
  const double pattern[] = {1.0, -0.6, 0.35, -0.8, 0.5, -0.2};
  VecX u = m.default_input_values();
  for (int i = 0; i < u.size(); ++i) {
    const ActuationInput& in = m.inputs()[i];
    const double range = std::isfinite(in.upper - in.lower) ? in.upper - in.lower : 1.0;
    u[i] += pattern[i % 6] * fraction * range;
  }
  return u;
}

/// The fed column of the stability tests: a steel rod (E = 200 GPa) with a 2 mm x 1 mm section clamped
/// upright in the base and fed through it (input: its length), its upper end clamped to a massless
/// platform under a dead load of 1 N down plus `lateral` N along x and y (an imperfection). Clamped-free
/// Euler column (Timoshenko & Gere §2.1): the straight column has its first unstable mode from
/// L_cr = (pi / 2) sqrt(E I_min / F) (weak plane), its second from 2 L_cr (strong plane, I_max = 4 I_min)
/// and its third from 3 L_cr (weak plane, second mode).
constexpr double kFedColumnLoad = 1.0;  // N
inline double fed_column_euler_length() {
  const double E = 200e9, width = 2e-3, height = 1e-3;  // Pa, m, m
  return M_PI / 2 * std::sqrt(E * width * std::pow(height, 3) / 12 / kFedColumnLoad);
}
inline std::shared_ptr<const RobotModel> fed_column(double lateral) {
  const std::string force =
      std::to_string(lateral) + " " + std::to_string(lateral) + " " + std::to_string(-kFedColumnLoad);
  const std::string xml = R"(<robot name="fed_column">
  <link name="base"/>
  <link name="platform"/>
  <joint name="platform_pose" type="floating">
    <parent link="base"/>
    <child link="platform"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/>
  </joint>
  <pcr_load link="platform" xyz="0 0 0" force=")" +
                          force + R"(" torque="0 0 0"/>
  <pcr_rod name="column">
    <start link="base" xyz="0 0 0" rpy="0 0 0" coupling="clamped"/>
    <end link="platform" xyz="0 0 0" rpy="0 0 0" coupling="clamped"/>
    <material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>
    <section type="rectangle" width="0.002" height="0.001"/>
    <length value="0.1" actuated="true" lower="0.05" upper="1.0"/>
  </pcr_rod>
</robot>)";
  return std::make_shared<const RobotModel>(parse_robot_model(xml, "fed_column"));
}

/// The planar robot with rods of the given radius instead of 0.5 mm; first_rod_extra: XML put into
/// the first rod element.
inline std::shared_ptr<const RobotModel> planar_with_radius(double radius,
                                                            const std::string& first_rod_extra = "") {
  std::string xml = model_text("planar_three_rod");
  const std::string from = "radius=\"0.0005\"", to = "radius=\"" + std::to_string(radius) + "\"";
  int replaced = 0;
  for (size_t at = xml.find(from); at != std::string::npos; at = xml.find(from, at + to.size()), ++replaced)
    xml.replace(at, from.size(), to);
  require(replaced == 3, model_path("planar_three_rod"), ": ", replaced, " rods of radius 0.5 mm, not 3");
  xml.insert(xml.find("</pcr_rod>"), first_rod_extra);
  return std::make_shared<const RobotModel>(parse_robot_model(xml, "planar_thick"));
}

/// models/six_rus.urdf without the platform's <inertial> (0.5 kg): the massless platform of the README
/// IK example of Rodrigues et al. (ARK 2024).
inline std::shared_ptr<const RobotModel> massless_six_rus() {
  std::string xml = model_text("six_rus");
  const size_t begin = xml.find("\n    <inertial>");
  const std::string close = "</inertial>";
  const size_t end = xml.find(close, begin);
  require(begin != std::string::npos && end != std::string::npos, model_path("six_rus"),
          ": no platform <inertial> to remove");
  xml.erase(begin, end + close.size() - begin);
  return std::make_shared<const RobotModel>(parse_robot_model(xml, "six_rus_massless"));
}

}  // namespace pcr::test
