// Unknown and residual layout of the shooting robot solver (see unknown_layout.hpp).
#include "unknown_layout.hpp"

#include "pcr/math/quaternion.hpp"

namespace pcr {
namespace shooting_robot {

UnknownLayout::UnknownLayout(const RobotShootingModel& m, bool ik) : ik_(ik) {
  add_unknowns(UnknownKind::RodBase, m.num_rods(), 6);
  if (ik)
    add_unknowns(UnknownKind::InputValue, static_cast<int>(m.model->inputs().size()), 1);
  else
    add_unknowns(UnknownKind::PlatformPose, m.num_platforms(), 6);
  add_unknowns(UnknownKind::PassiveJoint, m.num_passive(), 1);
  add_rows(ResidualKind::RodCoupling, m.num_rods(), 6);
  add_rows(ResidualKind::PlatformBalance, m.num_platforms(), 6);
  add_rows(ResidualKind::PassiveBalance, m.num_passive(), 1);
}

void UnknownLayout::add_unknowns(UnknownKind kind, int count, int size) {
  std::vector<int>& first = first_of_kind_[static_cast<int>(kind)];
  for (int i = 0; i < count; ++i) {
    first.push_back(num_unknowns_);
    unknowns_.push_back({kind, i, num_unknowns_, size});
    num_unknowns_ += size;
  }
}

void UnknownLayout::add_rows(ResidualKind kind, int count, int size) {
  std::vector<int>& first = first_row_of_kind_[static_cast<int>(kind)];
  for (int i = 0; i < count; ++i) {
    first.push_back(num_residuals_);
    residuals_.push_back({kind, i, num_residuals_, size});
    num_residuals_ += size;
  }
}

int UnknownLayout::column(UnknownKind kind, int index) const {
  const std::vector<int>& first = first_of_kind_[static_cast<int>(kind)];
  return index >= 0 && index < static_cast<int>(first.size()) ? first[index] : -1;
}

int UnknownLayout::row(ResidualKind kind, int index) const {
  return first_row_of_kind_[static_cast<int>(kind)][index];
}

void UnknownLayout::retract(const RobotShootingModel& m, const State& s, const VecX& dz, State& out) const {
  out = s;
  for (const UnknownBlock& b : unknowns_) {
    switch (b.kind) {
      case UnknownKind::RodBase:
        out.base[b.index] += m.rods[b.index].unknown_scale.cwiseProduct(dz.segment<6>(b.offset));
        break;
      case UnknownKind::PlatformPose: {
        Pose& pose = out.poses[b.index];
        pose.position += m.Ls * dz.segment<3>(b.offset);
        // World rotation vector increment: R <- exp(hat(dtheta)) R.
        pose.orientation = quat_multiply(quat_from_rotation_vector(dz.segment<3>(b.offset + 3)),
                                         s.poses[b.index].orientation)
                               .normalized();
        break;
      }
      case UnknownKind::InputValue: out.inputs[b.index] += m.input_scale[b.index] * dz[b.offset]; break;
      case UnknownKind::PassiveJoint:
        out.passive[b.index] += m.passive[b.index].unknown_scale * dz[b.offset];
        break;
    }
  }
}

}  // namespace shooting_robot
}  // namespace pcr
