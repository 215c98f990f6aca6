#pragma once
// Balance of a passive URDF joint (internal header of pcr::robots; docs/design.md §3). The joint j
// (value q, unit axis w and origin o in the world at the current joint values) is balanced when the
// generalised force of everything beyond it equals its spring's:
//   Q - k (q - rest) = 0,   Q = w . sum_i ((x_i - o) x F_i + M_i)   (revolute, continuous)
//                           Q = w . sum_i F_i                      (prismatic),
// over the wrenches (F_i at x_i, M_i) applied to the links the joint moves: the rod ends attached there
// (a rod applies -sigma (n, m) at its end point p, sigma = +1 at s = L and -1 at s = 0), the pcr_load
// loads and the link weights (mass g at the centre of mass). A floating joint transmits nothing: the
// platforms below do not count. Scaled like the platform balance rows: by the assembly's moment scale
// (revolute) or force scale (prismatic).
#include <vector>

#include "pcr/robots/robot_model.hpp"
#include "pcr/rods/rod_end.hpp"
#include "pcr/solve/residual_block.hpp"
#include "robot_blocks.hpp"

namespace pcr::assembly {

/// A dead wrench on a link the joint moves: force at `point` (link frame), torque; world-frame vectors.
struct LinkLoad {
  int link = -1;
  Vec3 point = Vec3::Zero(), force = Vec3::Zero(), torque = Vec3::Zero();
};

class PassiveJointBlock final : public ResidualBlock {
 public:
  /// joint_variables[value_index]: the variable block of every moving joint (value_index order).
  /// Touches the joints that move the joint itself or one of the loaded links, then the rod ends'
  /// variable blocks (each once).
  PassiveJointBlock(const RobotModel& model, int joint, const std::vector<VariableId>& joint_variables,
                    std::vector<PlatformRodEnd> ends, std::vector<LinkLoad> loads, double force_scale,
                    double moment_scale);
  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override;

 private:
  struct Layout {
    std::vector<int> joints;
    std::vector<VariableId> variables;
    std::vector<std::vector<int>> end_blocks;
  };
  static Layout layout_of(const RobotModel& model, int joint, const std::vector<VariableId>& joint_variables,
                          const std::vector<PlatformRodEnd>& ends, const std::vector<LinkLoad>& loads);
  PassiveJointBlock(const RobotModel& model, int joint, Layout layout, std::vector<PlatformRodEnd>&& ends,
                    std::vector<LinkLoad>&& loads, double scale);

  const RobotModel* model_;
  int joint_;
  std::vector<int> joints_;  ///< model joint indices of the first touched blocks
  std::vector<PlatformRodEnd> ends_;
  std::vector<std::vector<int>> end_blocks_;  ///< per end: positions of its variables in variables()
  std::vector<LinkLoad> loads_;
  double scale_;
};

}  // namespace pcr::assembly
