// RobotModel's tables, built and checked once at construction (robot_model.cpp calls build_tables):
// the link tree, joint values, platforms and the links they carry, passive joints, initial platform
// poses and loads. Each step throws InputError naming the element and value.
#include <cmath>
#include <limits>

#include "model_name_table.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/robot_model.hpp"

namespace pcr {
namespace {

using model_checks::add_name;
using model_checks::finite;

}  // namespace

void RobotModel::build_tables() {
  require(!links_.empty(), "robot '", name_, "' has no links");
  for (int i = 0; i < static_cast<int>(links_.size()); ++i) add_name(link_names_, "link", links_[i].name, i);
  for (int j = 0; j < static_cast<int>(joints_.size()); ++j)
    add_name(joint_names_, "joint", joints_[j].name, j);
  build_link_tree();
  build_joint_values();
  build_platform_tables();
  build_passive_tables();
  set_initial_platform_poses();
  check_loads();
}

void RobotModel::build_link_tree() {
  const int n_links = static_cast<int>(links_.size());
  // Tree: every link has at most one parent joint, exactly one link has none, no cycles.
  for (Link& link : links_) link.parent_joint = -1;
  for (int j = 0; j < static_cast<int>(joints_.size()); ++j) {
    Joint& joint = joints_[j];
    require(joint.parent_link >= 0 && joint.parent_link < n_links, "joint '", joint.name,
            "': parent link index ", joint.parent_link, " out of range");
    require(joint.child_link >= 0 && joint.child_link < n_links, "joint '", joint.name,
            "': child link index ", joint.child_link, " out of range");
    require(joint.parent_link != joint.child_link, "joint '", joint.name,
            "': parent and child are the same link '", links_[joint.child_link].name, "'");
    Link& child = links_[joint.child_link];
    require(child.parent_joint < 0, "link '", child.name, "' is the child of two joints ('",
            child.parent_joint >= 0 ? joints_[child.parent_joint].name : "", "' and '", joint.name, "')");
    child.parent_joint = j;
  }
  base_link_ = -1;
  for (int i = 0; i < n_links; ++i) {
    if (links_[i].parent_joint >= 0) continue;
    require(base_link_ < 0, "the link tree has several roots: '",
            base_link_ >= 0 ? links_[base_link_].name : "", "' and '", links_[i].name,
            "' (join them with a fixed joint)");
    base_link_ = i;
  }
  require(base_link_ >= 0, "the link tree has no root (the joints form a cycle)");
  for (int i = 0; i < n_links; ++i) {
    int link = i;
    for (int steps = 0; link != base_link_; ++steps) {
      require(steps < n_links, "link '", links_[i].name,
              "' is on a cycle of joints and not connected to the base '", links_[base_link_].name, "'");
      link = joints_[links_[link].parent_joint].parent_link;
    }
  }

  for (const Link& link : links_) {
    require(finite(link.mass) && link.mass >= 0.0, "link '", link.name, "': mass = ", link.mass,
            " must be non-negative and finite");
    require(link.center_of_mass.allFinite(), "link '", link.name, "': center of mass is not finite");
  }
}

void RobotModel::build_joint_values() {
  // Joints: axes, limits, defaults, value indices.
  joint_value_count_ = 0;
  const double inf = std::numeric_limits<double>::infinity();
  for (Joint& joint : joints_) {
    require(joint.origin.position.allFinite() && joint.origin.orientation.allFinite() &&
                joint.origin.orientation.norm() > 0.0,
            "joint '", joint.name, "': origin is not a finite pose");
    joint.origin.orientation.normalize();
    joint.value_index = -1;
    if (joint.type == JointType::Fixed || joint.type == JointType::Floating) {
      require(!joint.passive, "joint '", joint.name, "': a ", to_string(joint.type),
              " joint cannot be passive (it has no value)");
      continue;
    }
    if (joint.passive) {
      require(finite(joint.stiffness) && joint.stiffness >= 0.0, "passive joint '", joint.name,
              "': stiffness = ", joint.stiffness, " must be non-negative and finite");
      require(finite(joint.rest), "passive joint '", joint.name, "': rest = ", joint.rest, " is not finite");
    }
    require(joint.axis.allFinite() && joint.axis.norm() > 1e-12, "joint '", joint.name, "': axis = [",
            joint.axis.transpose(), "] is not a non-zero vector");
    joint.axis.normalize();
    if (joint.type == JointType::Continuous) {
      joint.lower = -inf;
      joint.upper = inf;
    } else {
      require(finite(joint.lower) && finite(joint.upper) && joint.lower <= joint.upper, "joint '", joint.name,
              "': limits lower = ", joint.lower, ", upper = ", joint.upper,
              " must be finite with lower <= upper");
    }
    require(finite(joint.default_value) && joint.within_limits(joint.default_value), "joint '", joint.name,
            "': default value ", joint.default_value, " is outside [", joint.lower, ", ", joint.upper, "]");
    joint.value_index = joint_value_count_++;
  }
}

void RobotModel::build_platform_tables() {
  const int n_links = static_cast<int>(links_.size());
  // Platforms: exactly the children of floating joints.
  platform_of_link_.assign(n_links, -1);
  for (int p = 0; p < static_cast<int>(platforms_.size()); ++p) {
    Platform& platform = platforms_[p];
    require(platform.link >= 0 && platform.link < n_links, "platform #", p, ": link index ", platform.link,
            " out of range");
    const Link& link = links_[platform.link];
    require(link.parent_joint >= 0 && joints_[link.parent_joint].type == JointType::Floating, "platform '",
            link.name, "': its parent joint is not floating");
    require(platform_of_link_[platform.link] < 0, "link '", link.name, "' is listed as a platform twice");
    require(finite(platform.mass) && platform.mass >= 0.0, "platform '", link.name,
            "': mass = ", platform.mass, " must be non-negative and finite");
    require(platform.center_of_mass.allFinite(), "platform '", link.name, "': center of mass is not finite");
    platform.name = link.name;
    platform.joint = link.parent_joint;
    platform_of_link_[platform.link] = p;
  }
  for (const Joint& joint : joints_) {
    require(joint.type != JointType::Floating || platform_of_link_[joint.child_link] >= 0, "floating joint '",
            joint.name, "': its child link '", links_[joint.child_link].name,
            "' is not listed as a platform");
  }
  carrying_platform_.assign(n_links, -1);
  for (int i = 0; i < n_links; ++i) {
    for (int link = i; link != base_link_; link = joints_[links_[link].parent_joint].parent_link) {
      if (platform_of_link_[link] >= 0) {
        carrying_platform_[i] = platform_of_link_[link];
        break;
      }
    }
  }
}

void RobotModel::build_passive_tables() {
  const int n_links = static_cast<int>(links_.size());
  for (const Joint& joint : joints_) {
    const int carrier = carrying_platform_[joint.child_link];
    require(!joint.passive || carrier < 0, "passive joint '", joint.name, "': it is carried by platform '",
            carrier >= 0 ? platforms_[carrier].name : "",
            "'; passive joints are supported between the world and rod attachments, not below a platform");
  }
  passive_ancestor_.assign(n_links, false);
  for (int i = 0; i < n_links; ++i) {
    for (int link = i; link != base_link_ && carrying_platform_[i] < 0;
         link = joints_[links_[link].parent_joint].parent_link)
      if (joints_[links_[link].parent_joint].passive) passive_ancestor_[i] = true;
  }
}

void RobotModel::set_initial_platform_poses() {
  // Initial platform poses, parents first: platform p's parent pose depends only on platforms above it.
  std::vector<bool> done(platforms_.size(), false);
  const VecX q0 = default_joint_values();
  for (std::size_t round = 0; round < platforms_.size(); ++round) {
    for (std::size_t p = 0; p < platforms_.size(); ++p) {
      if (done[p]) continue;
      const Joint& joint = joints_[platforms_[p].joint];
      const int above = carrying_platform_[joint.parent_link];
      if (above >= 0 && !done[above]) continue;
      const std::vector<Pose> poses = initial_platform_poses();
      platforms_[p].initial_pose = link_pose(joint.parent_link, q0, poses) * joint.origin;
      done[p] = true;
    }
  }
}

void RobotModel::check_loads() {
  const int n_links = static_cast<int>(links_.size());
  // Loads on links carried by a platform.
  for (const ExternalLoad& load : loads_) {
    require(load.link >= 0 && load.link < n_links, "pcr_load: link index ", load.link, " out of range");
    require(carrying_platform_[load.link] >= 0 || passive_ancestor_[load.link], "pcr_load on link '",
            links_[load.link].name,
            "': the link is not carried by a platform or moved by a passive joint, so the load would act "
            "on the fixed world");
    require(load.point.allFinite() && load.force.allFinite() && load.torque.allFinite(), "pcr_load on link '",
            links_[load.link].name, "': point, force or torque is not finite");
  }
}

}  // namespace pcr
