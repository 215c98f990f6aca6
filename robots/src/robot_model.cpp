#include "pcr/robots/robot_model.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include "model_name_table.hpp"
#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/robots/platform_hold_check.hpp"
#include "pcr/rods/end_axes.hpp"

namespace pcr {
namespace {

using model_checks::add_name;
using model_checks::finite;

int find_name(const std::map<std::string, int>& table, const char* kind, const std::string& name) {
  const auto it = table.find(name);
  if (it == table.end()) throw_input_error("unknown ", kind, " '", name, "'");
  return it->second;
}

// The joint axis of a universal or revolute attachment: finite, non-zero (normalised here), a universal
// one not along the attachment z axis (the rod tangent).
void check_joint_axis(const std::string& rod, const char* which, RodAttachment& end) {
  if (end.coupling != RodEndKind::Universal && end.coupling != RodEndKind::Revolute) return;
  require(end.axis.allFinite() && end.axis.norm() > 1e-12, "pcr_rod '", rod, "': ", which, " ",
          to_string(end.coupling), " axis = [", end.axis.transpose(), "] must be a finite non-zero vector");
  end.axis.normalize();
  require(end.coupling != RodEndKind::Universal || sine_to_tangent(end.axis) >= kMinJointAxisSine,
          "pcr_rod '", rod, "': ", which, " universal axis = [", end.axis.transpose(),
          "] lies along the attachment z axis (the rod tangent); the first joint axis must be normal to it");
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

// Attachments (links, finite frames, joint axes), the twist rule, lengths and discretisation hints of
// one rod; normalises the frames and axes.
void check_rod_element(RodElement& element, const std::vector<Link>& links) {
  const int n_links = static_cast<int>(links.size());
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
    check_joint_axis(name, which, *end);
  }
  const std::string twist = twist_rule_violation(element);
  require(twist.empty(), "pcr_rod '", name, "': ", twist);
  require(element.start.link < 0 || element.start.link != element.end.link, "pcr_rod '", name,
          "': both ends are on link '", element.start.link >= 0 ? links[element.start.link].name : "",
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

std::string twist_rule_violation(const RodElement& rod) {
  if (holds_twist(rod.start.coupling, rod.start.axis) || holds_twist(rod.end.coupling, rod.end.axis))
    return {};
  return std::string("couplings start = ") + to_string(rod.start.coupling) +
         ", end = " + to_string(rod.end.coupling) +
         " leave the rod free to move or twist about its tangent; clamp at least one end, or hold one by a "
         "universal coupling or a revolute coupling whose axis is not along the rod";
}

RobotModel::RobotModel(std::string name, std::vector<Link> links, std::vector<Joint> joints,
                       std::vector<Platform> platforms, std::vector<RodElement> rods,
                       std::vector<ExternalLoad> loads, const Vec3& gravity,
                       std::vector<ObstacleElement> obstacles)
    : name_(std::move(name)),
      links_(std::move(links)),
      joints_(std::move(joints)),
      platforms_(std::move(platforms)),
      rods_(std::move(rods)),
      loads_(std::move(loads)),
      obstacles_(std::move(obstacles)),
      gravity_(gravity) {
  require(gravity_.allFinite(), "gravity is not finite: [", gravity_.transpose(), "]");
  build_tables();
  build_rods();
  check_passive_joints_loaded();
  check_platforms_held(*this);
}

void RobotModel::build_rods() {
  for (int r = 0; r < static_cast<int>(rods_.size()); ++r) add_name(rod_names_, "pcr_rod", rods_[r].name, r);

  const VecX q0 = default_joint_values();
  const std::vector<Pose> poses0 = initial_platform_poses();
  for (RodElement& element : rods_) {
    check_rod_element(element, links_);
    RodModel& rod = element.rod;
    rod.name = element.name;
    rod.length = element.length_default;
    rod.loads.gravity = gravity_;
    rod.base.kind = element.start.coupling;
    rod.tip.kind = element.end.coupling;
    rod.base.axis = element.start.axis;
    rod.tip.axis = element.end.axis;
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
  build_inputs();
}

void RobotModel::build_inputs() {
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

void RobotModel::check_passive_joints_loaded() const {
  for (int j : passive_joints_) {
    bool loaded = false;
    for (const RodElement& rod : rods_)
      for (const RodAttachment* end : {&rod.start, &rod.end})
        loaded = loaded || (end->link >= 0 && joint_moves_link(j, end->link));
    for (const ExternalLoad& load : loads_) loaded = loaded || joint_moves_link(j, load.link);
    for (int l = 0; l < static_cast<int>(links_.size()); ++l)
      loaded = loaded || (links_[l].mass > 0.0 && !gravity_.isZero(0.0) && joint_moves_link(j, l));
    require(loaded, "passive joint '", joints_[j].name,
            "': nothing is attached beyond it (no rod end, pcr_load ", "or link mass under gravity on link '",
            links_[joints_[j].child_link].name,
            "' or the links it carries), so nothing determines its value");
  }
}

bool RobotModel::joint_moves_link(int joint, int link) const {
  require(joint >= 0 && joint < static_cast<int>(joints_.size()), "joint index ", joint, " out of range");
  require(link >= 0 && link < static_cast<int>(links_.size()), "link index ", link, " out of range");
  for (int l = link; l != base_link_; l = joints_[links_[l].parent_joint].parent_link) {
    if (links_[l].parent_joint == joint) return true;
    if (joints_[links_[l].parent_joint].type == JointType::Floating) return false;
  }
  return false;
}

bool RobotModel::moved_by_passive_joint(int link) const {
  require(link >= 0 && link < static_cast<int>(links_.size()), "link index ", link, " out of range");
  return passive_ancestor_[link];
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
