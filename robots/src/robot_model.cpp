#include "pcr/robots/robot_model.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/robots/platform_hold_check.hpp"
#include "pcr/rods/end_axes.hpp"

namespace pcr {
namespace {

bool finite(double v) {
  return std::isfinite(v);
}

// Adds name -> index, rejecting empty and duplicate names.
void add_name(std::map<std::string, int>& table, const std::string& kind, const std::string& name,
              int index) {
  require(!name.empty(), kind, " #", index, " has an empty name");
  require(table.emplace(name, index).second, "duplicate ", kind, " name '", name, "'");
}

int find_name(const std::map<std::string, int>& table, const char* kind, const std::string& name) {
  const auto it = table.find(name);
  if (it == table.end()) throw_input_error("unknown ", kind, " '", name, "'");
  return it->second;
}

// Child frame in the joint frame for a moving joint.
Pose joint_motion(const Joint& joint, double value) {
  Pose motion;
  if (joint.type == JointType::Prismatic) {
    motion.position = value * joint.axis;
  } else if (joint.type == JointType::Revolute || joint.type == JointType::Continuous) {
    motion.orientation = quat_from_rotation_vector(value * joint.axis);
  }
  return motion;
}

}  // namespace

const char* to_string(JointType type) {
  switch (type) {
    case JointType::Fixed: return "fixed";
    case JointType::Prismatic: return "prismatic";
    case JointType::Revolute: return "revolute";
    case JointType::Continuous: return "continuous";
    case JointType::Floating: return "floating";
  }
  return "unknown";
}

const char* to_string(RodFormulationHint formulation) {
  switch (formulation) {
    case RodFormulationHint::Auto: return "auto";
    case RodFormulationHint::Primal: return "primal";
    case RodFormulationHint::Mixed: return "mixed";
  }
  return "unknown";
}

int kinematic_constraint_count(RodEndKind coupling) {
  switch (coupling) {
    case RodEndKind::Clamped: return 6;
    case RodEndKind::Collar: return 5;
    case RodEndKind::Spherical: return 3;
    case RodEndKind::Universal: return 4;
    case RodEndKind::Revolute: return 5;
    case RodEndKind::Free: return 0;
  }
  return 0;
}

RobotModel::RobotModel(std::string name, std::vector<Link> links, std::vector<Joint> joints,
                       std::vector<Platform> platforms, std::vector<RodElement> rods,
                       std::vector<ExternalLoad> loads, const Vec3& gravity)
    : name_(std::move(name)),
      links_(std::move(links)),
      joints_(std::move(joints)),
      platforms_(std::move(platforms)),
      rods_(std::move(rods)),
      loads_(std::move(loads)),
      gravity_(gravity) {
  require(gravity_.allFinite(), "gravity is not finite: [", gravity_.transpose(), "]");
  build_tables();
  build_rods();
  check_platforms_held(*this);
}

void RobotModel::build_tables() {
  const int n_links = static_cast<int>(links_.size());
  require(n_links > 0, "robot '", name_, "' has no links");
  for (int i = 0; i < n_links; ++i) add_name(link_names_, "link", links_[i].name, i);
  for (int j = 0; j < static_cast<int>(joints_.size()); ++j)
    add_name(joint_names_, "joint", joints_[j].name, j);

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

  // Joints: axes, limits, defaults, value indices.
  joint_value_count_ = 0;
  const double inf = std::numeric_limits<double>::infinity();
  for (Joint& joint : joints_) {
    require(joint.origin.position.allFinite() && joint.origin.orientation.allFinite() &&
                joint.origin.orientation.norm() > 0.0,
            "joint '", joint.name, "': origin is not a finite pose");
    joint.origin.orientation.normalize();
    joint.value_index = -1;
    if (joint.type == JointType::Fixed || joint.type == JointType::Floating) continue;
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
    require(finite(joint.default_value) && joint.default_value >= joint.lower &&
                joint.default_value <= joint.upper,
            "joint '", joint.name, "': default value ", joint.default_value, " is outside [", joint.lower,
            ", ", joint.upper, "]");
    joint.value_index = joint_value_count_++;
  }

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

  // Loads on links carried by a platform.
  for (const ExternalLoad& load : loads_) {
    require(load.link >= 0 && load.link < n_links, "pcr_load: link index ", load.link, " out of range");
    require(carrying_platform_[load.link] >= 0, "pcr_load on link '", links_[load.link].name,
            "': the link is not carried by a platform, so the load would act on the fixed world");
    require(load.point.allFinite() && load.force.allFinite() && load.torque.allFinite(), "pcr_load on link '",
            links_[load.link].name, "': point, force or torque is not finite");
  }
}

void RobotModel::build_rods() {
  const int n_links = static_cast<int>(links_.size());
  for (int r = 0; r < static_cast<int>(rods_.size()); ++r) add_name(rod_names_, "pcr_rod", rods_[r].name, r);

  const VecX q0 = default_joint_values();
  const std::vector<Pose> poses0 = initial_platform_poses();
  for (RodElement& element : rods_) {
    const std::string& name = element.name;
    const std::pair<RodAttachment*, const char*> ends[] = {{&element.start, "start"}, {&element.end, "end"}};
    for (const auto& [end, which] : ends) {
      if (end->coupling == RodEndKind::Free) {
        if (end->link >= 0) {
          throw_input_error("pcr_rod '", name, "': free ", which,
                            " must not be attached to a link (link index ", end->link, ")");
        }
      } else {
        require(end->link >= 0 && end->link < n_links, "pcr_rod '", name, "': ", which, " link index ",
                end->link, " out of range");
        require(end->frame.position.allFinite() && end->frame.orientation.allFinite() &&
                    end->frame.orientation.norm() > 0.0,
                "pcr_rod '", name, "': ", which, " frame is not a finite pose");
        end->frame.orientation.normalize();
      }
    }
    // A clamped end, a universal joint or a pin not along the tangent holds the rod's twist (end_axes.hpp).
    require(
        holds_twist(element.start.coupling, element.start.axis) ||
            holds_twist(element.end.coupling, element.end.axis),
        "pcr_rod '", name, "': couplings start = ", to_string(element.start.coupling),
        ", end = ", to_string(element.end.coupling),
        " leave the rod free to move or twist about its tangent; clamp at least one end, or hold one by a "
        "universal coupling or a revolute coupling whose axis is not along the rod");
    require(element.start.link < 0 || element.start.link != element.end.link, "pcr_rod '", name,
            "': both ends are on link '", element.start.link >= 0 ? links_[element.start.link].name : "",
            "'; a rod must join two different links");
    if (element.length_actuated) {
      require(finite(element.length_lower) && finite(element.length_upper) && element.length_lower > 0.0 &&
                  element.length_lower <= element.length_upper,
              "pcr_rod '", name, "': length bounds lower = ", element.length_lower,
              ", upper = ", element.length_upper, " must be finite with 0 < lower <= upper");
      require(finite(element.length_default) && element.length_default >= element.length_lower &&
                  element.length_default <= element.length_upper,
              "pcr_rod '", name, "': default length ", element.length_default, " is outside [",
              element.length_lower, ", ", element.length_upper, "]");
    } else {
      require(finite(element.length_default) && element.length_default > 0.0, "pcr_rod '", name,
              "': length = ", element.length_default, " must be positive and finite");
      element.length_lower = element.length_upper = element.length_default;
    }
    require(element.degree == 0 || element.degree >= 2, "pcr_rod '", name, "': degree = ", element.degree,
            " must be >= 2 (or 0 for the solver's choice)");
    require(element.elements >= 0, "pcr_rod '", name, "': elements = ", element.elements,
            " must be >= 1 (or 0)");

    RodModel& rod = element.rod;
    rod.name = name;
    rod.length = element.length_default;
    rod.loads.gravity = gravity_;
    rod.base.kind = element.start.coupling;
    rod.tip.kind = element.end.coupling;
    const std::pair<const RodAttachment*, RodEnd*> rod_ends[] = {{&element.start, &rod.base},
                                                                 {&element.end, &rod.tip}};
    for (const auto& [attachment, rod_end] : rod_ends) {
      if (attachment->coupling == RodEndKind::Free) continue;
      const Pose world = attachment_pose(*attachment, q0, poses0);
      rod_end->position = world.position;
      rod_end->orientation = world.orientation;
    }
    rod.validate();
  }

  // Actuation inputs: rod lengths, then moving joints; names unique across both.
  inputs_.clear();
  input_names_.clear();
  for (int r = 0; r < static_cast<int>(rods_.size()); ++r) {
    const RodElement& e = rods_[r];
    if (!e.length_actuated) continue;
    inputs_.push_back(
        {e.name, ActuationInput::Kind::RodLength, r, e.length_lower, e.length_upper, e.length_default});
  }
  passive_joints_.clear();
  for (int j = 0; j < static_cast<int>(joints_.size()); ++j) {
    const Joint& joint = joints_[j];
    if (joint.value_index < 0) continue;
    if (joint.passive) {
      passive_joints_.push_back(j);
      continue;
    }
    inputs_.push_back(
        {joint.name, ActuationInput::Kind::JointValue, j, joint.lower, joint.upper, joint.default_value});
  }
  for (int i = 0; i < static_cast<int>(inputs_.size()); ++i) {
    require(input_names_.emplace(inputs_[i].name, i).second, "actuation input name '", inputs_[i].name,
            "' is used by both a rod and a joint; rename one");
  }
}

int RobotModel::link_index(const std::string& name) const {
  return find_name(link_names_, "link", name);
}
int RobotModel::joint_index(const std::string& name) const {
  return find_name(joint_names_, "joint", name);
}
int RobotModel::rod_index(const std::string& name) const {
  return find_name(rod_names_, "rod", name);
}
int RobotModel::input_index(const std::string& name) const {
  return find_name(input_names_, "actuation input", name);
}
int RobotModel::platform_index(const std::string& name) const {
  const auto it = link_names_.find(name);
  const int p = it == link_names_.end() ? -1 : platform_of_link_[it->second];
  if (p < 0) throw_input_error("unknown platform '", name, "'");
  return p;
}

int RobotModel::platform_of_link(int link) const {
  require(link >= 0 && link < static_cast<int>(links_.size()), "link index ", link, " out of range");
  return platform_of_link_[link];
}

int RobotModel::carrying_platform(int link) const {
  require(link >= 0 && link < static_cast<int>(links_.size()), "link index ", link, " out of range");
  return carrying_platform_[link];
}

VecX RobotModel::default_joint_values() const {
  VecX q(joint_value_count_);
  for (const Joint& joint : joints_) {
    if (joint.value_index >= 0) q[joint.value_index] = joint.default_value;
  }
  return q;
}

VecX RobotModel::default_input_values() const {
  VecX u(inputs_.size());
  for (std::size_t i = 0; i < inputs_.size(); ++i) u[i] = inputs_[i].default_value;
  return u;
}

std::vector<Pose> RobotModel::initial_platform_poses() const {
  std::vector<Pose> poses(platforms_.size());
  for (std::size_t p = 0; p < platforms_.size(); ++p) poses[p] = platforms_[p].initial_pose;
  return poses;
}

Pose RobotModel::link_pose(int link, const VecX& joint_values,
                           const std::vector<Pose>& platform_poses) const {
  require(link >= 0 && link < static_cast<int>(links_.size()), "link_pose: link index ", link,
          " out of range");
  require(joint_values.size() == joint_value_count_, "link_pose: ", joint_values.size(),
          " joint values given, the model has ", joint_value_count_);
  require(platform_poses.size() == platforms_.size(), "link_pose: ", platform_poses.size(),
          " platform poses given, the model has ", platforms_.size());
  // Walk up to the base or to the nearest platform, then compose downwards: T = T_top * ... * T_link.
  Pose below;  // pose of `link` in the frame of the current ancestor
  int current = link;
  while (current != base_link_) {
    const int p = platform_of_link_[current];
    if (p >= 0) return platform_poses[p] * below;
    const Joint& joint = joints_[links_[current].parent_joint];
    const double value = joint.value_index >= 0 ? joint_values[joint.value_index] : 0.0;
    below = joint.origin * joint_motion(joint, value) * below;
    current = joint.parent_link;
  }
  return below;
}

Pose RobotModel::attachment_pose(const RodAttachment& attachment, const VecX& joint_values,
                                 const std::vector<Pose>& platform_poses) const {
  require(attachment.link >= 0, "attachment_pose: the rod end is not attached to a link");
  return link_pose(attachment.link, joint_values, platform_poses) * attachment.frame;
}

}  // namespace pcr
