// IK with a rod stress limit (active and satisfied; infeasible, reported), bad IK options rejected with
// their names, the CLI's objective and stress options, and a full pose target that leaves no freedom
// (the Newton inputs whatever the objective).
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "ik_objective_fixtures.hpp"
#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/robots/kinematics.hpp"
#include "robot_fixtures.hpp"

#define PCR_CLI_WORK_DIRECTORY "pcr_test_ik_constraints"
#include "cli/cli_runner.hpp"

using namespace pcr;
using test::kPi;
using test::kTarget;
using test::load_model;
using test::max_stress;
using test::model_path;
using test::position_target;

BOOST_AUTO_TEST_CASE(partial_targets_go_to_the_reduced_space_and_agree_with_the_full_space) {
  // Position-only targets leave inputs free: the input distance is minimised in the reduced space by
  // default. On the planar robot (3 inputs, x and z targeted) the full-space Ipopt (IkOptions::
  // full_space) converges as well and must reach the same optimum: both satisfy the equations to the
  // tolerance 1e-10 and Ipopt's optimality to 1e-8 (scaled), so the inputs agree to ~1e-8 L; bound 1e-6 m.
  const auto planar = load_model("planar_three_rod");
  LinkTarget t = position_target(Vec3(0.01, 0.0, 0.29));
  t.components = {true, false, true, false, false, false};  // x, z
  const std::vector<Pose> pose{Pose{t.pose.position, Quat(1, 0, 0, 0)}};
  InverseKinematics reduced(planar, {t});
  KinematicsOptions o;
  o.ik.full_space = true;
  InverseKinematics full(planar, {t}, o);
  const VecX reference = planar->default_input_values();
  const RobotSolution a = reduced.solve(pose, &reference), b = full.solve(pose, &reference);
  BOOST_REQUIRE_MESSAGE(a.summary.converged(), a.summary.brief_report());
  BOOST_REQUIRE_MESSAGE(b.summary.converged(), b.summary.brief_report());
  BOOST_TEST(a.summary.solver == "ipopt (reduced)");
  BOOST_TEST(b.summary.solver == "ipopt");
  BOOST_TEST((a.inputs - b.inputs).lpNorm<Eigen::Infinity>() < 1e-6, a.inputs.transpose()
                                                                         << " | " << b.inputs.transpose());
  // stewart_gough, position only (3 of 6 inputs free): the reduced space converges (the full space did
  // not: IkOptions::full_space) and reaches the target to its tolerance 1e-9 L0 (L0 = 0.45 m) + FK noise.
  const auto sg = load_model("stewart_gough");
  InverseKinematics ik(sg, {position_target(kTarget)});
  const VecX sg_reference = sg->default_input_values();
  const RobotSolution s = ik.solve({Pose{kTarget, Quat(1, 0, 0, 0)}}, &sg_reference);
  BOOST_REQUIRE_MESSAGE(s.summary.converged(), s.summary.brief_report());
  BOOST_TEST((s.platforms[0].position - kTarget).norm() < 1e-8);
}

BOOST_AUTO_TEST_CASE(stress_limit_is_active_and_satisfied) {
  // The limit is 70 % of the max stress at the distance optimum (reduced space). The distance
  // objective has several local optima near the target, with max stresses (measured at the default
  // mesh) of 9.7e8 Pa (the one reached here, input distance 62.42 mm), 9.55e8 Pa (62.48 mm, reached
  // at 32 elements) and 1.25e9 Pa (62.01 mm, reached without IkOptions::max_input_step); 70 % is below
  // all of them, so the limit must bind whichever one Ipopt approaches, and it is reachable (the
  // effort optimum has 4.6e8 Pa).
  const auto model = load_model("stewart_gough");
  const VecX reference = model->default_input_values();
  const std::vector<Pose> target{Pose{kTarget, Quat(1, 0, 0, 0)}};
  InverseKinematics free_ik(model, {position_target(kTarget)});
  const RobotSolution s_free = free_ik.solve(target, &reference);
  BOOST_REQUIRE(s_free.summary.converged());
  const int points = 2 * AssemblyOptions().discretization.elements + 1;  // the default: 2 elements + 1
  const double sigma_free = max_stress(free_ik.assembly(), free_ik.state(), points, 0.001);
  BOOST_TEST_MESSAGE("max stress at the distance optimum: " << sigma_free << " Pa");
  KinematicsOptions o;
  o.ik.max_rod_stress = 0.7 * sigma_free;
  InverseKinematics ik(model, {position_target(kTarget)}, o);
  const RobotSolution s = ik.solve(target, &reference);
  BOOST_REQUIRE_MESSAGE(s.summary.converged(), s.summary.brief_report());
  BOOST_TEST_MESSAGE(s.summary.brief_report());
  const double sigma = max_stress(ik.assembly(), ik.state(), points, 0.001);
  // Satisfied: rows sigma / sigma_max <= 1 within target_tolerance 1e-9 (the smoothing only
  // overestimates); active: the unconstrained optimum violates the limit, so it must bind (to
  // Ipopt's tol 1e-8 on the complementarity); tolerances 1e-8 and 1e-6 relative.
  BOOST_TEST(sigma <= *o.ik.max_rod_stress * (1.0 + 1e-8));
  BOOST_TEST(sigma >= *o.ik.max_rod_stress * (1.0 - 1e-6));
  BOOST_TEST((s.platforms[0].position - kTarget).norm() < 1e-8);
  // The limit costs distance (margin 1e-6 relative, above the optimality tolerance).
  const double d_free = (s_free.inputs - reference).squaredNorm(), d = (s.inputs - reference).squaredNorm();
  BOOST_TEST(d > d_free * (1.0 + 1e-6));
}

BOOST_AUTO_TEST_CASE(infeasible_stress_limit_is_reported) {
  // 1 kPa: gravity alone (platform 0.1 kg on six 1 mm rods) gives axial stresses ~1e5 Pa.
  const auto model = load_model("stewart_gough");
  KinematicsOptions o;
  o.ik.objective = IkObjective::ElasticEnergy;
  o.ik.max_rod_stress = 1e3;
  InverseKinematics ik(model, {position_target(kTarget)}, o);
  const RobotSolution s = ik.solve({Pose{kTarget, Quat(1, 0, 0, 0)}});
  BOOST_TEST(!s.summary.converged(), s.summary.brief_report());
  BOOST_TEST(s.inputs.allFinite());
  BOOST_TEST(s.platforms[0].position.allFinite());
  BOOST_TEST(std::isfinite(s.summary.objective));
}

BOOST_AUTO_TEST_CASE(bad_ik_options_are_rejected_with_names) {
  const auto model = load_model("stewart_gough");
  auto make = [&](const KinematicsOptions& o) { InverseKinematics ik(model, {position_target(kTarget)}, o); };
  KinematicsOptions o;
  o.ik.objective = IkObjective::ActuationEffort;
  o.ik.distance_weight = -1.0;
  BOOST_CHECK_THROW(make(o), InputError);
  o.ik.distance_weight = 0.0;
  o.ik.max_rod_stress = -5.0;
  BOOST_CHECK_THROW(make(o), InputError);
  o.ik.max_rod_stress = 1e8;
  o.ik.max_input_step = 0.0;
  BOOST_CHECK_THROW(make(o), InputError);
  o.ik.max_input_step = 0.05;
  o.ik.stress_points_per_rod = 1;
  BOOST_CHECK_THROW(make(o), InputError);
  try {
    o.ik.stress_points_per_rod = 1;
    make(o);
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("stress_points_per_rod = 1") != std::string::npos, e.what());
  }
  // A robot without fed rods has no effort objective.
  const auto slider = load_model("slider_actuated");
  LinkTarget t = position_target(kTarget);
  KinematicsOptions e;
  e.ik.objective = IkObjective::ActuationEffort;
  BOOST_CHECK_THROW(InverseKinematics(slider, {t}, e), InputError);
}

BOOST_AUTO_TEST_CASE(cli_objective_and_stress_options) {
  const std::string ik = "ik '" + model_path("stewart_gough") + "' --target platform=0.01,-0.015,0.41";
  const Run effort = run_pcr(ik + " --objective effort --json");
  BOOST_TEST(effort.exit_code == 0, effort.err);
  BOOST_TEST(contains(effort.out, "objective effort"), effort.out);
  BOOST_TEST(contains(effort.out, "\"status\": \"converged\""), effort.out);
  // An unreachable stress limit: solve failed (exit code 1), reported as infeasible.
  const Run infeasible = run_pcr(ik + " --objective energy --max-stress 1e3 --json");
  BOOST_TEST(infeasible.exit_code == 1);
  BOOST_TEST(contains(infeasible.out, "infeasible"), infeasible.out);
  // Bad values are usage errors (exit code 2) naming the option.
  const Run bad_objective = run_pcr(ik + " --objective speed");
  BOOST_TEST(bad_objective.exit_code == 2);
  BOOST_TEST(contains(bad_objective.err, "--objective speed"), bad_objective.err);
  const Run bad_stress = run_pcr(ik + " --max-stress -5");
  BOOST_TEST(bad_stress.exit_code == 2);
  BOOST_TEST(contains(bad_stress.err, "--max-stress -5"), bad_stress.err);
  // --formulation condensed solves R5a's rods under gravity (n, m with the integral of p); the
  // agreement with the mixed form is tested in test_kinematics and test_shooting_crosscheck.
  const Run condensed = run_pcr(ik + " --formulation condensed --json");
  BOOST_TEST(condensed.exit_code == 0, condensed.err);
  BOOST_TEST(contains(condensed.out, "\"status\": \"converged\""), condensed.out);
  const Run help = run_pcr("ik --help");
  BOOST_TEST(contains(help.out, "--objective distance|effort|energy"));
  BOOST_TEST(contains(help.out, "--formulation auto|mixed|condensed|primal"));
}

BOOST_AUTO_TEST_CASE(square_target_gives_the_newton_inputs_whatever_the_objective) {
  // R5a full pose target: no freedom left, so the reduced-space solve must land on the inputs of the
  // square Newton path. Both solve to 1e-10 dimensionless residuals; the inputs agree to ~1e-10 m,
  // tolerance 1e-8 m.
  const auto model = load_model("stewart_gough");
  LinkTarget t;
  t.link = "platform";
  t.pose.position = Vec3(0.0, 0.0, 0.4);
  t.pose.orientation = quat_from_rotation_vector(Vec3(0.0, 10.0 * kPi / 180.0, 0.0));
  InverseKinematics newton(model, {t});
  const RobotSolution s_newton = newton.solve({t.pose});
  BOOST_REQUIRE(s_newton.summary.converged());
  BOOST_TEST(s_newton.summary.solver == "newton");
  KinematicsOptions o;
  o.ik.objective = IkObjective::ElasticEnergy;
  InverseKinematics reduced(model, {t}, o);
  const RobotSolution s = reduced.solve({t.pose});
  BOOST_REQUIRE_MESSAGE(s.summary.converged(), s.summary.brief_report());
  BOOST_TEST((s.inputs - s_newton.inputs).cwiseAbs().maxCoeff() < 1e-8);
}
