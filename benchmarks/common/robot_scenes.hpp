#pragma once
// The Stewart-Gough scenes of the benchmarks (docs/benchmarks.md (Scenes) R5a, R5b): models, the R5a
// inputs and target, the R5b teleoperation path.
#include <memory>
#include <string>
#include <vector>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/pose.hpp"
#include "pcr/robots/robot_model.hpp"
#include "pcr/robots/shooting/shooting_robot_solver.hpp"

namespace pcr::bench {

/// models/stewart_gough.urdf (R5a: steel, gravity, 0.1 kg platform).
std::shared_ptr<const RobotModel> load_r5a();
/// models/stewart_gough_teleop.urdf (R5b: no gravity, no platform mass).
std::shared_ptr<const RobotModel> load_r5b();

/// R5a FK inputs off the default ones: rod lengths moved by 5 mm times (1, -0.6, 0.35, -0.8, 0.5, -0.2).
VecX r5a_moved_inputs(const RobotModel& r5a);
/// R5a IK target: platform at (0, 0, 0.4) m, turned by R_y(10 deg).
Pose r5a_target();
/// R5b path: (0, 0.02, 0.48) + i (0, 0.001, 0.001) m for i = 0..steps and back to i = 0 (2 steps + 1
/// poses; the scene has steps = 100), orientation identity.
std::vector<Pose> r5b_path(int steps = 100);
/// R5b helical path: `targets` + 1 poses on the helix p(theta) = (-r sin theta, r cos theta, 0.48 m +
/// h theta / (2 pi)) about the z axis, radius r = 0.02 m, pitch h = 0.01 m per turn, starting at the
/// model's default platform position (0, 0.02, 0.48) m, consecutive poses 1.3 mm apart along the helix,
/// orientation identity. No pose is visited twice (400 targets: 4.1 turns, 0.52 m of path).
std::vector<Pose> r5b_helix_path(int targets = 400);
/// Collocation IK target on the link "platform" (full pose).
LinkTarget platform_target();
/// Shooting settings of the robot references: Dormand-Prince with integration_relative_tolerance =
/// integration_absolute_tolerance = 1e-12 and residual tolerance 1e-12.
ShootingRobotOptions shooting_reference_options();

/// A timed shooting setting: its integrator ("rk4" or "dormand_prince"), the settings column of the
/// CSV ("N=40", "tol=1e-08") and the solver options (otherwise the defaults).
struct ShootingMethod {
  std::string name, settings;
  ShootingRobotOptions options;
};
/// The timed shooting settings: RK4 with each of `rk4_steps` steps per rod, then Dormand-Prince at
/// integration_relative_tolerance = integration_absolute_tolerance = 1e-6, 1e-8 and 1e-10.
std::vector<ShootingMethod> shooting_methods(const std::vector<int>& rk4_steps);

}  // namespace pcr::bench
