#include "common/six_rus_scene.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "robot_fixtures.hpp"

namespace pcr::bench {

std::shared_ptr<const RobotModel> load_six_rus(bool platform_mass) {
  return platform_mass ? test::load_model("six_rus") : test::massless_six_rus();
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
