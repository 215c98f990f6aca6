#pragma once
// Immutable description of a parallel continuum robot (docs/design.md §3): the URDF link tree (fixed base,
// actuated joints, floating platforms), the Cosserat rods joining links, gravity, external loads and the
// actuation inputs. Built by the URDF loader (urdf_loader.hpp) or in code; the solver keeps its own
// per-evaluation buffers. SI units; "world" is the frame of the base (root) link.
#include <map>
#include <string>
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/robots/pose.hpp"
#include "pcr/rods/obstacle.hpp"
#include "pcr/rods/rod_model.hpp"

namespace pcr {

struct Link {
  std::string name;
  int parent_joint = -1;  ///< index into RobotModel::joints(); -1 for the base (root) link
  /// URDF <inertial> of a link that is neither a platform nor carried by one [kg], centre of mass in the
  /// link frame [m]: its weight loads the passive joints between it and the world. Unused on links no
  /// passive joint moves (the base or the actuators carry that weight).
  double mass = 0.0;
  Vec3 center_of_mass = Vec3::Zero();
};

enum class JointType { Fixed, Prismatic, Revolute, Continuous, Floating };
const char* to_string(JointType type);

/// A URDF joint. The child link frame is origin * motion(value) in the parent link frame, with
/// motion = translation value * axis (prismatic) or rotation by value about axis (revolute,
/// continuous); fixed joints have no value; a floating joint's child is a Platform whose world pose
/// is an unknown of the assembly.
struct Joint {
  std::string name;
  JointType type = JointType::Fixed;
  int parent_link = -1;
  int child_link = -1;
  Pose origin;                      ///< joint frame in the parent link frame
  Vec3 axis = Vec3::UnitX();        ///< unit vector in the joint frame
  double lower = 0.0, upper = 0.0;  ///< URDF limits [m or rad]; +-infinity for continuous joints
  double default_value = 0.0;  ///< initial value, within [lower, upper] (a passive joint's initial guess)
  int value_index = -1;        ///< index into the joint-value vector (moving joints only), else -1
  /// A passive joint is not an input: its value is an unknown of the assembly, balanced by the
  /// generalised force of everything beyond it (rods, loads, weights) and its spring,
  /// Q_beyond - stiffness (q - rest) = 0 [N or N m; stiffness in N/m or N m/rad].
  bool passive = false;
  double stiffness = 0.0;
  double rest = 0.0;
  /// Whether value lies within [lower, upper] (a passive joint's limits are not enforced by the solve).
  bool within_limits(double value) const { return value >= lower && value <= upper; }
};

/// A link whose parent joint is floating: its world pose (position x, unit quaternion Q) is unknown.
struct Platform {
  std::string name;  ///< the link's name
  int link = -1;
  int joint = -1;                      ///< the floating joint
  double mass = 0.0;                   ///< [kg], from the link's URDF <inertial>
  Vec3 center_of_mass = Vec3::Zero();  ///< in the platform link frame [m]
  Pose initial_pose;  ///< world pose guess: parent pose (default inputs) * floating joint origin
};

/// How a rod end is held. `link` = -1 only for a free (unattached) end.
struct RodAttachment {
  int link = -1;
  Pose frame;  ///< rod end frame in the link frame (its z axis is the rod tangent d3)
  RodEndKind coupling = RodEndKind::Free;
  Vec3 axis = Vec3::UnitX();  ///< universal: first joint axis; revolute: pin axis (unit, in `frame`)
};

enum class RodFormulationHint { Auto, Primal, Mixed };
const char* to_string(RodFormulationHint formulation);

struct RodElement {
  std::string name;
  /// Material, section, intrinsic strains and gravity filled; length = the fixed or default length;
  /// base/tip kinds = the couplings; base/tip positions and orientations = the attachment world
  /// frames at the default inputs and initial platform poses (the assembly overwrites them); free-end
  /// loads (world frame) in base/tip force and moment.
  RodModel rod;
  RodAttachment start;  ///< s = 0
  RodAttachment end;    ///< s = L
  bool length_actuated = false;
  double length_lower = 0.0, length_upper = 0.0, length_default = 0.0;  ///< [m]
  RodFormulationHint formulation = RodFormulationHint::Auto;  ///< discretisation hints; 0 = solver's choice
  int degree = 0;
  int elements = 0;
  /// Obstacles the rod may touch (indices into RobotModel::obstacles(); docs/contact.md) and its contact
  /// radius [m] (the section's outer radius unless given).
  std::vector<int> obstacles;
  double contact_radius = 0.0;
};

/// A rigid obstacle (<pcr_obstacle>): its geometry in the frame of `link` (the base link: the world).
struct ObstacleElement {
  Obstacle obstacle;
  int link = -1;
};

/// A dead wrench on a link carried by a platform or moved by a passive joint: force and torque in the
/// world frame, force applied at `point` (link frame).
struct ExternalLoad {
  int link = -1;
  Vec3 point = Vec3::Zero();
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
};

struct ActuationInput {
  enum class Kind { RodLength, JointValue };
  std::string name;  ///< the rod's or the joint's name
  Kind kind = Kind::RodLength;
  int index = -1;  ///< rod index or joint index
  double lower = 0.0, upper = 0.0, default_value = 0.0;
};

/// Number of kinematic constraints a coupling puts on the relative motion of the two links a rod joins
/// (the Dirichlet part of its 7 end equations, docs/design.md §1): clamped 6, collar 5, revolute 5,
/// universal 4, spherical 3, free 0.
int kinematic_constraint_count(RodEndKind coupling);

/// Empty when one end of the rod holds its twist about the tangent (clamped, universal, or revolute
/// with the pin axis not along the tangent), else the reason, naming both couplings.
std::string twist_rule_violation(const RodElement& rod);

class RobotModel {
 public:
  RobotModel() = default;
  /// Validates the cross references (one root, a tree, indices in range, unique names, limits,
  /// every rod well-posed, every platform held) and derives platforms' initial poses, actuation inputs
  /// and name tables. `platforms` need only link, mass and center_of_mass; throws InputError.
  RobotModel(std::string name, std::vector<Link> links, std::vector<Joint> joints,
             std::vector<Platform> platforms, std::vector<RodElement> rods, std::vector<ExternalLoad> loads,
             const Vec3& gravity, std::vector<ObstacleElement> obstacles = {});

  const std::string& name() const { return name_; }
  const std::vector<Link>& links() const { return links_; }
  const std::vector<Joint>& joints() const { return joints_; }
  const std::vector<Platform>& platforms() const { return platforms_; }
  const std::vector<RodElement>& rods() const { return rods_; }
  const std::vector<ExternalLoad>& loads() const { return loads_; }
  const std::vector<ObstacleElement>& obstacles() const { return obstacles_; }
  /// Order: actuated rod lengths (rod order), then moving joints that are not passive (joint order).
  const std::vector<ActuationInput>& inputs() const { return inputs_; }
  /// Indices (into joints()) of the passive joints, in joint order.
  const std::vector<int>& passive_joints() const { return passive_joints_; }
  const Vec3& gravity() const { return gravity_; }
  int base_link() const { return base_link_; }

  /// Index look-ups; throw InputError naming the unknown name.
  int link_index(const std::string& name) const;
  int joint_index(const std::string& name) const;
  int rod_index(const std::string& name) const;
  int platform_index(const std::string& name) const;  ///< by the platform link's name
  int input_index(const std::string& name) const;
  /// Platform index of a link that is a platform, else -1.
  int platform_of_link(int link) const;
  /// The platform whose motion carries this link (nearest platform ancestor, itself included), or
  /// -1 for links fixed to the world (possibly through actuated joints).
  int carrying_platform(int link) const;

  /// Whether the value of `joint` moves `link`: the joint lies on the link's path from the world with no
  /// floating joint between them (a platform is not moved by the joints above it).
  bool joint_moves_link(int joint, int link) const;
  /// Whether a passive joint moves `link` (loads and link masses there load that joint).
  bool moved_by_passive_joint(int link) const;

  /// Joint-value vector: one entry per moving (prismatic, revolute, continuous) joint, see
  /// Joint::value_index.
  int joint_value_count() const { return joint_value_count_; }
  VecX default_joint_values() const;
  VecX default_input_values() const;
  std::vector<Pose> initial_platform_poses() const;

  /// World pose of a link: forward kinematics over the URDF tree with the given joint values and
  /// platform world poses (platform_poses[i] for platforms()[i]). Throws InputError on size mismatch.
  Pose link_pose(int link, const VecX& joint_values, const std::vector<Pose>& platform_poses) const;
  /// World frame of a rod end attachment (link pose * attachment frame); the end must be attached.
  Pose attachment_pose(const RodAttachment& attachment, const VecX& joint_values,
                       const std::vector<Pose>& platform_poses) const;

  /// Assembly counts (docs/design.md §3): each platform adds 7 unknowns (x, Q) and 7 equations (6 balance +
  /// |Q|^2 = 1); each rod end adds 7 boundary/coupling equations, of which kinematic_constraint_count
  /// hold the links together.
  int platform_unknown_count() const { return 7 * static_cast<int>(platforms_.size()); }
  int platform_equation_count() const { return 7 * static_cast<int>(platforms_.size()); }

 private:
  void build_tables();  // the steps below, in order (robot_model_tables.cpp)
  void build_link_tree();
  void build_joint_values();
  void build_platform_tables();
  void build_passive_tables();
  void set_initial_platform_poses();
  void check_loads();
  void build_rods();
  void build_inputs();  // rod lengths, then moving joints that are not passive
  void check_passive_joints_loaded() const;

  std::string name_;
  std::vector<Link> links_;
  std::vector<Joint> joints_;
  std::vector<Platform> platforms_;
  std::vector<RodElement> rods_;
  std::vector<ExternalLoad> loads_;
  std::vector<ObstacleElement> obstacles_;
  std::vector<ActuationInput> inputs_;
  std::vector<int> passive_joints_;
  Vec3 gravity_ = Vec3::Zero();
  int base_link_ = -1;
  int joint_value_count_ = 0;
  std::vector<int> platform_of_link_;
  std::vector<int> carrying_platform_;
  std::vector<bool> passive_ancestor_;  ///< per link: a passive joint on its path from the world
  std::map<std::string, int> link_names_, joint_names_, rod_names_, input_names_;
};

}  // namespace pcr
