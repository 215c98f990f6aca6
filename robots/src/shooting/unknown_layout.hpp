#pragma once
// Private to the shooting robot solver: the unknowns and residual rows of one solve as tables of
// blocks. Unknowns (scaled: dz = 1 moves a block by one of its scales):
//   RodBaseWrench  (per rod, 6):      n(0) += F_s dz[0..3), m(0) += M_s dz[3..6)
//   PlatformPose   (per platform, 6; FK): x += L_s dz[0..3), R <- exp(hat(dz[3..6))) R (world frame)
//   InputValue     (per input, 1; IK):    u += L_s dz (fed rod lengths)
// Residual rows: RodCoupling (per rod, 6: the tip coupling of its kind, coupling_residuals.hpp) and
// PlatformBalance (per platform, 6: force and moment balance).
// A new kind of unknown (e.g. a passive joint value) is one more UnknownKind with its block size, its
// retraction in retract() and its Jacobian columns; a new kind of rows one more ResidualKind.
#include <vector>

#include "robot_shooting_model.hpp"

namespace pcr {
namespace shooting_robot {

enum class UnknownKind { RodBaseWrench, PlatformPose, InputValue };
enum class ResidualKind { RodCoupling, PlatformBalance };

struct UnknownBlock {
  UnknownKind kind;
  int index;   ///< rod, platform or input
  int offset;  ///< first column
  int size;
};

struct ResidualRows {
  ResidualKind kind;
  int index;   ///< rod or platform
  int offset;  ///< first row
  int size;
};

class UnknownLayout {
 public:
  UnknownLayout() = default;
  /// FK (ik = false): rod wrenches and platform poses; IK: rod wrenches and inputs.
  UnknownLayout(const RobotShootingModel& m, bool ik);

  bool ik() const { return ik_; }
  int num_unknowns() const { return num_unknowns_; }
  int num_residuals() const { return num_residuals_; }
  const std::vector<UnknownBlock>& unknowns() const { return unknowns_; }
  const std::vector<ResidualRows>& residuals() const { return residuals_; }
  /// First column of a block (-1 if the layout has no such block).
  int column(UnknownKind kind, int index) const;
  /// First row of the rows of a kind for a rod or platform.
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
  std::vector<int> first_of_kind_[3];  // column of each index, per UnknownKind
  std::vector<int> first_row_of_kind_[2];
};

}  // namespace shooting_robot
}  // namespace pcr
