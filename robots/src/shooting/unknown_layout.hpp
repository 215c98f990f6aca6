#pragma once
// Private to the shooting robot solver: the unknowns and residual rows of one solve as tables of
// blocks. Unknowns (scaled: dz = 1 moves a block by one of its scales):
//   RodBase       (per rod, 6):      the six base unknowns (State::base) += RodSetup::unknown_scale dz
//                                    (F_s for forces, M_s for moments, 1 rad for joint angles)
//   PlatformPose  (per platform, 6; FK): x += L_s dz[0..3), R <- exp(hat(dz[3..6))) R (world frame)
//   InputValue    (per input, 1; IK):    u += (L_s or 1 rad) dz (fed rod lengths, joint values)
//   PassiveJoint  (per passive joint, 1): q += (L_s or 1 rad) dz
// Residual rows: RodCoupling (per rod, 6: the tip coupling of its kind, coupling_residuals.hpp),
// PlatformBalance (per platform, 6: force and moment balance) and PassiveBalance (per passive joint, 1:
// its generalised force balance).
// A new kind of unknown is one more UnknownKind with its block size, its retraction in retract() and
// its Jacobian columns; a new kind of rows one more ResidualKind.
#include <vector>

#include "robot_shooting_model.hpp"

namespace pcr {
namespace shooting_robot {

enum class UnknownKind { RodBase, PlatformPose, InputValue, PassiveJoint };
enum class ResidualKind { RodCoupling, PlatformBalance, PassiveBalance };

struct UnknownBlock {
  UnknownKind kind;
  int index;   ///< rod, platform, input or passive joint (RobotShootingModel::passive)
  int offset;  ///< first column
  int size;
};

struct ResidualRows {
  ResidualKind kind;
  int index;   ///< rod, platform or passive joint
  int offset;  ///< first row
  int size;
};

class UnknownLayout {
 public:
  UnknownLayout() = default;
  /// FK (ik = false): rod base unknowns, platform poses, passive joints; IK: rod base unknowns, inputs,
  /// passive joints.
  UnknownLayout(const RobotShootingModel& m, bool ik);

  bool ik() const { return ik_; }
  int num_unknowns() const { return num_unknowns_; }
  int num_residuals() const { return num_residuals_; }
  const std::vector<UnknownBlock>& unknowns() const { return unknowns_; }
  const std::vector<ResidualRows>& residuals() const { return residuals_; }
  /// First column of a block (-1 if the layout has no such block).
  int column(UnknownKind kind, int index) const;
  /// First row of the rows of a kind for a rod, platform or passive joint.
  int row(ResidualKind kind, int index) const;
  /// out = s (+) dz, every block moved by the retraction of its kind.
  void retract(const RobotShootingModel& m, const State& s, const VecX& dz, State& out) const;

 private:
  void add_unknowns(UnknownKind kind, int count, int size);
  void add_rows(ResidualKind kind, int count, int size);

  bool ik_ = false;
  int num_unknowns_ = 0, num_residuals_ = 0;
  std::vector<UnknownBlock> unknowns_;
  std::vector<ResidualRows> residuals_;
  std::vector<int> first_of_kind_[4];  // column of each index, per UnknownKind
  std::vector<int> first_row_of_kind_[3];
};

}  // namespace shooting_robot
}  // namespace pcr
