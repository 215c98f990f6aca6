// The dead loads on platforms and passive joints, and the unit-quaternion rows (energy_terms.hpp).
#include <algorithm>
#include <utility>

#include "energy_kinematics.hpp"
#include "energy_terms.hpp"

namespace pcr::kinematics {

PlatformLoadTerm::PlatformLoadTerm(VariableId platform, std::vector<Vec3> forces, std::vector<Vec3> points,
                                   double energy_scale)
    : ObjectiveTerm("energy.platform", {platform}),
      forces_(std::move(forces)),
      points_(std::move(points)),
      scale_(energy_scale) {}

double PlatformLoadTerm::evaluate(const double* const* values, double* const* gradients) const {
  using D = Dual<7>;
  V3<D> x;
  V4<D> Q;
  for (int i = 0; i < 3; ++i) x[i] = D::variable(values[0][i], i);
  for (int i = 0; i < 4; ++i) Q[i] = D::variable(values[0][3 + i], 3 + i);
  const M3<D> R = collocation::rotation(Q);
  D work(0.0);  // of the dead forces at the world points x + R r
  for (std::size_t k = 0; k < forces_.size(); ++k) {
    const V3<D> at = x + R * points_[k].cast<D>();
    for (int i = 0; i < 3; ++i) work += forces_[k][i] * at[i];
  }
  if (gradients && gradients[0]) {
    Eigen::Map<Eigen::Matrix<double, 7, 1>> g(gradients[0]);
    g = -work.v / scale_;
  }
  return -work.a / scale_;
}

PassiveJointTerm::PassiveJointTerm(const RobotModel& model, VecX joint_values,
                                   std::vector<VariableId> passive, double energy_scale)
    : ObjectiveTerm("energy.passive_joints", std::move(passive)),
      model_(model),
      joint_values_(std::move(joint_values)),
      scale_(energy_scale),
      sizes_(variables().size(), 1) {
  for (int l = 0; l < static_cast<int>(model.links().size()); ++l) {
    const Link& link = model.links()[l];
    if (model.moved_by_passive_joint(l) && link.mass > 0.0)
      forces_.push_back({l, link.center_of_mass, link.mass * model.gravity()});
  }
  for (const ExternalLoad& load : model.loads())
    if (model.moved_by_passive_joint(load.link)) forces_.push_back({load.link, load.point, load.force});
}

double PassiveJointTerm::evaluate(const double* const* values, double* const* gradients) const {
  const std::vector<int>& passive = model_.passive_joints();
  VecX q = joint_values_;
  for (std::size_t j = 0; j < passive.size(); ++j) q[model_.joints()[passive[j]].value_index] = values[j][0];
  const std::vector<Pose> platforms = model_.initial_platform_poses();  // unused: no platform is moved
  double energy = 0.0;
  for (std::size_t j = 0; j < passive.size(); ++j) {
    const Joint& joint = model_.joints()[passive[j]];
    const double stretch = values[j][0] - joint.rest;
    energy += 0.5 * joint.stiffness * stretch * stretch;
    if (gradients && gradients[j]) gradients[j][0] = joint.stiffness * stretch;
  }
  for (const PointForce& f : forces_) {
    const Vec3 at = model_.link_pose(f.link, q, platforms).transform_point(f.point);
    energy -= f.force.dot(at);
    if (!gradients) continue;
    for (std::size_t j = 0; j < passive.size(); ++j) {
      if (!gradients[j] || !model_.joint_moves_link(passive[j], f.link)) continue;
      // dX/dq = omega x (X - o) about the joint's world axis through its origin (revolute, continuous),
      // the world axis (prismatic).
      const Joint& joint = model_.joints()[passive[j]];
      const Pose frame = model_.link_pose(joint.parent_link, q, platforms) * joint.origin;
      const Vec3 axis = frame.rotation() * joint.axis.normalized();
      const Vec3 dx = joint.type == JointType::Prismatic ? axis : Vec3(axis.cross(at - frame.position));
      gradients[j][0] -= f.force.dot(dx);
    }
  }
  if (gradients)
    for (std::size_t j = 0; j < passive.size(); ++j)
      if (gradients[j]) gradients[j][0] /= scale_;
  return energy / scale_;
}

UnitQuaternionRow::UnitQuaternionRow(VariableId block)
    : ResidualBlock("energy.unit_quaternion", "", 1, {block}) {}

void UnitQuaternionRow::evaluate(const double* const* values, double* residual,
                                 double* const* jacobians) const {
  const Eigen::Map<const Quat> Q(values[0] + 3);
  residual[0] = Q.squaredNorm() - 1.0;
  if (!jacobians || !jacobians[0]) return;
  for (int i = 0; i < 3; ++i) jacobians[0][i] = 0.0;
  for (int i = 0; i < 4; ++i) jacobians[0][3 + i] = 2.0 * Q[i];
}

void UnitQuaternionRow::evaluate_hessian(const double* const*, const double* weights, double* hessian) const {
  std::fill(hessian, hessian + 49, 0.0);
  for (int i = 3; i < 7; ++i) hessian[i * 7 + i] = 2.0 * weights[0];  // d^2 |Q|^2 / dQ^2 = 2 I
}

}  // namespace pcr::kinematics
