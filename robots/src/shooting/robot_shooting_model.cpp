// What the shooting robot solver takes from a RobotModel (see robot_shooting_model.hpp).
#include "robot_shooting_model.hpp"

#include <algorithm>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"

namespace pcr {
namespace shooting_robot {

namespace {

// Moving joints between a link and the world, from the link up.
std::vector<int> moving_joints_above(const RobotModel& m, int link) {
  std::vector<int> joints;
  while (link != m.base_link()) {
    const int j = m.links()[link].parent_joint;
    if (m.joints()[j].value_index >= 0) joints.push_back(j);
    link = m.joints()[j].parent_link;
  }
  return joints;
}

bool contains(const std::vector<int>& v, int x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

// Joint values move only links fixed to the world: a moving joint under a platform would move rod ends,
// loads or weights in the platform frame, which the shooting solver takes as fixed.
void check_joints(const RobotModel& m) {
  for (const Joint& joint : m.joints()) {
    if (joint.value_index < 0) continue;
    const int k = m.carrying_platform(joint.child_link);
    require(k < 0, "ShootingRobotSolver: joint '", joint.name, "' moves link '",
            m.links()[joint.child_link].name, "' carried by platform '", k >= 0 ? m.platforms()[k].name : "",
            "' (moving joints on platforms are not supported by the shooting solver)");
  }
  for (const RodElement& rod : m.rods())
    require(rod.obstacles.empty(), "ShootingRobotSolver: rod '", rod.name,
            "' may touch obstacles (<contact>), which the shooting solver does not model");
}

RodSetup rod_setup(const RobotModel& m, int i, const VecX& joints, const std::vector<Pose>& poses0) {
  const RodElement& e = m.rods()[i];
  require(e.start.link >= 0, "ShootingRobotSolver: rod '", e.name,
          "' has a free start (not supported by the shooting solver)");
  require(m.carrying_platform(e.start.link) < 0, "ShootingRobotSolver: rod '", e.name,
          "' starts on a link carried by a platform (two-stage robots are not supported by the shooting "
          "solver)");
  require(e.start.coupling == RodEndKind::Clamped || joint_end::is_joint(e.start.coupling),
          "ShootingRobotSolver: rod '", e.name, "' has a ", to_string(e.start.coupling),
          " start; the shooting solver needs a clamped, universal or revolute start");
  require(e.end.link >= 0 && m.carrying_platform(e.end.link) >= 0, "ShootingRobotSolver: rod '", e.name,
          "' does not end on a platform-carried link (not supported by the shooting solver)");
  require(e.end.coupling != RodEndKind::Free, "ShootingRobotSolver: rod '", e.name,
          "' has a free end (not supported by the shooting solver)");
  RodSetup r;
  r.rod = i;
  r.platform = m.carrying_platform(e.end.link);
  r.start_coupling = e.start.coupling;
  r.coupling = e.end.coupling;
  if (joint_end::is_joint(r.start_coupling))
    r.start_axes = joint_end::axes_of(r.start_coupling, e.start.axis, "pcr_rod '" + e.name + "' start");
  if (joint_end::is_joint(r.coupling))
    r.end_axes = joint_end::axes_of(r.coupling, e.end.axis, "pcr_rod '" + e.name + "' end");
  r.model = e.rod;
  for (int j = 0; j < static_cast<int>(m.inputs().size()); ++j)
    if (m.inputs()[j].kind == ActuationInput::Kind::RodLength && m.inputs()[j].index == i) r.input = j;
  r.base_joints = moving_joints_above(m, e.start.link);
  r.base_frame = m.attachment_pose(e.start, joints, poses0);
  r.end_offset = poses0[r.platform].inverse() * m.attachment_pose(e.end, joints, poses0);
  r.set_length(e.rod.length);
  return r;
}

// A passive joint: the rods starting beyond it and the weighted links beyond it (links carried by a
// platform are not: a floating joint transmits nothing).
PassiveSetup passive_setup(const RobotModel& m, int j, const std::vector<RodSetup>& rods) {
  PassiveSetup p;
  p.joint = j;
  const Joint& joint = m.joints()[j];
  p.prismatic = joint.type == JointType::Prismatic;
  for (int l = 0; l < static_cast<int>(m.links().size()); ++l)
    if (m.links()[l].mass > 0.0 && m.carrying_platform(l) < 0 && contains(moving_joints_above(m, l), j))
      p.links.push_back(l);
  for (int i = 0; i < static_cast<int>(rods.size()); ++i)
    if (contains(rods[i].base_joints, j)) p.rods.push_back(i);
  require(!p.rods.empty() || !p.links.empty() || joint.stiffness > 0.0,
          "ShootingRobotSolver: passive joint '", joint.name,
          "' carries no rod and no weight and has no spring: its value is undetermined");
  return p;
}

}  // namespace

RobotShootingModel::RobotShootingModel(std::shared_ptr<const RobotModel> robot) : model(std::move(robot)) {
  require(model != nullptr, "ShootingRobotSolver: model is null");
  const RobotModel& m = *model;
  check_joints(m);
  const VecX joints = m.default_joint_values();
  const std::vector<Pose> poses0 = m.initial_platform_poses();
  rods_of_platform.assign(m.platforms().size(), {});
  Ls = 0.0;
  double stiff_force = 0.0;
  for (int i = 0; i < static_cast<int>(m.rods().size()); ++i) {
    RodSetup r = rod_setup(m, i, joints, poses0);
    const RodElement& e = m.rods()[i];
    const double L = r.input >= 0 ? std::max(e.length_upper, e.rod.length) : e.rod.length;
    Ls = std::max(Ls, L);
    stiff_force =
        std::max(stiff_force, e.rod.bending_torsion_stiffness.maxCoeff() / (e.rod.length * e.rod.length));
    rods_of_platform[r.platform].push_back(i);
    rods.push_back(std::move(r));
  }
  for (int k = 0; k < num_platforms(); ++k)
    require(!rods_of_platform[k].empty(), "ShootingRobotSolver: platform '", m.platforms()[k].name,
            "' is held by no rod");
  double applied = 0.0;
  for (const Platform& p : m.platforms()) applied += p.mass * m.gravity().norm();
  // Link masses load only the passive joints that move them (Link::mass); they count in the scale.
  for (const Link& link : m.links()) applied += link.mass * m.gravity().norm();
  for (const RodSetup& r : rods) applied += r.model.distributed_force().norm() * r.model.length;
  for (const ExternalLoad& l : m.loads()) {
    const int k = l.link >= 0 ? m.carrying_platform(l.link) : -1;
    require(k >= 0, "ShootingRobotSolver: the pcr_load on link '", l.link >= 0 ? m.links()[l.link].name : "",
            "' is not carried by a platform (loads on links moved by passive joints are not supported by the "
            "shooting solver)");
    LoadSetup s;
    s.platform = k;
    s.point =
        poses0[k].inverse().transform_point(m.link_pose(l.link, joints, poses0).transform_point(l.point));
    s.force = l.force;
    s.torque = l.torque;
    applied += l.force.norm() + l.torque.norm() / Ls;
    loads.push_back(s);
  }
  Fs = std::max(stiff_force, applied);
  Ms = Fs * Ls;
  for (RodSetup& r : rods) {
    r.unknown_scale << Vec3::Constant(Fs),
        r.joint_start() ? joint_end::unknown_scale(r.start_axes, Ms) : Vec3::Constant(Ms);
  }
  for (int j : m.passive_joints()) {
    PassiveSetup p = passive_setup(m, j, rods);
    p.row_scale = p.prismatic ? Fs : Ms;
    p.unknown_scale = p.prismatic ? Ls : 1.0;
    passive.push_back(std::move(p));
  }
  input_scale.resize(static_cast<int>(m.inputs().size()));
  for (int i = 0; i < input_scale.size(); ++i) {
    const ActuationInput& in = m.inputs()[i];
    const bool angle =
        in.kind == ActuationInput::Kind::JointValue && m.joints()[in.index].type != JointType::Prismatic;
    input_scale[i] = angle ? 1.0 : Ls;
  }
}

VecX RobotShootingModel::joint_values(const State& s) const {
  const RobotModel& m = *model;
  VecX q = m.default_joint_values();
  for (int i = 0; i < static_cast<int>(m.inputs().size()); ++i) {
    const ActuationInput& in = m.inputs()[i];
    if (in.kind == ActuationInput::Kind::JointValue) q[m.joints()[in.index].value_index] = s.inputs[i];
  }
  for (int p = 0; p < num_passive(); ++p) q[m.joints()[passive[p].joint].value_index] = s.passive[p];
  return q;
}

Pose RobotShootingModel::base_frame(int i, const VecX& joint_values, const State& s) const {
  const RodSetup& r = rods[i];
  if (r.base_joints.empty()) return r.base_frame;
  return model->attachment_pose(model->rods()[r.rod].start, joint_values, s.poses);
}

void RobotShootingModel::base_state(int i, const Pose& frame, const Vec6& z, RodStateVector& y0,
                                    joint_end::BaseTangents* dy_dz,
                                    joint_end::FrameTangents* dy_dframe) const {
  const RodSetup& r = rods[i];
  if (r.joint_start()) {
    joint_end::base_state(r.start_axes, frame.position, frame.orientation, Vec3::Zero(), z, y0, dy_dz,
                          dy_dframe);
    return;
  }
  // Clamped: the unknowns are n(0), m(0); a turn of the frame turns only the rod's frame.
  y0 << frame.position, frame.orientation, z;
  if (dy_dz) {
    dy_dz->setZero();
    dy_dz->bottomRows<6>().setIdentity();
  }
  if (dy_dframe) {
    // World rotation e_k: dq = 1/2 q (x) [0, R^T e_k].
    const Mat3 Rt = frame.rotation().transpose();
    dy_dframe->setZero();
    for (int k = 0; k < 3; ++k) {
      const Vec3 w = Rt.col(k);
      dy_dframe->col(k).segment<4>(RodStateIndex::q) =
          0.5 * quat_multiply(frame.orientation, Quat(0.0, w[0], w[1], w[2]));
    }
  }
}

void RobotShootingModel::base_frame_rate(int i, int j, const VecX& q, const State& s, Vec3& velocity,
                                         Vec3& omega) const {
  const RobotModel& m = *model;
  const Joint& joint = m.joints()[j];
  const Pose frame = m.link_pose(joint.parent_link, q, s.poses) * joint.origin;
  const Vec3 axis = frame.rotation() * joint.axis;
  if (joint.type == JointType::Prismatic) {
    velocity = axis;
    omega.setZero();
  } else {
    omega = axis;
    velocity = axis.cross(base_frame(i, q, s).position - frame.position);
  }
}

State RobotShootingModel::cold_state(const VecX& inputs, const std::vector<Pose>& poses) const {
  // Unbent rods sharing their platform's load equally: n(L) = (m g + F_ext) / N, n(0) = n(L) + f L.
  State s;
  s.inputs = inputs;
  s.poses = poses;
  std::vector<Vec3> share(num_platforms(), Vec3::Zero());
  for (int k = 0; k < num_platforms(); ++k) share[k] = model->platforms()[k].mass * model->gravity();
  for (const LoadSetup& l : loads) share[l.platform] += l.force;
  for (const RodSetup& r : rods) {
    const double L = r.input >= 0 ? inputs[r.input] : r.model.length;  // = length_of(r, s)
    Vec6 z = Vec6::Zero();
    z.head<3>() = share[r.platform] / static_cast<double>(rods_of_platform[r.platform].size()) +
                  r.model.distributed_force() * L;
    s.base.push_back(z);
  }
  s.passive.resize(num_passive());
  for (int p = 0; p < num_passive(); ++p) s.passive[p] = model->joints()[passive[p].joint].default_value;
  return s;
}

}  // namespace shooting_robot
}  // namespace pcr
