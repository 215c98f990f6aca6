#pragma once
// Private to the shooting robot solver: the residual rows of a rod's end coupling to its platform,
// one entry per coupling kind, the platforms' balance and the passive joints' balance (see
// shooting_robot_solver.hpp). A new coupling kind is one more function and one more case in
// coupling_of(): its 6 rows of the tip state y(L) against the attachment frame T and their scales.
#include "robot_shooting_model.hpp"

namespace pcr {
namespace shooting_robot {

struct Coupling {
  /// The 6 scaled rows at the tip state y against the attachment frame T (world) with the joint axes
  /// of a universal or revolute coupling.
  Vec6 (*residual)(const RodStateVector& y, const Pose& T, const joint_end::Axes& axes,
                   const RobotShootingModel& m);
  /// Unscaled row = scaled row * row_scale.
  Vec6 (*row_scale)(const joint_end::Axes& axes, const RobotShootingModel& m);
};

/// The coupling of a rod end kind; throws InputError for a kind the shooting solver cannot couple.
const Coupling& coupling_of(RodEndKind kind);

/// Force and moment balance of platform k at its pose, from the tip states of its rods (rods[i].Y),
/// divided by F_s and M_s.
Vec6 platform_balance(const RobotShootingModel& m, int k, const Pose& pose);

/// World axis w and origin o of a joint at the joint values q.
void joint_axis(const RobotShootingModel& m, int joint, const VecX& q, const State& s, Vec3& w, Vec3& o);
/// Balance of passive joint p, Q - k (q - rest), divided by its row scale. Q: the generalised force on
/// what lies beyond it, from the base states y0[i] of its rods (force n(0) at p(0), moment m(0)) and the
/// weights of its links: w . (sum of moments about o) (revolute, continuous) or w . (sum of forces).
double passive_balance(const RobotShootingModel& m, int p, const VecX& q, const State& s,
                       const std::vector<RodStateVector>& y0);
/// d(unscaled Q of passive joint p) / d y(0) of one of its rods, for the axis w and origin o.
Eigen::Matrix<double, 1, kRodStateSize> passive_force_gradient(const PassiveSetup& p, const Vec3& w,
                                                               const Vec3& o, const RodStateVector& y0);

}  // namespace shooting_robot
}  // namespace pcr
