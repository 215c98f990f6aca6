#include "link_frame.hpp"

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"

namespace pcr::assembly {
namespace {

Vec7 to_vec7(const Pose& pose) {
  Vec7 z;
  z << pose.position, pose.orientation;
  return z;
}

}  // namespace

LinkFrame LinkFrame::of(const RobotModel& model, int link, const Pose& attachment,
                        const std::vector<VariableId>& platform_variables,
                        const std::vector<VariableId>& joint_variables) {
  LinkFrame f;
  f.model = &model;
  f.link = link;
  const int platform = model.carrying_platform(link);
  // Moving joints between the link and the root (or the carrying platform).
  std::vector<int> moving;
  for (int l = link; l >= 0 && model.links()[l].parent_joint >= 0;) {
    const Joint& j = model.joints()[model.links()[l].parent_joint];
    if (j.type == JointType::Floating) break;
    if (j.value_index >= 0) moving.push_back(model.links()[l].parent_joint);
    l = j.parent_link;
  }
  const VecX q0 = model.default_joint_values();
  if (platform >= 0) {
    require(moving.empty(), "link '", model.links()[link].name, "': moving joints between a platform and a rod attachment are not supported");
    std::vector<Pose> identity(model.platforms().size());
    f.kind = Kind::Platform;
    f.offset = model.link_pose(link, q0, identity) * attachment;  // platform frame -> attachment
    f.variables = {platform_variables[platform]};
    return f;
  }
  if (moving.empty()) {
    f.kind = Kind::Constant;
    f.constant = to_vec7(model.link_pose(link, q0, model.initial_platform_poses()) * attachment);
    f.offset = Pose::identity();
    return f;
  }
  f.kind = Kind::Joints;
  f.offset = attachment;
  f.joints = moving;
  for (int j : moving) f.variables.push_back(joint_variables[model.joints()[j].value_index]);
  return f;
}

void LinkFrame::evaluate(const double* const* values, Vec7& z, MatX* dz) const {
  switch (kind) {
    case Kind::Constant:
      z = constant;
      if (dz) dz->resize(7, 0);
      return;
    case Kind::Platform:
      z = Eigen::Map<const Vec7>(values[0]);
      if (dz) *dz = MatX::Identity(7, 7);
      return;
    case Kind::Joints: {
      VecX q = model->default_joint_values();
      for (size_t k = 0; k < joints.size(); ++k) q[model->joints()[joints[k]].value_index] = values[k][0];
      const std::vector<Pose> no_platforms = model->initial_platform_poses();
      const Pose link_pose = model->link_pose(link, q, no_platforms);
      z = to_vec7(link_pose);
      if (!dz) return;
      dz->setZero(7, static_cast<int>(joints.size()));
      for (size_t k = 0; k < joints.size(); ++k) {
        const Joint& j = model->joints()[joints[k]];
        const Pose joint_frame = model->link_pose(j.parent_link, q, no_platforms) * j.origin;
        const Vec3 w = joint_frame.rotation() * j.axis;
        if (j.type == JointType::Prismatic) {
          dz->block<3, 1>(0, k) = w;
        } else {
          dz->block<3, 1>(0, k) = w.cross(link_pose.position - joint_frame.position);
          dz->block<4, 1>(3, k) = 0.5 * quat_multiply(Quat(0, w.x(), w.y(), w.z()), link_pose.orientation);
        }
      }
      return;
    }
  }
}

Pose LinkFrame::attachment_pose(const Vec7& z) const {
  Pose base;
  base.position = z.head<3>();
  base.orientation = z.tail<4>().normalized();
  return base * offset;
}

}  // namespace pcr::assembly
