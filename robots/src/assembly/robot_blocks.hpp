#pragma once
// Residual blocks of the robot assembly (docs/design.md §3; internal header of pcr::robots):
//  - CouplingBlock: a rod end held in a link frame (the 7 end equations of its coupling kind, with
//    the target frame = link pose * attachment, docs/design.md §1);
//  - PlatformBalanceBlock: force and moment balance of a platform about its origin, and |Q|^2 = 1;
//  - PoseTargetBlock: IK target on a platform-carried frame (position and/or orientation).
#include <array>
#include <vector>

#include "link_frame.hpp"
#include "pcr/rods/collocation/equations.hpp"
#include "pcr/rods/rod_end.hpp"
#include "platform_contact.hpp"

namespace pcr::assembly {

class CouplingBlock final : public ResidualBlock {
 public:
  /// axis: the joint axis of a universal or revolute coupling in the attachment frame (else unused).
  CouplingBlock(const std::string& name, RodEndEvaluator end, LinkFrame frame, RodEndKind kind,
                const Vec3& axis, const collocation::PointConstants& scales);
  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override;

 private:
  RodEndEvaluator end_;
  LinkFrame frame_;
  RodEndKind kind_;
  Mat3 axes_;  ///< joint_axes(axis), end_axes.hpp
  collocation::PointConstants scales_;
  int end_blocks_;
  std::vector<int> sizes_;
};

/// One rod end acting on a platform; sigma = +1 for a rod's s = L end, -1 for its s = 0 end.
struct PlatformRodEnd {
  RodEndEvaluator end;
  double sigma;
};

/// A dead wrench on the platform: force at `point` (platform frame), torque; world frame vectors.
struct PlatformLoad {
  Vec3 point = Vec3::Zero(), force = Vec3::Zero(), torque = Vec3::Zero();
};

class PlatformBalanceBlock final : public ResidualBlock {
 public:
  /// Rows: force balance / force_scale (3), moment balance about the platform origin / moment_scale
  /// (3), |Q|^2 - 1 (1):
  ///   F_ext + m g - sum sigma n_end - sum_j c_j F_j = 0
  ///   M_ext + sum (R r_load) x F_load + (R c) x m g - sum sigma (m_end + (p_end - x) x n_end)
  ///     - sum_j c_j (p_j - x) x F_j = 0
  /// (the last sums: the reaction of contact with obstacles the platform carries, platform_contact.hpp).
  /// contacts: rods touching obstacles carried by the platform; their reaction enters both balances
  /// (platform_contact.hpp).
  PlatformBalanceBlock(const std::string& name, VariableId platform, std::vector<PlatformRodEnd> ends,
                       std::vector<PlatformLoad> loads, double mass, const Vec3& center_of_mass,
                       const Vec3& gravity, double force_scale, double moment_scale,
                       std::vector<PlatformContact> contacts = {});
  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override;

 private:
  std::vector<PlatformRodEnd> ends_;
  std::vector<PlatformLoad> loads_;
  double mass_;
  Vec3 com_, gravity_;
  double force_scale_, moment_scale_;
  PlatformContactReaction contact_;
};

/// Selected pose components: position x, y, z (world) and rotation about x, y, z (target frame).
using PoseComponents = std::array<bool, 6>;

/// IK target: the selected rows of (x_f - x_t) / length_scale and 2 vec(conj(Q_t) (x) Q_f) (the
/// rotation from target to reached frame, to first order), where (x_f, Q_f) = platform pose * offset
/// and the target (x_t, Q_t) is a variable block of its own (fixed by the IK at each solve).
class PoseTargetBlock final : public ResidualBlock {
 public:
  PoseTargetBlock(const std::string& name, VariableId platform, VariableId target, const Pose& offset,
                  const PoseComponents& components, double length_scale);
  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override;

 private:
  Pose offset_;
  PoseComponents components_;
  double length_scale_;
};

}  // namespace pcr::assembly
