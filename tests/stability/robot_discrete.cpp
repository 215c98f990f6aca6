#include "stability/robot_discrete.hpp"

#include <boost/test/unit_test.hpp>

namespace pcr::test {

namespace {

DiscreteTip tip_of(RodEndKind kind) {
  switch (kind) {
    case RodEndKind::Clamped: return DiscreteTip::Clamped;
    case RodEndKind::Collar: return DiscreteTip::Collar;
    case RodEndKind::Spherical: return DiscreteTip::Spherical;
    case RodEndKind::Free: return DiscreteTip::Free;
    default: break;
  }
  BOOST_FAIL("discrete model: unsupported end coupling " << to_string(kind));
  return DiscreteTip::Free;
}

/// Joint values at the state x: inputs and passive joints.
VecX state_joint_values(const RobotAssembly& assembly, const VecX& x) {
  const RobotModel& model = assembly.model();
  VecX q = model.default_joint_values();
  const VecX u = assembly.inputs(x);
  for (size_t i = 0; i < model.inputs().size(); ++i)
    if (model.inputs()[i].kind == ActuationInput::Kind::JointValue)
      q[model.joints()[model.inputs()[i].index].value_index] = u[static_cast<int>(i)];
  const std::vector<int>& passive = model.passive_joints();
  for (size_t k = 0; k < passive.size(); ++k)
    q[model.joints()[passive[k]].value_index] =
        x[assembly.problem().variable(assembly.passive_joint_variable(static_cast<int>(k))).offset];
  return q;
}

/// The discrete hinge of passive joint j (a revolute joint on a fixed link) at the state x: its world axis,
/// spring, and the weights and loads on the links it moves.
DiscreteHingeSpec hinge_of(const RobotAssembly& assembly, const VecX& x, int passive, const VecX& q,
                           const std::vector<Pose>& poses) {
  const RobotModel& model = assembly.model();
  const int j = model.passive_joints()[passive];
  const Joint& joint = model.joints()[j];
  BOOST_TEST_REQUIRE((joint.type == JointType::Revolute || joint.type == JointType::Continuous));
  BOOST_TEST_REQUIRE(!model.moved_by_passive_joint(joint.parent_link));  // one hinge, on a fixed link
  BOOST_TEST_REQUIRE(model.carrying_platform(joint.parent_link) < 0);
  DiscreteHingeSpec h;
  const Pose frame = model.link_pose(joint.parent_link, q, poses) * joint.origin;
  h.origin = frame.position;
  h.axis = (frame.rotation() * joint.axis).normalized();
  h.stiffness = joint.stiffness;
  h.rest = joint.rest;
  h.value = x[assembly.problem().variable(assembly.passive_joint_variable(passive)).offset];
  for (size_t l = 0; l < model.links().size(); ++l) {
    const Link& link = model.links()[l];
    if (link.mass > 0.0 && model.joint_moves_link(j, static_cast<int>(l)))
      h.forces.emplace_back(
          model.link_pose(static_cast<int>(l), q, poses).transform_point(link.center_of_mass),
          link.mass * model.gravity());
  }
  for (const ExternalLoad& load : model.loads())
    if (model.joint_moves_link(j, load.link))
      h.forces.emplace_back(model.link_pose(load.link, q, poses).transform_point(load.point), load.force);
  return h;
}

}  // namespace

DiscreteRods::Inertia discrete_robot_inertia(const RobotAssembly& assembly, const VecX& x, int segments) {
  const RobotModel& model = assembly.model();
  const int np = static_cast<int>(model.platforms().size());
  std::vector<Pose> poses;
  std::vector<int> platform_of_link(model.links().size(), -1);
  for (int p = 0; p < np; ++p) {
    poses.push_back(assembly.platform_pose(x, p));
    platform_of_link[model.platforms()[p].link] = p;
  }
  std::vector<DiscretePlatformSpec> platforms(np);
  for (int p = 0; p < np; ++p) {
    const Platform& P = model.platforms()[p];
    platforms[p].forces.emplace_back(P.center_of_mass, P.mass * model.gravity());
  }
  for (const ExternalLoad& load : model.loads()) {
    BOOST_TEST_REQUIRE(load.torque.isZero(0.0));
    if (platform_of_link[load.link] >= 0)  // else on a hinge's link (hinge_of)
      platforms[platform_of_link[load.link]].forces.emplace_back(load.point, load.force);
  }
  const VecX q = state_joint_values(assembly, x);
  const std::vector<int>& passive = model.passive_joints();
  std::vector<DiscreteHingeSpec> hinges;
  for (size_t k = 0; k < passive.size(); ++k)
    hinges.push_back(hinge_of(assembly, x, static_cast<int>(k), q, poses));
  std::vector<DiscreteRodSpec> rods;
  for (int i = 0; i < assembly.num_rods(); ++i) {
    const RodElement& e = model.rods()[i];
    const CollocationRod& rod = assembly.rod(i);
    BOOST_TEST_REQUIRE((e.start.coupling == RodEndKind::Clamped));
    BOOST_TEST_REQUIRE(platform_of_link[e.start.link] < 0);  // a fixed link or one on a hinge
    const bool free_tip = e.end.coupling == RodEndKind::Free;
    BOOST_TEST_REQUIRE((free_tip || platform_of_link[e.end.link] >= 0));
    if (!free_tip) BOOST_TEST_REQUIRE(e.end.link == model.platforms()[platform_of_link[e.end.link]].link);
    DiscreteRodSpec s;
    for (size_t k = 0; k < passive.size(); ++k)
      if (model.joint_moves_link(passive[k], e.start.link)) s.base_hinge = static_cast<int>(k);
    s.length = rod.length(x, assembly.rod_variables(i));
    s.k_se = rod.model().shear_extension_stiffness;
    s.k_bt = rod.model().bending_torsion_stiffness;
    s.distributed_force = rod.model().distributed_force();
    const RodState base = rod.state_at(x, assembly.rod_variables(i), 0.0);
    s.base_position = base.position;
    s.base_rotation = base.rotation;
    s.tip = tip_of(e.end.coupling);
    if (free_tip) {
      BOOST_TEST_REQUIRE(rod.model().tip.moment.isZero(0.0));  // a dead couple has no potential
      s.tip_force = rod.model().tip.force;
    } else {
      s.platform = platform_of_link[e.end.link];
    }
    s.attachment_position = e.end.frame.position;
    s.attachment_rotation = e.end.frame.rotation();
    s.segments = segments;
    rods.push_back(s);
  }
  DiscreteRods d(rods, platforms, hinges);
  for (int p = 0; p < np; ++p) d.set_platform(p, poses[p].position, poses[p].rotation());
  for (int i = 0; i < assembly.num_rods(); ++i) {
    const CollocationRod& rod = assembly.rod(i);
    const RodVariables& vars = assembly.rod_variables(i);
    d.set_rod(i, [&](double s, Vec3& p, Mat3& R) {
      const RodState st = rod.state_at(x, vars, s);
      p = st.position;
      R = st.rotation;
    });
  }
  BOOST_TEST_REQUIRE(d.relax());
  return d.inertia();
}

}  // namespace pcr::test
