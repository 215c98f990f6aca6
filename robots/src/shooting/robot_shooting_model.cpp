// What the shooting robot solver takes from a RobotModel (see robot_shooting_model.hpp).
#include "robot_shooting_model.hpp"

#include <algorithm>

#include "pcr/core/error.hpp"

namespace pcr {
namespace shooting_robot {

RobotShootingModel::RobotShootingModel(std::shared_ptr<const RobotModel> robot) : model(std::move(robot)) {
  require(model != nullptr, "ShootingRobotSolver: model is null");
  const RobotModel& m = *model;
  for (const ActuationInput& in : m.inputs())
    require(in.kind == ActuationInput::Kind::RodLength, "ShootingRobotSolver: input '", in.name,
            "' is a joint value; joint-driven bases are not supported by the shooting solver");
  const VecX joints = m.default_joint_values();
  const std::vector<Pose> poses0 = m.initial_platform_poses();
  rods_of_platform.assign(m.platforms().size(), {});
  Ls = 0.0;
  double stiff_force = 0.0;
  for (int i = 0; i < static_cast<int>(m.rods().size()); ++i) {
    const RodElement& e = m.rods()[i];
    require(e.start.link >= 0 && m.carrying_platform(e.start.link) < 0, "ShootingRobotSolver: rod '", e.name,
            "' starts on a link carried by a platform (two-stage robots are not supported by the shooting "
            "solver)");
    require(e.start.coupling == RodEndKind::Clamped, "ShootingRobotSolver: rod '", e.name, "' has a ",
            to_string(e.start.coupling), " start; the shooting solver needs a clamped start");
    require(e.end.link >= 0 && m.carrying_platform(e.end.link) >= 0, "ShootingRobotSolver: rod '", e.name,
            "' does not end on a platform-carried link (not supported by the shooting solver)");
    require(e.end.coupling != RodEndKind::Free, "ShootingRobotSolver: rod '", e.name,
            "' has a free end (not supported by the shooting solver)");
    RodSetup r;
    r.rod = i;
    r.platform = m.carrying_platform(e.end.link);
    r.coupling = e.end.coupling;
    r.model = e.rod;
    for (int j = 0; j < static_cast<int>(m.inputs().size()); ++j)
      if (m.inputs()[j].index == i) r.input = j;
    r.base_frame = m.attachment_pose(e.start, joints, poses0);
    r.end_offset = poses0[r.platform].inverse() * m.attachment_pose(e.end, joints, poses0);
    r.set_length(e.rod.length);
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
  for (const RodSetup& r : rods) applied += r.model.distributed_force().norm() * r.model.length;
  for (const ExternalLoad& l : m.loads()) {
    const int k = l.link >= 0 ? m.carrying_platform(l.link) : -1;
    if (k < 0) continue;  // carried by the ground
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
    s.n0.push_back(share[r.platform] / static_cast<double>(rods_of_platform[r.platform].size()) +
                   r.model.distributed_force() * L);
    s.m0.push_back(Vec3::Zero());
  }
  return s;
}

}  // namespace shooting_robot
}  // namespace pcr
