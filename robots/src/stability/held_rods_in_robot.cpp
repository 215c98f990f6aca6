// Each rod of a robot with its couplings held in fixed link frames, and the model's assumptions
// (robot_stability_parts.hpp).
#include <algorithm>
#include <sstream>

#include "pcr/rods/drawn_rod.hpp"
#include "pcr/rods/stability/rod_stability.hpp"
#include "robot_stability_parts.hpp"

namespace pcr::stability {

std::string robot_assumption_failure(const RobotModel& model) {
  std::ostringstream msg;
  auto add = [&msg](const std::string& s) { msg << (msg.tellp() > 0 ? "; " : "") << s; };
  for (const RodElement& rod : model.rods()) {
    const std::string rod_failure = nonconservative_loads(rod.rod);
    if (!rod_failure.empty()) add(rod_failure);
  }
  for (const ExternalLoad& load : model.loads())
    if (!load.torque.isZero(0.0))
      add("dead torque on link '" + model.links()[load.link].name + "' has no potential (" +
          (model.carrying_platform(load.link) >= 0
               ? "a platform turns about any axis"
               : "treated as non-conservative on links that passive joints turn") +
          ")");
  return msg.str();
}

namespace {

/// Joint values of the model at the state x: inputs and passive joints from x (every moving joint is one
/// or the other).
VecX joint_values(const RobotAssembly& assembly, const VecX& x) {
  const RobotModel& model = assembly.model();
  VecX q = model.default_joint_values();
  const VecX u = assembly.inputs(x);
  for (size_t i = 0; i < model.inputs().size(); ++i) {
    const ActuationInput& in = model.inputs()[i];
    if (in.kind == ActuationInput::Kind::JointValue)
      q[model.joints()[in.index].value_index] = u[static_cast<int>(i)];
  }
  const std::vector<int>& passive = model.passive_joints();
  for (size_t j = 0; j < passive.size(); ++j)
    q[model.joints()[passive[j]].value_index] =
        x[assembly.problem().variable(assembly.passive_joint_variable(static_cast<int>(j))).offset];
  return q;
}

/// The held end of a rod end attached to a link (its world attachment frame from the link pose).
HeldEnd held_coupling(const RobotModel& model, const RodAttachment& attachment, const VecX& q,
                      const std::vector<Pose>& platforms, const Mat3& rod_rotation) {
  if (attachment.link < 0) {
    HeldEnd free;
    free.kind = RodEndKind::Free;
    return free;
  }
  const Mat3 frame = model.attachment_pose(attachment, q, platforms).rotation();
  return held_end(attachment.coupling, frame, attachment.axis, rod_rotation);
}

}  // namespace

HeldRodIndex held_rod_in_robot(const RobotAssembly& assembly, const VecX& x, int i) {
  const RobotModel& model = assembly.model();
  const CollocationRod& rod = assembly.rod(i);
  const RodVariables& vars = assembly.rod_variables(i);
  const RodElement& element = model.rods()[i];
  std::vector<Pose> platforms;
  for (size_t p = 0; p < model.platforms().size(); ++p)
    platforms.push_back(assembly.platform_pose(x, static_cast<int>(p)));
  const VecX q = joint_values(assembly, x);
  const JacobiStateAt states = jacobi_states(rod, x, vars);
  const double L = rod.length(x, vars);
  HeldRod held;
  held.length = L;
  // Drawn rods: the effective stiffnesses (drawn_rod.hpp), as jacobi_states gives N, M.
  const DrawnConstants d =
      drawn_constants(rod.model(), rod.model().intrinsic.shear_extension, rod.model().intrinsic.curvature);
  held.shear_extension_stiffness = d.k_se;
  held.bending_torsion_stiffness = d.k_bt;
  held.base = held_coupling(model, element.start, q, platforms, states(0.0).rotation);
  held.tip = held_coupling(model, element.end, q, platforms, states(L).rotation);
  HeldRodOptions options;
  options.min_segments = std::max(options.min_segments, rod.discretization().elements);
  return held_rod_index(held, states, options);
}

}  // namespace pcr::stability
