#pragma once
// Private to the shooting robot solver: what it takes from a RobotModel (the rods with their start
// couplings, base frames and end attachments, the joints that move the base frames, the passive joints
// with what they carry, the loads and weights carried by platforms, the scales of lengths, forces and
// moments), the values of its unknowns (State), and the checks of what it supports.
#include <memory>
#include <optional>
#include <vector>

#include "pcr/robots/pose.hpp"
#include "pcr/robots/robot_model.hpp"
#include "pcr/rods/shooting/joint_ends.hpp"
#include "pcr/rods/shooting/rod_integrator.hpp"

namespace pcr {
namespace shooting_robot {

using Vec6 = Eigen::Matrix<double, 6, 1>;

struct RodSetup {
  int rod = -1;
  int platform = -1;  ///< platform carrying the end link
  int input = -1;     ///< index of the fed-length input, or -1
  RodEndKind start_coupling = RodEndKind::Clamped;
  RodEndKind coupling = RodEndKind::Clamped;  ///< at the end (s = L)
  joint_end::Axes start_axes, end_axes;       ///< of universal / revolute couplings
  /// Moving joints between the start link and the world (indices into joints()); empty: the base frame
  /// is fixed (base_frame).
  std::vector<int> base_joints;
  Pose base_frame;                    ///< world frame of the start attachment (fixed base frames)
  Pose end_offset;                    ///< end attachment frame in the platform frame
  RodModel model;                     ///< model.length = current length
  std::optional<RodOde> ode;          ///< rebuilt in place when the length changes (no allocation)
  std::vector<double> mesh_fraction;  ///< frozen Dormand-Prince steps, as fractions of L
  std::vector<double> mesh;
  Vec6 unknown_scale;              ///< of the six base unknowns (State::base)
  RodStateVector y0;               ///< base state of the last integration
  joint_end::BaseTangents dy0_dz;  ///< d y(0) / d(base unknowns), unscaled, of the last integration
  RodStateWithTangents Y;          ///< tip state and d y(L) / d(base unknowns) of the last integration
  /// d y(L) / d(world rotation of the base frame) of the last integration with tangents, when the base
  /// frame moves with an unknown (a second tangent pass on the same steps).
  joint_end::FrameTangents dyL_dframe;
  RodStateVector dy_dL;      ///< f(L, y(L))
  RodTrajectory trajectory;  ///< states at the steps of the last integration

  bool joint_start() const { return joint_end::is_joint(start_coupling); }
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

/// A passive joint and what lies beyond it (links not carried by a platform).
struct PassiveSetup {
  int joint = -1;  ///< index into joints()
  bool prismatic = false;
  double row_scale = 1.0;      ///< of its balance row: F_s (prismatic) or M_s
  double unknown_scale = 1.0;  ///< of its value: L_s (prismatic) or 1 rad
  std::vector<int> rods;       ///< rods starting on a link beyond it
  std::vector<int> links;      ///< links with mass beyond it
};

/// Values of the unknowns (world frame): each rod's six base unknowns (clamped start: n(0), m(0);
/// universal: n(0), theta1, theta2, mu; revolute: n(0), theta, mu1, mu2; joint_ends.hpp), each
/// platform's pose, the inputs, the passive joint values (RobotModel::passive_joints() order).
struct State {
  std::vector<Vec6> base;
  std::vector<Pose> poses;
  VecX inputs;
  VecX passive;
};

struct RobotShootingModel {
  /// Throws InputError for what the shooting solver does not support (see shooting_robot_solver.hpp).
  explicit RobotShootingModel(std::shared_ptr<const RobotModel> model);

  std::shared_ptr<const RobotModel> model;
  std::vector<RodSetup> rods;
  std::vector<LoadSetup> loads;  ///< external loads (all on links carried by platforms)
  std::vector<PassiveSetup> passive;
  std::vector<std::vector<int>> rods_of_platform;
  VecX input_scale;  ///< L_s for rod lengths and prismatic joints, 1 rad for revolute joints
  double Ls = 1.0, Fs = 1.0, Ms = 1.0;  ///< length, force, moment scales

  int num_rods() const { return static_cast<int>(rods.size()); }
  int num_platforms() const { return static_cast<int>(model->platforms().size()); }
  int num_passive() const { return static_cast<int>(passive.size()); }
  double length_of(const RodSetup& r, const State& s) const {
    return r.input >= 0 ? s.inputs[r.input] : r.model.length;
  }
  /// The joint-value vector (RobotModel::joint_value_count()) of a state: inputs and passive values.
  VecX joint_values(const State& s) const;
  /// World frame of rod i's start attachment in state s (joint_values(s) given for moving bases).
  Pose base_frame(int i, const VecX& joint_values, const State& s) const;
  /// Rod i's base state y(0) in state s, optionally with d y(0) / d(base unknowns) and d y(0) /
  /// d(world rotation of the base frame).
  void base_state(int i, const Pose& frame, const Vec6& z, RodStateVector& y0,
                  joint_end::BaseTangents* dy_dz = nullptr,
                  joint_end::FrameTangents* dy_dframe = nullptr) const;
  /// Rate of rod i's base frame (velocity of its origin, angular velocity; world) per unit value of the
  /// moving joint j, at the joint values q.
  void base_frame_rate(int i, int j, const VecX& q, const State& s, Vec3& velocity, Vec3& omega) const;
  /// Unbent rods sharing their platform's load equally; joint angles and moments at the base zero.
  State cold_state(const VecX& inputs, const std::vector<Pose>& poses) const;
};

}  // namespace shooting_robot
}  // namespace pcr
