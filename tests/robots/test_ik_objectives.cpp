// IK objectives (actuation effort, elastic energy), the rod stress limit and the reduced-space IK:
// values against independent computations (strain-form energy, read_solution's axial forces, the
// stress formula on state_at), gradients against finite differences, optima against nearby feasible
// points found independently (null-space moves re-projected onto the target with FK), partial targets.
// The stress limit active / infeasible, bad options, the CLI options and a square target:
// test_ik_constraints.cpp (same executable).
#define BOOST_TEST_MODULE ik_objectives
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <map>

#include "../../robots/src/kinematics/ik_objectives.hpp"
#include "../../robots/src/kinematics/reduced_ik.hpp"
#include "ik_objective_fixtures.hpp"
#include "pcr/math/dense_decompositions.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/solve/jacobian_check.hpp"
#include "robot_fixtures.hpp"

using namespace pcr;
using test::circle_stress;
using test::fk_objectives;
using test::FkObjectives;
using test::kTarget;
using test::load_model;
using test::moved_inputs;
using test::numeric_gradient;
using test::planar_with_radius;
using test::position_target;
using test::project_onto_target;
using test::strain_energy;

BOOST_AUTO_TEST_CASE(objective_and_stress_values_match_independent_computations) {
  // 32 elements: the strain form's shear energy (from p', K_SE ~ 6e5 N) is 3x off at 8 elements
  // (3.4e-3 J vs 1.0e-3 J), within 2e-4 relative at 16 and 32 elements; the bending parts agree to
  // 5e-5 already at 8 (Simpson, 2000 intervals per rod).
  const auto model = load_model("stewart_gough");
  KinematicsOptions o;
  o.assembly.discretization.elements = 32;
  ForwardKinematics fk(model, o);
  const RobotSolution s = fk.solve(moved_inputs(*model, 0.05));
  BOOST_REQUIRE(s.summary.converged());
  const RobotAssembly& a = fk.assembly();
  const VecX& x = fk.state();
  // Effort: the same axial forces as read_solution's (interpolated at s = 0: round-off only, 1e-12).
  double effort = 0.0;
  for (const RodResult& r : s.rods) effort += 0.5 * std::pow(r.axial_force / a.force_scale(), 2);
  BOOST_TEST(kinematics::actuation_effort(a, x, nullptr) == effort, boost::test_tools::tolerance(1e-12));
  // Energy: the complementary form (n, m interpolated) against the strain form (p', q' interpolated);
  // the mixed form satisfies the constitutive law only at the collocation points, so they differ by
  // the discretisation error: measured 1.6e-8 relative here (32 elements); tolerance 1e-5.
  const double e_strain = strain_energy(a, x);
  BOOST_TEST(e_strain > 0.0);
  BOOST_TEST(kinematics::elastic_energy(a, x, nullptr) == e_strain, boost::test_tools::tolerance(1e-5));
  // Stress: the smoothing delta = 1e-9 F0 changes the value by < 1e-9 relative; tolerance 1e-8.
  const auto points = kinematics::stress_points(a, 9);
  const VecX sigma = kinematics::rod_stresses(a, x, points, nullptr);
  for (size_t j = 0; j < points.size(); ++j) {
    const CollocationRod& rod = a.rod(points[j].rod);
    const RodState st = rod.state_at(x, a.rod_variables(points[j].rod),
                                     points[j].u * rod.length(x, a.rod_variables(points[j].rod)));
    BOOST_TEST(sigma[j] == circle_stress(st, 0.001), boost::test_tools::tolerance(1e-8));
  }
}

BOOST_AUTO_TEST_CASE(objective_and_stress_gradients_match_finite_differences) {
  // Mixed rods (analytic chain rule) on R5a, condensed rods (analytic) on R5b (no distributed loads) and
  // R5a (gravity: n, m also read L and the integral of p), primal rods (local central differences) on
  // the planar robot. Central differences with h = 1e-6 (1 + |x|): truncation ~1e-12, round-off
  // ~1e-16 f / h ~1e-10 relative; tolerance 1e-6 of the gradient's max-abs.
  struct Case {
    RodFormulation formulation;
    std::string model;
  };
  for (const Case& k :
       {Case{RodFormulation::Mixed, "stewart_gough"}, Case{RodFormulation::Condensed, "stewart_gough_teleop"},
        Case{RodFormulation::Condensed, "stewart_gough"}, Case{RodFormulation::Primal, ""}}) {
    const RodFormulation formulation = k.formulation;
    const bool primal = formulation == RodFormulation::Primal;
    KinematicsOptions o;
    // Primal rods lock at R5a's slenderness (FK does not converge); 1 cm rods on the planar robot.
    o.assembly.discretization.formulation = formulation;
    if (primal) o.assembly.discretization = RodDiscretization{RodFormulation::Primal, 5, 8};
    o.assembly.formulation_by_slenderness = false;
    o.assembly.condense_mixed_rods = false;
    const auto model = primal ? planar_with_radius(0.01) : load_model(k.model);
    ForwardKinematics fk(model, o);
    BOOST_REQUIRE(fk.solve(moved_inputs(*model, 0.05)).summary.converged());
    const RobotAssembly& a = fk.assembly();
    BOOST_TEST((a.rod(0).discretization().formulation == formulation));
    const VecX x = fk.state();
    const std::string label = std::string(to_string(formulation)) + ", " + (primal ? "planar" : k.model);
    auto check = [&](const std::string& what, const VecX& analytic, const VecX& numeric) {
      const double scale = analytic.cwiseAbs().maxCoeff();
      BOOST_TEST(scale > 0.0);
      BOOST_TEST((analytic - numeric).cwiseAbs().maxCoeff() <= 1e-6 * scale,
                 what << " (" << label << "): error " << (analytic - numeric).cwiseAbs().maxCoeff() << " of "
                      << scale);
    };
    VecX g;
    kinematics::actuation_effort(a, x, &g);
    check("effort", g,
          numeric_gradient([&](const VecX& y) { return kinematics::actuation_effort(a, y, nullptr); }, x));
    kinematics::elastic_energy(a, x, &g);
    check("energy", g,
          numeric_gradient([&](const VecX& y) { return kinematics::elastic_energy(a, y, nullptr); }, x));
    const auto points = kinematics::stress_points(a, 5);
    MatX H;
    kinematics::rod_stresses(a, x, points, &H);
    for (size_t j = 0; j < points.size(); j += 3)
      check("stress " + std::to_string(j), H.row(j).transpose(),
            numeric_gradient(
                [&](const VecX& y) { return kinematics::rod_stresses(a, y, {points[j]}, nullptr)[0]; }, x));
  }
}

BOOST_AUTO_TEST_CASE(reduced_gradients_match_finite_differences_of_fk) {
  // The reduced objective, target rows and stress rows over u (each evaluation an FK solve) against
  // central differences with relative step 1e-6. Measured on the worst stress row (|N| near 0, where
  // its smoothing is strongly curved): error 0.17 at step 1e-4, 1.7e-3 at 1e-5 (O(h^2) truncation,
  // so ~2e-5 at 1e-6, of a derivative ~134), plus FK noise (x(u) to ~1e-12 relative / 1e-6 step);
  // tolerance 2e-5 absolute + relative.
  const auto model = load_model("stewart_gough");
  InverseKinematics ik(model, {position_target(kTarget)});
  const Problem& p = ik.problem();
  BOOST_REQUIRE(p.variable(ik.target_variable(0)).name == "target.platform");
  KinematicsOptions o;
  o.tolerance = 1e-12;
  ForwardKinematics fk(model, o);
  const VecX u = moved_inputs(*model, 0.05);
  BOOST_REQUIRE(fk.solve(u).summary.converged());
  VecX z(7);
  z << kTarget, 1, 0, 0, 0;
  VecX x(p.num_variables());
  x << fk.state(), z;
  for (const IkObjective objective : {IkObjective::ActuationEffort, IkObjective::ElasticEnergy}) {
    o.ik.objective = objective;
    o.ik.distance_weight = 0.1;
    o.ik.max_rod_stress = 1e8;
    kinematics::ReducedIk reduced(std::make_shared<const kinematics::ReducedIkModel>(
        ik.assembly_ptr(), p, std::vector{ik.target_residual(0)}, o));
    reduced.prepare(x, model->default_input_values());  // x holds the target pose z
    JacobianCheckOptions c;
    c.absolute_tolerance = 2e-5;
    c.relative_tolerance = 2e-5;
    const JacobianCheckResult r = check_problem_jacobian(reduced.problem(), u, c);
    BOOST_TEST(r.passed, to_string(objective) << ": " << r.to_string());
    BOOST_TEST(r.entries_checked > 6 * 3);
  }
}

BOOST_AUTO_TEST_CASE(effort_and_energy_optima_beat_nearby_feasible_points) {
  const auto model = load_model("stewart_gough");
  KinematicsOptions fo;
  fo.tolerance = 1e-12;
  ForwardKinematics fk(model, fo);
  const VecX reference = model->default_input_values();
  const double L0 = 0.45;  // any positive scale gives the same comparisons; the assembly's (model length)
  std::map<IkObjective, VecX> optimum;
  for (const IkObjective objective :
       {IkObjective::InputDistance, IkObjective::ActuationEffort, IkObjective::ElasticEnergy}) {
    KinematicsOptions o;
    o.ik.objective = objective;
    InverseKinematics ik(model, {position_target(kTarget)}, o);
    const RobotSolution s = ik.solve({Pose{kTarget, Quat(1, 0, 0, 0)}}, &reference);
    BOOST_REQUIRE_MESSAGE(s.summary.converged(), to_string(objective) << ": " << s.summary.brief_report());
    BOOST_TEST_MESSAGE(to_string(objective) << ": " << s.summary.brief_report());
    // Target reached: target_tolerance 1e-9 on (x - x_t) / L0 (L0 = 0.45 m), plus FK noise.
    BOOST_TEST((s.platforms[0].position - kTarget).norm() < 1e-8);
    optimum[objective] = s.inputs;
    // The objective at the optimum and at nearby feasible points: u* moved by 5 mm along each null
    // vector of the position Jacobian, both ways, re-projected onto the target. A local minimum is
    // no worse than any of them; the margin 1e-7 relative covers Ipopt's tol 1e-8 on the scaled problem.
    auto value = [&](const VecX& u) {
      const FkObjectives f = fk_objectives(fk, u);
      BOOST_REQUIRE(f.converged);
      if (objective == IkObjective::ActuationEffort) return f.effort;
      if (objective == IkObjective::ElasticEnergy) return f.energy;
      return 0.5 * ((u - reference) / L0).squaredNorm();
    };
    const double f_opt = value(s.inputs);
    BOOST_REQUIRE(fk.solve(s.inputs).summary.converged());
    const MatX J = fk.input_jacobian().topRows(3);
    const RightSingularVectors svd = right_singular_vectors(J);
    int compared = 0;
    for (int k = 3; k < 6; ++k)
      for (const double sign : {-1.0, 1.0}) {
        VecX u = s.inputs + sign * 0.005 * svd.V.col(k);
        BOOST_REQUIRE(project_onto_target(fk, u, kTarget));
        const double f_near = value(u);
        BOOST_TEST(f_opt <= f_near * (1.0 + 1e-7), to_string(objective)
                                                       << ": f* = " << f_opt << ", nearby " << f_near);
        ++compared;
      }
    BOOST_TEST(compared == 6);
  }
  // The optima differ: each is strictly better in its own measure than the others' optima (margins
  // 1e-4 relative, far above the optimality tolerance).
  const FkObjectives at_distance = fk_objectives(fk, optimum[IkObjective::InputDistance]);
  const FkObjectives at_effort = fk_objectives(fk, optimum[IkObjective::ActuationEffort]);
  const FkObjectives at_energy = fk_objectives(fk, optimum[IkObjective::ElasticEnergy]);
  BOOST_TEST(at_effort.effort < at_distance.effort * (1.0 - 1e-4));
  BOOST_TEST(at_energy.energy < at_distance.energy * (1.0 - 1e-4));
  BOOST_TEST(at_effort.effort < at_energy.effort * (1.0 - 1e-4));
  BOOST_TEST(at_energy.energy < at_effort.energy * (1.0 - 1e-4));
  BOOST_TEST((optimum[IkObjective::ActuationEffort] - optimum[IkObjective::InputDistance]).norm() > 1e-4);
}
