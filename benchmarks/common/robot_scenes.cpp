#include "common/robot_scenes.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/urdf_loader.hpp"

namespace pcr::bench {

std::shared_ptr<const RobotModel> load_r5a() {
  return std::make_shared<const RobotModel>(
      load_robot_model(std::string(PCR_MODEL_DIR) + "/stewart_gough.urdf"));
}

std::shared_ptr<const RobotModel> load_r5b() {
  return std::make_shared<const RobotModel>(
      load_robot_model(std::string(PCR_MODEL_DIR) + "/stewart_gough_teleop.urdf"));
}

VecX r5a_moved_inputs(const RobotModel& r5a) {
  VecX u = r5a.default_input_values();
  const double pattern[] = {1.0, -0.6, 0.35, -0.8, 0.5, -0.2};
  for (int i = 0; i < u.size(); ++i) u[i] += 0.005 * pattern[i % 6];
  return u;
}

Pose r5a_target() {
  Pose target;
  target.position = Vec3(0, 0, 0.4);
  target.orientation = quat_from_rotation(rotation_y(10.0 * M_PI / 180.0));
  return target;
}

std::vector<Pose> r5b_path(int steps) {
  std::vector<Pose> path;
  for (int i = 0; i <= steps; ++i) {
    Pose p;
    p.position = Vec3(0, 0.02 + 0.001 * i, 0.48 + 0.001 * i);
    path.push_back(p);
  }
  for (int i = steps - 1; i >= 0; --i) path.push_back(path[i]);
  return path;
}

std::vector<Pose> r5b_helix_path(int targets) {
  const double radius = 0.02, pitch = 0.01, step = 1.3e-3;
  const double rise = pitch / (2.0 * M_PI);                               // dz / dtheta
  const double dtheta = step / std::sqrt(radius * radius + rise * rise);  // |dp / dtheta| dtheta = step
  std::vector<Pose> path;
  for (int i = 0; i <= targets; ++i) {
    const double theta = i * dtheta;
    Pose p;
    p.position = Vec3(-radius * std::sin(theta), radius * std::cos(theta), 0.48 + rise * theta);
    path.push_back(p);
  }
  return path;
}

LinkTarget platform_target() {
  LinkTarget t;
  t.link = "platform";
  return t;
}

ShootingRobotOptions shooting_reference_options() {
  ShootingRobotOptions o;
  o.integration_relative_tolerance = o.integration_absolute_tolerance = 1e-12;
  o.tolerance = 1e-12;
  return o;
}

std::vector<ShootingMethod> shooting_methods(const std::vector<int>& rk4_steps) {
  std::vector<ShootingMethod> out;
  for (int n : rk4_steps) {
    ShootingRobotOptions o;
    o.integrator = IntegratorMethod::RK4;
    o.rk4_steps = n;
    out.push_back({"rk4", "N=" + std::to_string(n), o});
  }
  for (double tol : {1e-6, 1e-8, 1e-10}) {
    ShootingRobotOptions o;
    o.integration_relative_tolerance = o.integration_absolute_tolerance = tol;
    char text[32];
    std::snprintf(text, sizeof text, "tol=%g", tol);
    out.push_back({"dormand_prince", text, o});
  }
  return out;
}

}  // namespace pcr::bench
