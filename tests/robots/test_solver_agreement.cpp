// One robot problem solved two ways gives one answer: FK by Newton and by Ipopt, FK and warm-started IK
// with the structured and the general sparse LU, and with the mixed rods condensed (the default) or kept.
#include <boost/test/unit_test.hpp>

#include <memory>
#include <string>

#include "pcr/math/so3.hpp"
#include "pcr/robots/kinematics.hpp"
#include "robot_fixtures.hpp"

using namespace pcr;
using test::load_model;
using test::moved_inputs;
using test::tight_kinematics;

namespace {

/// Warm-started IK along the first 10 steps of the R5b teleoperation path with two option sets: both
/// converge at every step and their inputs agree to `tolerance` m.
void check_warm_teleop_ik_agrees(const std::shared_ptr<const RobotModel>& teleop, const KinematicsOptions& a,
                                 const KinematicsOptions& b, double tolerance) {
  LinkTarget target;
  target.link = "platform";
  InverseKinematics ia(teleop, {target}, a), ib(teleop, {target}, b);
  for (int i = 0; i < 10; ++i) {
    Pose pose;
    pose.position = Vec3(0.0, 0.02 + 0.001 * i, 0.48 + 0.001 * i);
    const RobotSolution sa = ia.solve({pose}), sb = ib.solve({pose});
    BOOST_TEST_REQUIRE(sa.summary.converged(), sa.summary.brief_report());
    BOOST_TEST_REQUIRE(sb.summary.converged(), sb.summary.brief_report());
    BOOST_TEST((sa.inputs - sb.inputs).lpNorm<Eigen::Infinity>() < tolerance, "step " << i);
  }
}

/// FK of `model` at inputs u with the default assembly (mixed rods solved condensed) and with the mixed
/// rods kept, both at tolerance 1e-12 and converged; the options are returned for further solves.
struct CondensedAndMixed {
  KinematicsOptions condensed = tight_kinematics(), mixed = tight_kinematics();
  bool condensed_with_loads = false;  // of the first rod in the condensed assembly
  RobotSolution fk_condensed, fk_mixed;
};
CondensedAndMixed condensed_and_mixed_fk(const std::shared_ptr<const RobotModel>& model, const VecX& u) {
  CondensedAndMixed out;
  out.mixed.assembly.condense_mixed_rods = false;
  ForwardKinematics fc(model, out.condensed), fm(model, out.mixed);
  BOOST_TEST((fc.assembly().rod(0).discretization().formulation == RodFormulation::Condensed));
  BOOST_TEST((fm.assembly().rod(0).discretization().formulation == RodFormulation::Mixed));
  out.condensed_with_loads = fc.assembly().rod(0).condensed_with_loads();
  out.fk_condensed = fc.solve(u);
  out.fk_mixed = fm.solve(u);
  BOOST_TEST_REQUIRE(out.fk_condensed.summary.converged(), out.fk_condensed.summary.brief_report());
  BOOST_TEST_REQUIRE(out.fk_mixed.summary.converged(), out.fk_mixed.summary.brief_report());
  return out;
}

}  // namespace

BOOST_AUTO_TEST_CASE(newton_and_ipopt_forward_kinematics_agree) {
  const auto model = load_model("stewart_gough");
  KinematicsOptions o = tight_kinematics();
  ForwardKinematics newton(model, o);
  o.solver = SolverKind::Ipopt;
  o.tolerance = 1e-11;
  ForwardKinematics ipopt(model, o);
  const VecX u = moved_inputs(*model, 0.03);
  const RobotSolution a = newton.solve(u), b = ipopt.solve(u);
  BOOST_REQUIRE_MESSAGE(a.summary.converged(), a.summary.brief_report());
  BOOST_REQUIRE_MESSAGE(b.summary.converged(), b.summary.brief_report());
  // Same square system solved to 1e-11..1e-12: platform positions agree to 1e-10 m.
  BOOST_TEST((a.platforms[0].position - b.platforms[0].position).norm() < 1e-10);
  BOOST_TEST(rotation_angle_between(a.platforms[0].rotation(), b.platforms[0].rotation()) < 1e-9);
}

// The structured LU (a band LU per rod, condensed onto platforms and inputs; the default) and the
// general sparse LU solve the same Newton systems: on every model FK at moved inputs and IK back to
// the reached pose agree to the solver tolerance (1e-12 residuals, well-conditioned systems: 1e-9 m).
BOOST_AUTO_TEST_CASE(structured_and_sparse_lu_give_the_same_kinematics) {
  for (const std::string name : {"stewart_gough", "stewart_gough_teleop", "planar_three_rod",
                                 "slider_actuated", "two_stage", "cantilever"}) {
    const auto model = load_model(name);
    KinematicsOptions structured = tight_kinematics(), sparse = tight_kinematics();
    sparse.linear_solver = NewtonLinearSolver::Sparse;
    ForwardKinematics a(model, structured), b(model, sparse);
    const VecX u = moved_inputs(*model, 0.02);
    const RobotSolution sa = a.solve(u), sb = b.solve(u);
    BOOST_TEST_REQUIRE(sa.summary.converged(), name << ": " << sa.summary.brief_report());
    BOOST_TEST_REQUIRE(sb.summary.converged(), name << ": " << sb.summary.brief_report());
    for (size_t p = 0; p < sa.platforms.size(); ++p)
      BOOST_TEST((sa.platforms[p].position - sb.platforms[p].position).norm() < 1e-9, name);
    for (size_t r = 0; r < sa.rods.size(); ++r)
      BOOST_TEST((sa.rods[r].base_force - sb.rods[r].base_force).norm() <=
                     1e-6 * (1.0 + sb.rods[r].base_force.norm()),
                 name << " rod " << r);
  }
  // R5b: warm-started IK along a few steps of the teleoperation path (Newton with factorisation reuse).
  const auto teleop = load_model("stewart_gough_teleop");
  KinematicsOptions structured = tight_kinematics(), sparse = tight_kinematics();
  sparse.linear_solver = NewtonLinearSolver::Sparse;
  check_warm_teleop_ik_agrees(teleop, structured, sparse, 1e-9);
}

BOOST_AUTO_TEST_CASE(condensed_and_mixed_rods_give_the_same_kinematics) {
  // R5b's rods carry no distributed load; there the condensed form (the default assembly's)
  // is the mixed midpoint scheme with n, m eliminated (test_collocation_rod), so FK and warm-started
  // IK must agree with the mixed rods up to the solver tolerance: both solve to 1e-12 (dimensionless),
  // which moves positions by ~1e-12 L0 times cond; 1e-9 m, and 1e-6 relative on the rod wrenches.
  const auto teleop = load_model("stewart_gough_teleop");
  const CondensedAndMixed both = condensed_and_mixed_fk(teleop, moved_inputs(*teleop, 0.02));
  const RobotSolution &sc = both.fk_condensed, &sm = both.fk_mixed;
  BOOST_TEST((sc.platforms[0].position - sm.platforms[0].position).norm() < 1e-9);
  BOOST_TEST(rotation_angle_between(sc.platforms[0].rotation(), sm.platforms[0].rotation()) < 1e-9);
  for (size_t r = 0; r < sc.rods.size(); ++r) {
    const RodResult &a = sc.rods[r], &b = sm.rods[r];
    BOOST_TEST((a.base_force - b.base_force).norm() <= 1e-6 * (1.0 + b.base_force.norm()), "rod " << r);
    BOOST_TEST((a.tip_moment - b.tip_moment).norm() <= 1e-6 * (1.0 + b.tip_moment.norm()), "rod " << r);
    for (size_t k = 0; k < a.centerline.size(); ++k)
      BOOST_TEST((a.centerline[k] - b.centerline[k]).norm() < 1e-9, "rod " << r << " point " << k);
  }
  check_warm_teleop_ik_agrees(teleop, both.condensed, both.mixed, 1e-9);
}

BOOST_AUTO_TEST_CASE(condensed_and_mixed_rods_agree_under_gravity) {
  // R5a's rods carry gravity: there the condensed form (exact balance with the integral of p) is not the
  // mixed scheme but converges to the same solution. At the default mesh both are 1.8e-10 m (FK
  // platform) and 1.7e-8 m (IK inputs) from a fine mixed reference (bench_robots, docs/benchmarks.md
  // "Robots"), so they differ by at most twice that: asserted 1e-9 m and 5e-8 m.
  const auto r5a = load_model("stewart_gough");
  const CondensedAndMixed both = condensed_and_mixed_fk(r5a, r5a->default_input_values());
  BOOST_TEST(both.condensed_with_loads);
  BOOST_TEST((both.fk_condensed.platforms[0].position - both.fk_mixed.platforms[0].position).norm() < 1e-9);
  LinkTarget target;
  target.link = "platform";
  target.pose.position = Vec3(0.0, 0.0, 0.4);
  target.pose.orientation = quat_from_rotation_vector(Vec3(0.0, 10.0 * M_PI / 180.0, 0.0));
  InverseKinematics ic(r5a, {target}, both.condensed), im(r5a, {target}, both.mixed);
  const RobotSolution a = ic.solve({target.pose}), b = im.solve({target.pose});
  BOOST_TEST_REQUIRE(a.summary.converged(), a.summary.brief_report());
  BOOST_TEST_REQUIRE(b.summary.converged(), b.summary.brief_report());
  BOOST_TEST((a.inputs - b.inputs).lpNorm<Eigen::Infinity>() < 5e-8);
}
