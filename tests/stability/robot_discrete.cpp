#include "stability/robot_discrete.hpp"

#include <boost/test/unit_test.hpp>

namespace pcr::test {

namespace {

DiscreteTip tip_of(RodEndKind kind) {
  switch (kind) {
    case RodEndKind::Clamped: return DiscreteTip::Clamped;
    case RodEndKind::Collar: return DiscreteTip::Collar;
    case RodEndKind::Spherical: return DiscreteTip::Spherical;
    default: break;
  }
  BOOST_FAIL("discrete model: unsupported end coupling " << to_string(kind));
  return DiscreteTip::Free;
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
    BOOST_TEST_REQUIRE(platform_of_link[load.link] >= 0);
    platforms[platform_of_link[load.link]].forces.emplace_back(load.point, load.force);
  }
  std::vector<DiscreteRodSpec> rods;
  for (int i = 0; i < assembly.num_rods(); ++i) {
    const RodElement& e = model.rods()[i];
    const CollocationRod& rod = assembly.rod(i);
    BOOST_TEST_REQUIRE((e.start.coupling == RodEndKind::Clamped));
    BOOST_TEST_REQUIRE(platform_of_link[e.start.link] < 0);  // a fixed link: its pose is the state's
    BOOST_TEST_REQUIRE(platform_of_link[e.end.link] >= 0);
    BOOST_TEST_REQUIRE(e.end.link == model.platforms()[platform_of_link[e.end.link]].link);
    DiscreteRodSpec s;
    s.length = rod.length(x, assembly.rod_variables(i));
    s.k_se = rod.model().shear_extension_stiffness;
    s.k_bt = rod.model().bending_torsion_stiffness;
    s.distributed_force = rod.model().distributed_force();
    const RodState base = rod.state_at(x, assembly.rod_variables(i), 0.0);
    s.base_position = base.position;
    s.base_rotation = base.rotation;
    s.tip = tip_of(e.end.coupling);
    s.platform = platform_of_link[e.end.link];
    s.attachment_position = e.end.frame.position;
    s.attachment_rotation = e.end.frame.rotation();
    s.segments = segments;
    rods.push_back(s);
  }
  DiscreteRods d(rods, platforms);
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
