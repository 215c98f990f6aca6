#pragma once
// Private to the shooting robot solver: the residual rows of a rod's end coupling to its platform,
// one entry per coupling kind, and the platforms' balance (see shooting_robot_solver.hpp).
// A new coupling kind (e.g. universal, revolute) is one more function and one more case in
// coupling_of(): its 6 rows of the tip state y(L) against the attachment frame T and their scales.
#include "robot_shooting_model.hpp"

namespace pcr {
namespace shooting_robot {

using Vec6 = Eigen::Matrix<double, 6, 1>;

struct Coupling {
  /// The 6 scaled rows at the tip state y against the attachment frame T (world).
  Vec6 (*residual)(const RodStateVector& y, const Pose& T, const RobotShootingModel& m);
  /// Unscaled row = scaled row * row_scale.
  Vec6 (*row_scale)(const RobotShootingModel& m);
};

/// The coupling of a rod end kind; throws InputError for a kind the shooting solver cannot couple.
const Coupling& coupling_of(RodEndKind kind);

/// Force and moment balance of platform k at its pose, from the tip states of its rods (rods[i].Y),
/// divided by F_s and M_s.
Vec6 platform_balance(const RobotShootingModel& m, int k, const Pose& pose);

}  // namespace shooting_robot
}  // namespace pcr
