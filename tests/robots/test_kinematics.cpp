// Robot assembly and kinematics: every coupling, balance and target block against finite
// differences, FK -> IK round trips on every model, derivatives (implicit function theorem) against
// finite differences of FK, failure reporting. The solvers' agreement (Newton / Ipopt, structured /
// sparse LU, condensed / mixed rods): test_solver_agreement.cpp (same executable).
#define BOOST_TEST_MODULE kinematics
#include <boost/test/unit_test.hpp>

#include <fstream>
#include <random>
#include <sstream>

#include "pcr/core/error.hpp"
#include "pcr/math/dense_decompositions.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/solve/jacobian_check.hpp"
#include "robot_fixtures.hpp"

using namespace pcr;
using test::load_model;
using test::model_text;
using test::moved_inputs;
using test::tight_kinematics;

namespace {

/// The planar robot with a fourth rod ending in a spherical joint (exercises that coupling).
std::shared_ptr<const RobotModel> planar_with_spherical_rod() {
  std::string xml = model_text("planar_three_rod");
  const std::string rod = R"(
  <pcr_rod name="pin">
    <start link="base" xyz="0 0.05 0" rpy="0 0 0" coupling="clamped"/>
    <end link="platform" xyz="0 0.05 0" rpy="0 0 0" coupling="spherical"/>
    <material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>
    <section type="circle" radius="0.0005"/>
    <length value="0.3"/>
  </pcr_rod>
</robot>)";
  xml.replace(xml.rfind("</robot>"), 8, rod);
  return std::make_shared<const RobotModel>(parse_robot_model(xml, "planar_with_spherical_rod"));
}

// Pose components each model's inputs control (x, y, z, rx, ry, rz), see the models' comments.
struct IkCase {
  std::string model;
  std::vector<std::string> links;
  std::array<bool, 6> components;
};
const std::array<bool, 6> kFull{{true, true, true, true, true, true}};
const std::array<bool, 6> kHeaveTilt{{false, false, true, true, true, false}};  // z, rx, ry
const std::array<bool, 6> kPlanar{{true, false, true, false, true, false}};     // x, z, ry

}  // namespace

BOOST_AUTO_TEST_CASE(every_coupling_balance_and_target_block_matches_finite_differences) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<std::pair<std::string, std::shared_ptr<const RobotModel>>> models;
  for (const char* name : {"stewart_gough", "stewart_gough_teleop", "planar_three_rod", "two_stage",
                           "cantilever", "slider_actuated"})
    models.emplace_back(name, load_model(name));
  models.emplace_back("planar_with_spherical_rod", planar_with_spherical_rod());
  for (const auto& [name, model] : models) {
    ForwardKinematics fk(model);
    const RobotSolution s = fk.solve(model->default_input_values());
    BOOST_REQUIRE_MESSAGE(s.summary.converged(), name << ": " << s.summary.brief_report());
    // A perturbed state (relative 1e-3, quaternions no longer unit) with free input variables.
    VecX x = fk.state();
    for (int i = 0; i < x.size(); ++i) x[i] += 1e-3 * (std::abs(x[i]) + 1e-2) * noise(rng);
    // Default checker tolerances (1e-6 abs + rel; central differences with relative step 1e-6).
    const JacobianCheckResult r = check_problem_jacobian(fk.assembly().problem(), x);
    BOOST_TEST(r.passed, name << ": " << r.to_string());
  }
  // Target blocks: a full-pose target with a rotated offset link is in the IK problem.
  const auto model = load_model("stewart_gough");
  LinkTarget t;
  t.link = "platform";
  t.pose.position = Vec3(0.01, -0.02, 0.4);
  t.pose.orientation = quat_from_rotation_vector(Vec3(0.0, 0.17, 0.05));
  InverseKinematics ik(model, {t});
  VecX x = ik.state();
  for (int i = 0; i < x.size(); ++i) x[i] += 1e-3 * (std::abs(x[i]) + 1e-2) * noise(rng);
  const JacobianCheckResult r = check_problem_jacobian(ik.problem(), x);
  BOOST_TEST(r.passed, "ik problem: " << r.to_string());
}

BOOST_AUTO_TEST_CASE(fk_then_ik_round_trip_on_every_model) {
  // FK at moved inputs, then IK to the reached pose (the components each robot's inputs control):
  //  - always: FK at the IK's inputs reaches the target (the IK solved the right problem);
  //  - where the targeted map is well conditioned (singular value ratio of the selected rows of
  //    d(pose)/d(inputs) > 1e-3), the IK inputs are the FK inputs to 1e-8 m (issue requirement; both
  //    solves at 1e-10 dimensionless residual). The planar robot's three nearly parallel rods give a
  //    ratio ~5e-4: there several input sets reach the same pose, and the IK returns the one closest
  //    to its reference inputs, so only the first check applies.
  const std::vector<IkCase> cases = {{"stewart_gough", {"platform"}, kFull},
                                     {"stewart_gough_teleop", {"platform"}, kFull},
                                     {"planar_three_rod", {"platform"}, kPlanar},
                                     {"two_stage", {"platform1", "platform2"}, kHeaveTilt},
                                     {"slider_actuated", {"platform"}, kHeaveTilt}};
  for (const IkCase& c : cases) {
    const auto model = load_model(c.model);
    ForwardKinematics fk(model);
    // 0.5 % of the input ranges (mm): moderate deformations. (Larger unequal length changes of the
    // planar robot can make a direct FK jump to an unstable equilibrium; KinematicsOptions::check_stability
    // monitors that, test_stability_monitor.)
    const VecX u = moved_inputs(*model, 0.005);
    const RobotSolution s = fk.solve(u);
    BOOST_REQUIRE_MESSAGE(s.summary.converged(), c.model << " FK: " << s.summary.brief_report());
    for (const RodResult& rod : s.rods)  // sanity: far from kN self-stress (loads here are < 10 N)
      BOOST_TEST(std::abs(rod.axial_force) < 10.0,
                 c.model << " " << rod.name << " axial force " << rod.axial_force);
    double ratio = 0.0;
    {
      const MatX J = fk.input_jacobian();
      MatX selected(0, J.cols());
      for (const std::string& link : c.links)
        for (int k = 0; k < 6; ++k)
          if (c.components[k]) {
            selected.conservativeResize(selected.rows() + 1, Eigen::NoChange);
            selected.row(selected.rows() - 1) = J.row(6 * model->platform_index(link) + k);
          }
      const VecX sigma = singular_values(selected);
      ratio = sigma.minCoeff() / sigma.maxCoeff();
      BOOST_TEST_MESSAGE(c.model << ": target/input singular value ratio " << ratio);
    }
    std::vector<LinkTarget> targets;
    std::vector<Pose> poses;
    for (const std::string& link : c.links) {
      LinkTarget t;
      t.link = link;
      t.components = c.components;
      const int p = model->platform_index(link);
      t.pose = s.platforms[p];
      targets.push_back(t);
      poses.push_back(s.platforms[p]);
    }
    InverseKinematics ik(model, targets);
    const RobotSolution r = ik.solve(poses);
    BOOST_REQUIRE_MESSAGE(r.summary.converged(),
                          c.model << " IK: " << r.summary.brief_report() << " " << r.summary.message);
    const RobotSolution check = fk.solve(r.inputs);
    BOOST_REQUIRE_MESSAGE(
        check.summary.converged(),
        c.model << " FK at the IK inputs: " << check.summary.brief_report() << " " << check.summary.message);
    for (const std::string& link : c.links) {
      const int p = model->platform_index(link);
      const Vec3 dx = check.platforms[p].position - s.platforms[p].position;
      const Vec3 dr = so3_log(s.platforms[p].rotation().transpose() * check.platforms[p].rotation());
      for (int k = 0; k < 3; ++k) {
        // Targeted components reached to 1e-9 (m, rad): solver tolerance 1e-10 x length scale ~0.5 m.
        if (c.components[k])
          BOOST_TEST(std::abs(dx[k]) < 1e-9, c.model << " " << link << " position " << k << ": " << dx[k]);
        if (c.components[3 + k])
          BOOST_TEST(std::abs(dr[k]) < 1e-9, c.model << " " << link << " rotation " << k << ": " << dr[k]);
      }
    }
    if (ratio > 1e-3)
      BOOST_TEST((r.inputs - u).lpNorm<Eigen::Infinity>() < 1e-8,
                 c.model << ": IK inputs " << r.inputs.transpose() << " vs FK inputs " << u.transpose());
  }
}

BOOST_AUTO_TEST_CASE(input_jacobian_matches_finite_differences_of_fk) {
  for (const char* name : {"stewart_gough", "slider_actuated"}) {
    const auto model = load_model(name);
    ForwardKinematics fk(model, tight_kinematics());
    const VecX u0 = moved_inputs(*model, 0.01);
    BOOST_REQUIRE(fk.solve(u0).summary.converged());
    const MatX J = fk.input_jacobian();
    // Central differences with h = 1e-5 m: truncation ~h^2 |d3 pose/du3| ~ 1e-10, solver noise
    // ~1e-12 / h = 1e-7 relative at worst; tolerance 1e-5 of the largest entry.
    const double h = 1e-5;
    MatX fd(J.rows(), J.cols());
    for (int i = 0; i < u0.size(); ++i) {
      VecX up = u0, um = u0;
      up[i] += h;
      um[i] -= h;
      const RobotSolution sp = fk.solve(up), sm = fk.solve(um);
      BOOST_REQUIRE(sp.summary.converged() && sm.summary.converged());
      for (size_t p = 0; p < sp.platforms.size(); ++p) {
        fd.block<3, 1>(6 * p, i) = (sp.platforms[p].position - sm.platforms[p].position) / (2 * h);
        fd.block<3, 1>(6 * p + 3, i) =
            so3_log(sp.platforms[p].rotation() * sm.platforms[p].rotation().transpose()) / (2 * h);
      }
    }
    BOOST_TEST((J - fd).cwiseAbs().maxCoeff() < 1e-5 * J.cwiseAbs().maxCoeff(), name << ":\nIFT\n"
                                                                                     << J << "\nFD\n"
                                                                                     << fd);
  }
}

BOOST_AUTO_TEST_CASE(compliance_matches_finite_differences_of_fk) {
  const auto base = load_model("stewart_gough");
  ForwardKinematics fk(base, tight_kinematics());
  BOOST_REQUIRE(fk.solve(base->default_input_values()).summary.converged());
  const MatX C = fk.compliance(0);
  // FD: the same model with an extra dead wrench on the platform (force at its origin, torque).
  const double hf = 1e-3, ht = 1e-4;  // N, N m (the legs carry ~0.3 N; linear range)
  MatX fd(6, 6);
  for (int k = 0; k < 6; ++k) {
    Pose poses[2];
    for (int sign : {1, -1}) {
      std::vector<ExternalLoad> loads = base->loads();
      ExternalLoad l;
      l.link = base->platforms()[0].link;
      (k < 3 ? l.force : l.torque)[k % 3] = sign * (k < 3 ? hf : ht);
      loads.push_back(l);
      std::vector<Platform> platforms = base->platforms();
      auto model = std::make_shared<const RobotModel>(base->name(), base->links(), base->joints(), platforms,
                                                      base->rods(), loads, base->gravity());
      ForwardKinematics f(model, tight_kinematics());
      const RobotSolution s = f.solve(model->default_input_values());
      BOOST_REQUIRE(s.summary.converged());
      poses[sign > 0 ? 0 : 1] = s.platforms[0];
    }
    const double h = k < 3 ? hf : ht;
    fd.block<3, 1>(0, k) = (poses[0].position - poses[1].position) / (2 * h);
    fd.block<3, 1>(3, k) = so3_log(poses[0].rotation() * poses[1].rotation().transpose()) / (2 * h);
  }
  // Truncation O(h^2) relative to the nonlinearity (~1e-6 here), solver noise 1e-12 / h; 1e-4 of
  // the largest entry.
  BOOST_TEST((C - fd).cwiseAbs().maxCoeff() < 1e-4 * C.cwiseAbs().maxCoeff(), "IFT\n" << C << "\nFD\n" << fd);
}

BOOST_AUTO_TEST_CASE(summary_counts_the_fresh_jacobians_of_every_attempt) {
  const auto model = load_model("stewart_gough");
  ForwardKinematics fk(model, tight_kinematics());
  const VecX u = moved_inputs(*model, 0.03);
  const RobotSolution cold = fk.solve(u);
  BOOST_REQUIRE_MESSAGE(cold.summary.converged(), cold.summary.brief_report());
  // From the straight rods: at least one fresh Jacobian, and at most one per (quasi-)Newton iteration.
  BOOST_TEST(cold.summary.jacobian_evaluations >= 1);
  BOOST_TEST(cold.summary.jacobian_evaluations <= cold.summary.iterations);
  // Again at the same inputs: the start is the solution, nothing is evaluated.
  const RobotSolution again = fk.solve(u);
  BOOST_TEST(again.summary.iterations == 0);
  BOOST_TEST(again.summary.jacobian_evaluations == 0);
}

BOOST_AUTO_TEST_CASE(a_rod_compressed_to_a_point_is_not_a_solution) {
  // One rod clamped at both ends to the same point (the second end on a link fixed to the base there).
  // From the straight rod Newton reaches, in one step, the rod compressed to zero length (v3 = 0, axial
  // force -EA): an exact equilibrium of the extensible model, within a 1e-8 tolerance (measured
  // |r|max = 5.3e-9). It must be reported as a failure with the rod named, not as a result - also with
  // KinematicsOptions::read_centerline = false: the axial stretch check does not need the centerline.
  const std::string xml = R"(<?xml version="1.0"?>
<robot name="coinciding_ends"><link name="base"/><link name="anchor"/>
  <joint name="fix" type="fixed"><parent link="base"/><child link="anchor"/><origin xyz="0 0 0" rpy="0 0 0"/></joint>
  <pcr_rod name="loop">
    <start link="base" xyz="0 0 0" rpy="0 0 0" coupling="clamped"/>
    <end link="anchor" xyz="0 0 0" rpy="0 0 0" coupling="clamped"/>
    <material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>
    <section type="circle" radius="0.0005"/>
    <length value="0.3"/>
  </pcr_rod>
</robot>)";
  const auto model = std::make_shared<const RobotModel>(parse_robot_model(xml, "coinciding_ends"));
  for (const bool read_centerline : {true, false}) {
    KinematicsOptions o;
    o.tolerance = 1e-8;
    o.read_centerline = read_centerline;
    ForwardKinematics fk(model, o);
    const RobotSolution s = fk.solve(model->default_input_values());
    BOOST_TEST(!s.summary.converged(), s.summary.brief_report());
    BOOST_TEST(s.summary.message.find("inadmissible state: rod 'loop'") != std::string::npos,
               s.summary.message);
    BOOST_TEST(s.rods.at(0).min_axial_stretch <= 1e-6);
    BOOST_TEST(s.rods.at(0).centerline.empty() == !read_centerline);
    BOOST_CHECK_THROW(fk.input_jacobian(), InputError);  // no converged solution to differentiate
  }
}

BOOST_AUTO_TEST_CASE(read_centerline_false_leaves_out_only_the_centerline) {
  // Two IK objects along the same steps of the R5b teleoperation path, one without centerline samples:
  // the same solves (the read-out comes after the solve), so every other result agrees to the bit, and
  // the smallest axial stretch is the minimum over the same sample points.
  const auto teleop = load_model("stewart_gough_teleop");
  KinematicsOptions with, without;
  without.read_centerline = false;
  LinkTarget target;
  target.link = "platform";
  InverseKinematics a(teleop, {target}, with), b(teleop, {target}, without);
  for (int i = 0; i < 4; ++i) {
    Pose pose;
    pose.position = Vec3(0.0, 0.02 + 0.001 * i, 0.48 + 0.001 * i);
    const RobotSolution sa = a.solve({pose}), sb = b.solve({pose});
    BOOST_TEST_REQUIRE(sa.summary.converged(), sa.summary.brief_report());
    BOOST_TEST_REQUIRE(sb.summary.converged(), sb.summary.brief_report());
    BOOST_TEST((sa.inputs - sb.inputs).lpNorm<Eigen::Infinity>() == 0.0, "step " << i);
    BOOST_TEST((sa.platforms[0].position - sb.platforms[0].position).norm() == 0.0, "step " << i);
    BOOST_TEST_REQUIRE(sa.rods.size() == sb.rods.size());
    for (size_t r = 0; r < sa.rods.size(); ++r) {
      BOOST_TEST(sa.rods[r].centerline.size() == static_cast<size_t>(with.centerline_points));
      BOOST_TEST(sb.rods[r].centerline.empty());
      BOOST_TEST(sb.rods[r].min_axial_stretch == sa.rods[r].min_axial_stretch, "step " << i << " rod " << r);
      BOOST_TEST((sb.rods[r].tip_force - sa.rods[r].tip_force).norm() == 0.0);
      BOOST_TEST((sb.rods[r].base_moment - sa.rods[r].base_moment).norm() == 0.0);
    }
  }
}

BOOST_AUTO_TEST_CASE(admissible_solutions_report_their_smallest_axial_stretch) {
  // Steel rods under platform loads of a few N: |eps3| = |n| / EA ~ 1e-5, so v3 within 1e-3 of 1.
  const auto model = load_model("stewart_gough");
  ForwardKinematics fk(model);
  const RobotSolution s = fk.solve(moved_inputs(*model, 0.03));
  BOOST_REQUIRE_MESSAGE(s.summary.converged(), s.summary.brief_report());
  for (const RodResult& r : s.rods) BOOST_TEST(std::abs(r.min_axial_stretch - 1.0) < 1e-3, r.name);
}

BOOST_AUTO_TEST_CASE(unreachable_target_is_reported_not_hidden) {
  const auto model = load_model("stewart_gough");
  LinkTarget t;
  t.link = "platform";
  InverseKinematics ik(model, {t});
  Pose far;
  far.position = Vec3(0.0, 0.0, 1.5);  // rods are at most 0.8 m long
  const RobotSolution r = ik.solve({far});
  BOOST_TEST(!r.summary.converged(), r.summary.brief_report());
  BOOST_TEST(r.platforms[0].position.allFinite());
  BOOST_TEST(r.inputs.allFinite());
  for (int i = 0; i < r.inputs.size(); ++i) BOOST_TEST(r.inputs[i] <= model->inputs()[i].upper + 1e-9);
}

BOOST_AUTO_TEST_CASE(bad_inputs_are_rejected_with_names) {
  const auto model = load_model("stewart_gough");
  ForwardKinematics fk(model);
  BOOST_CHECK_THROW(fk.solve(VecX::Constant(5, 0.45)), InputError);
  VecX u = model->default_input_values();
  u[2] = 2.0;
  try {
    fk.solve(u);
    BOOST_FAIL("out-of-bounds input accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("leg2") != std::string::npos, e.what());
  }
  u[2] = std::nan("");
  BOOST_CHECK_THROW(fk.solve(u), InputError);
  BOOST_CHECK_THROW(
      InverseKinematics(model, {LinkTarget{"no_such_link", LinkTarget::Mode::Pose, Pose{}, kFull}}),
      InputError);
}

BOOST_AUTO_TEST_CASE(assembly_hands_out_its_coupling_and_balance_blocks) {
  // Typed handles instead of searching blocks by kind: each names the block of that rod end or platform.
  const RobotAssembly sg(load_model("stewart_gough"));
  const Problem& p = sg.problem();
  for (int i = 0; i < sg.num_rods(); ++i) {
    const std::string rod = sg.rod(i).model().name;
    BOOST_TEST(p.residual(sg.rod_coupling(i, false)).name() == rod + ".start");
    BOOST_TEST(p.residual(sg.rod_coupling(i, true)).name() == rod + ".end");
    BOOST_TEST(p.residual(sg.rod_coupling(i, true)).kind() != p.residual(sg.platform_balance(0)).kind());
  }
  BOOST_TEST(p.residual(sg.platform_balance(0)).name() == sg.model().platforms()[0].name);
  BOOST_TEST(p.residual(sg.platform_balance(0)).num_rows() == 7);
  // The cantilever's tip is free: no coupling block there.
  const RobotAssembly cantilever(load_model("cantilever"));
  BOOST_TEST(cantilever.rod_coupling(0, false) >= 0);
  BOOST_TEST(cantilever.rod_coupling(0, true) == -1);
  BOOST_CHECK_THROW(cantilever.rod_coupling(1, false), InputError);
}
