#include "common/six_rus_scene.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/urdf_loader.hpp"

namespace pcr::bench {

std::shared_ptr<const RobotModel> load_six_rus(bool platform_mass) {
  const std::string path = std::string(PCR_MODEL_DIR) + "/six_rus.urdf";
  if (platform_mass) return std::make_shared<const RobotModel>(load_robot_model(path));
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = text.str();
  const size_t begin = xml.find("\n    <inertial>");
  const std::string close = "</inertial>";
  const size_t end = xml.find(close, begin);
  require(begin != std::string::npos && end != std::string::npos,
          path + ": no platform <inertial> to remove");
  xml.erase(begin, end + close.size() - begin);
  return std::make_shared<const RobotModel>(parse_robot_model(xml, "six_rus_massless"));
}

VecX six_rus_readme_fk_inputs() {
  VecX u(6);
  u << 0.48785652, 0.48785652, 0.42037453, 0.28121425, 0.28121425, 0.42037453;
  return u;
}

Pose six_rus_readme_ik_target() {
  Pose target;
  target.position = Vec3(0, 0, 0.5);
  target.orientation = quat_from_rotation(rotation_x(10.0 * M_PI / 180.0));
  return target;
}

std::vector<Pose> six_rus_helix(int points) {
  std::vector<Pose> helix;
  for (int i = 0; i < points; ++i) {
    const double f = double(i) / (points - 1), angle = 2.0 * M_PI * f;
    Pose p;
    p.position = Vec3(0.25 * std::cos(angle), 0.25 * std::sin(angle), 0.4 + 0.15 * f);
    helix.push_back(p);
  }
  return helix;
}

}  // namespace pcr::bench
