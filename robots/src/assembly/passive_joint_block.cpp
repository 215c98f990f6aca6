#include "passive_joint_block.hpp"

#include <algorithm>

#include "pcr/core/error.hpp"

namespace pcr::assembly {
namespace {

// A joint's unit axis w and origin o in the world at joint values q.
struct JointAxis {
  Vec3 w, o;
  bool prismatic;
};

JointAxis axis_of(const RobotModel& m, int j, const VecX& q, const std::vector<Pose>& platforms) {
  const Joint& joint = m.joints()[j];
  const Pose frame = m.link_pose(joint.parent_link, q, platforms) * joint.origin;
  return {frame.rotation() * joint.axis, frame.position, joint.type == JointType::Prismatic};
}

// Velocity of the world point x carried by joint a at unit rate: w (prismatic), w x (x - o) (revolute).
Vec3 point_rate(const JointAxis& a, const Vec3& x) {
  return a.prismatic ? a.w : Vec3(a.w.cross(x - a.o));
}

// Moving joints whose value moves the joint itself or a loaded link, in joint order.
std::vector<int> touched_joints(const RobotModel& m, int joint, const std::vector<LinkLoad>& loads) {
  std::vector<int> out;
  for (int k = 0; k < static_cast<int>(m.joints().size()); ++k) {
    if (m.joints()[k].value_index < 0) continue;
    bool moves = m.joint_moves_link(k, m.joints()[joint].child_link);
    for (const LinkLoad& l : loads) moves = moves || m.joint_moves_link(k, l.link);
    if (moves) out.push_back(k);
  }
  return out;
}

}  // namespace

PassiveJointBlock::Layout PassiveJointBlock::layout_of(const RobotModel& model, int joint,
                                                       const std::vector<VariableId>& joint_variables,
                                                       const std::vector<PlatformRodEnd>& ends,
                                                       const std::vector<LinkLoad>& loads) {
  Layout layout;
  layout.joints = touched_joints(model, joint, loads);
  for (int k : layout.joints) layout.variables.push_back(joint_variables[model.joints()[k].value_index]);
  // Both ends of one rod may lie beyond the joint and share blocks (a condensed rod's wrench and length):
  // each block is touched once.
  for (const PlatformRodEnd& e : ends) {
    std::vector<int> positions;
    for (VariableId v : e.end.variables()) {
      auto it = std::find(layout.variables.begin(), layout.variables.end(), v);
      if (it == layout.variables.end()) it = layout.variables.insert(layout.variables.end(), v);
      positions.push_back(static_cast<int>(it - layout.variables.begin()));
    }
    layout.end_blocks.push_back(std::move(positions));
  }
  return layout;
}

PassiveJointBlock::PassiveJointBlock(const RobotModel& model, int joint,
                                     const std::vector<VariableId>& joint_variables,
                                     std::vector<PlatformRodEnd> ends, std::vector<LinkLoad> loads,
                                     double force_scale, double moment_scale)
    : PassiveJointBlock(model, joint, layout_of(model, joint, joint_variables, ends, loads), std::move(ends),
                        std::move(loads),
                        model.joints()[joint].type == JointType::Prismatic ? force_scale : moment_scale) {}

// ends and loads by reference: layout_of reads them before they are moved into the members.
PassiveJointBlock::PassiveJointBlock(const RobotModel& model, int joint, Layout layout,
                                     std::vector<PlatformRodEnd>&& ends, std::vector<LinkLoad>&& loads,
                                     double scale)
    : ResidualBlock("joint.passive_balance", model.joints()[joint].name, 1, std::move(layout.variables)),
      model_(&model),
      joint_(joint),
      joints_(std::move(layout.joints)),
      ends_(std::move(ends)),
      end_blocks_(std::move(layout.end_blocks)),
      loads_(std::move(loads)),
      scale_(scale) {}

void PassiveJointBlock::evaluate(const double* const* values, double* residual,
                                 double* const* jacobians) const {
  const RobotModel& m = *model_;
  const Joint& joint = m.joints()[joint_];
  VecX q = m.default_joint_values();
  for (size_t k = 0; k < joints_.size(); ++k) q[m.joints()[joints_[k]].value_index] = values[k][0];
  const std::vector<Pose> platforms = m.initial_platform_poses();  // not on these links' paths
  const JointAxis axis = axis_of(m, joint_, q, platforms);
  // Force and moment about o of everything beyond the joint.
  Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
  std::vector<Vec3> points;
  for (const LinkLoad& l : loads_) {
    points.push_back(m.link_pose(l.link, q, platforms).transform_point(l.point));
    force += l.force;
    moment += l.torque + (points.back() - axis.o).cross(l.force);
  }
  std::vector<RodEndVector> ys(ends_.size());
  std::vector<std::vector<MatX>> dys(ends_.size());
  for (size_t e = 0; e < ends_.size(); ++e) {
    std::vector<const double*> v;
    for (int position : end_blocks_[e]) v.push_back(values[position]);
    ends_[e].end.evaluate(v.data(), ys[e], jacobians ? &dys[e] : nullptr);
    const Vec3 p = ys[e].segment<3>(0), F = -ends_[e].sigma * ys[e].segment<3>(7);
    force += F;
    moment += -ends_[e].sigma * ys[e].segment<3>(10) + (p - axis.o).cross(F);
  }
  const double generalised = axis.w.dot(axis.prismatic ? force : moment);
  residual[0] = (generalised - joint.stiffness * (q[joint.value_index] - joint.rest)) / scale_;
  if (!jacobians) return;

  // Joint values: a joint above j turns w and moves o (and the loads); one at or below j moves the loads.
  for (size_t k = 0; k < joints_.size(); ++k) {
    if (!jacobians[k]) continue;
    const JointAxis a = axis_of(m, joints_[k], q, platforms);
    double d = 0.0;
    if (m.joint_moves_link(joints_[k], joint.parent_link)) {
      const Vec3 dw = a.prismatic ? Vec3::Zero() : Vec3(a.w.cross(axis.w)), d_origin = point_rate(a, axis.o);
      d += axis.prismatic ? dw.dot(force) : dw.dot(moment) - axis.w.dot(d_origin.cross(force));
    }
    if (!axis.prismatic) {
      for (size_t i = 0; i < loads_.size(); ++i)
        if (m.joint_moves_link(joints_[k], loads_[i].link))
          d += axis.w.dot(point_rate(a, points[i]).cross(loads_[i].force));
    }
    if (joints_[k] == joint_) d -= joint.stiffness;
    jacobians[k][0] = d / scale_;
  }
  // Rod ends: dQ/dp = (F x w)^T, dQ/dn = -sigma (w x (p - o))^T, dQ/dm = -sigma w^T (revolute);
  // dQ/dn = -sigma w^T (prismatic). Blocks shared by two ends add up.
  for (size_t e = 0; e < ends_.size(); ++e)
    for (size_t b = 0; b < end_blocks_[e].size(); ++b)
      if (double* J = jacobians[end_blocks_[e][b]]) std::fill(J, J + dys[e][b].cols(), 0.0);
  for (size_t e = 0; e < ends_.size(); ++e) {
    const double sigma = ends_[e].sigma;
    const Vec3 p = ys[e].segment<3>(0), F = -sigma * ys[e].segment<3>(7);
    Eigen::Matrix<double, 1, 13> dy = Eigen::Matrix<double, 1, 13>::Zero();
    if (axis.prismatic) {
      dy.segment<3>(7) = -sigma * axis.w.transpose();
    } else {
      dy.segment<3>(0) = F.cross(axis.w).transpose();
      dy.segment<3>(7) = -sigma * axis.w.cross(p - axis.o).transpose();
      dy.segment<3>(10) = -sigma * axis.w.transpose();
    }
    dy /= scale_;
    for (size_t b = 0; b < end_blocks_[e].size(); ++b) {
      double* J = jacobians[end_blocks_[e][b]];
      if (!J) continue;
      Eigen::Map<Eigen::Matrix<double, 1, Eigen::Dynamic>>(J, dys[e][b].cols()) += dy * dys[e][b];
    }
  }
}

}  // namespace pcr::assembly
