#pragma once
// Private to the shooting robot solver: what it takes from a RobotModel (the rods with their base
// frames and end attachments, the loads carried by platforms, the scales of lengths, forces and
// moments), the values of its unknowns (State), and the checks of what it supports.
#include <memory>
#include <optional>
#include <vector>

#include "pcr/robots/pose.hpp"
#include "pcr/robots/robot_model.hpp"
#include "pcr/rods/shooting/rod_integrator.hpp"

namespace pcr {
namespace shooting_robot {

struct RodSetup {
  int rod = -1;
  int platform = -1;  ///< platform carrying the end link
  int input = -1;     ///< index of the fed-length input, or -1
  RodEndKind coupling = RodEndKind::Clamped;
  Pose base_frame;                    ///< world frame of the clamped start
  Pose end_offset;                    ///< end attachment frame in the platform frame
  RodModel model;                     ///< model.length = current length
  std::optional<RodOde> ode;          ///< rebuilt in place when the length changes (no allocation)
  std::vector<double> mesh_fraction;  ///< frozen Dormand-Prince steps, as fractions of L
  std::vector<double> mesh;
  RodStateWithTangents Y;    ///< tip state and d y(L) / d (n(0), m(0)) of the last integration
  RodStateVector dy_dL;      ///< f(L, y(L))
  RodTrajectory trajectory;  ///< states at the steps of the last integration

  void set_length(double L) {
    if (ode && model.length == L) return;
    model.length = L;
    ode.emplace(model);
  }
};

/// An external load carried by a platform, its point in the platform frame.
struct LoadSetup {
  int platform = -1;
  Vec3 point = Vec3::Zero();
  Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
};

/// Values of the unknowns (world frame): each rod's base wrench, each platform's pose, the inputs.
struct State {
  std::vector<Vec3> n0, m0;
  std::vector<Pose> poses;
  VecX inputs;
};

struct RobotShootingModel {
  /// Throws InputError for what the shooting solver does not support (see shooting_robot_solver.hpp).
  explicit RobotShootingModel(std::shared_ptr<const RobotModel> model);

  std::shared_ptr<const RobotModel> model;
  std::vector<RodSetup> rods;
  std::vector<LoadSetup> loads;
  std::vector<std::vector<int>> rods_of_platform;
  double Ls = 1.0, Fs = 1.0, Ms = 1.0;  ///< length, force, moment scales

  int num_rods() const { return static_cast<int>(rods.size()); }
  int num_platforms() const { return static_cast<int>(model->platforms().size()); }
  double length_of(const RodSetup& r, const State& s) const {
    return r.input >= 0 ? s.inputs[r.input] : r.model.length;
  }
  /// Unbent rods sharing their platform's load equally.
  State cold_state(const VecX& inputs, const std::vector<Pose>& poses) const;
};

}  // namespace shooting_robot
}  // namespace pcr
