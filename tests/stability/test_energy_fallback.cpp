// The last FK strategy (robots/src/kinematics/energy_fallback.hpp, internal): minimise the total potential
// energy (energy_model.hpp) with Ipopt, then Newton on the collocation equations, accepted only at a
// stable equilibrium. Checked: the energy's gradient and the constraint Jacobians and Hessians against
// finite differences; the strategy reaching the ordinary FK result where that is stable; the passive_hinge
// input that every other strategy fails on, converged to an equilibrium that the tests' independent
// discrete energy model (robot_discrete.hpp) also finds stable; universal_passive and universal_pair inputs
// (a minimiser beyond the joint limits; a rod nearly at a conjugate point). With contact:
// test_energy_fallback_contact.cpp (same executable).
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "kinematics/energy_fallback.hpp"
#include "kinematics/energy_model.hpp"
#include "kinematics/energy_terms.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/robot_stability.hpp"
#include "pcr/rods/rod_contact.hpp"
#include "pcr/solve/ipopt_solver.hpp"
#include "pcr/solve/jacobian_check.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "robot_fixtures.hpp"
#include "stability/energy_fallback_fixtures.hpp"
#include "stability/energy_minimum.hpp"
#include "stability/robot_discrete.hpp"

using namespace pcr;
using namespace pcr::kinematics;
using test::block_values;
using test::default_state;
using test::Fk;
using test::load_model;

BOOST_AUTO_TEST_SUITE(energy_fallback)

// The energy's gradient and the constraint rows' Jacobians (check_problem_jacobian's defaults: central
// differences with relative step 1e-6, entries within 1e-6 + 1e-6 relative) and Hessians, at a state off
// the equilibrium and off the constraints (the default equilibrium of passive_hinge, moved by 1e-4: its
// passive joint, platform and clamped and spherical couplings are all in the energy). Not by 1e-2: there the
// axial strains make the energy 1e4 times larger, and its round-off in the differences (eps |V| / h) exceeds
// the 1e-6 tolerance.
BOOST_AUTO_TEST_CASE(gradient_and_jacobians_against_finite_differences) {
  Fk fk(load_model("passive_hinge"));
  const VecX& start = default_state(fk);
  const EnergyModel energy(*fk.assembly, start);
  const Problem& p = energy.problem();
  const VecX e = energy.perturbed(energy.from_state(start), 1e-4);
  const JacobianCheckResult all = check_problem_jacobian(p, e);
  BOOST_TEST(all.passed, all.to_string());
  // The Hessians of the constraint rows, with weights of mixed signs (as Ipopt's multipliers).
  for (int b = 0; b < p.num_residual_blocks(); ++b) {
    const ResidualBlock& block = p.residual(b);
    const VecX weights = VecX::LinSpaced(block.num_rows(), -1.0, 2.0);
    const JacobianCheckResult h = check_block_hessian(block, block_values(p, block.variables(), e), weights);
    BOOST_TEST(h.passed, block.kind() + ": " + h.to_string());
  }
  // The rod's Hessian (exact: second-order forward mode per quadrature node) against differences of the
  // whole gradient: entries within 1e-5 of the largest (differences with steps 1e-6: errors ~1e-10
  // relative to the gradient's size, amplified by the stiff axial terms' 1e5 range of scales).
  const CollocationRod& rod = fk.assembly->rod(0);
  std::vector<VariableId> points;
  for (int k = 0; k < rod.num_control_points(); ++k) points.push_back(k);  // rod 0's blocks come first
  const RodEnergyTerm term(rod, rod.length(start, fk.assembly->rod_variables(0)), points, 1.0);
  const std::vector<VecX> values = block_values(p, points, e);
  std::vector<const double*> pointers;
  for (const VecX& v : values) pointers.push_back(v.data());
  const int n = 7 * rod.num_control_points();
  MatX exact(n, n), differences(n, n);
  term.evaluate_hessian(pointers.data(), exact.data());
  gradient_difference_hessian(term, std::vector<int>(points.size(), 7), pointers.data(), differences.data());
  const double largest = exact.cwiseAbs().maxCoeff();
  BOOST_TEST_MESSAGE("rod Hessian against differences: "
                     << (exact - differences).cwiseAbs().maxCoeff() / largest << " of the largest entry");
  BOOST_TEST((exact - differences).cwiseAbs().maxCoeff() <= 1e-5 * largest);
}

// The coupling rows of the other kinds (revolute: planar_pinned, universal on links moved by actuated
// joints: six_rus, collar: slider_actuated) against finite differences, as above, at the straight initial
// guess moved by 1e-3.
BOOST_AUTO_TEST_CASE(coupling_rows_of_every_kind_against_finite_differences) {
  for (const char* name : {"planar_pinned", "six_rus", "slider_actuated"}) {
    const auto model = load_model(name);
    const RobotAssembly assembly(model);
    const VecX x = assembly.initial_guess();
    const EnergyModel energy(assembly, x);
    const Problem& p = energy.problem();
    const VecX e = energy.perturbed(energy.from_state(x), 1e-3);
    int couplings = 0;
    for (int b = 0; b < p.num_residual_blocks(); ++b) {
      const ResidualBlock& block = p.residual(b);
      if (block.kind() != "energy.coupling") continue;
      ++couplings;
      const std::vector<VecX> values = block_values(p, block.variables(), e);
      const JacobianCheckResult j = check_block_jacobian(block, values);
      BOOST_TEST(j.passed, name << ": " << j.to_string());
      const JacobianCheckResult h =
          check_block_hessian(block, values, VecX::LinSpaced(block.num_rows(), -1.0, 2.0));
      BOOST_TEST(h.passed, name << ": " << h.to_string());
    }
    BOOST_TEST(couplings == 2 * model->rods().size());
  }
}

// stewart_gough at its default inputs: the ordinary FK result is stable (test_robot_verdict). From the
// straight initial guess (not an equilibrium) the strategy reaches the same equilibrium: the platform within
// 1e-9 m and 1e-9 rad (both are Newton solutions of the same equations to the tolerance 1e-10 (scaled):
// their distance is the conditioning times that, measured 1e-12). The Ipopt minimiser alone (the Ritz
// form's own discrete equilibrium, an independent discretisation of the same rods) is within 1e-8 m of
// it: the two discretisation errors at degree 6, 8 elements (the collocation's platform error is 1.8e-10
// m here, docs/benchmarks.md "Robots"; the gap measured 1.7e-10 m).
BOOST_AUTO_TEST_CASE(reaches_the_ordinary_fk_result_where_it_is_stable) {
  const auto model = load_model("stewart_gough");
  ForwardKinematics ordinary(model);
  const RobotSolution reference = ordinary.solve(model->default_input_values());
  BOOST_TEST_REQUIRE(reference.summary.converged());
  Fk fk(model);
  const VecX straight = fk.assembly->initial_guess();
  const EnergyFallback r = minimise_energy_then_newton(fk.data, model->default_input_values(),
                                                       {{&straight, "the straight initial guess"}});
  BOOST_TEST_REQUIRE(r.converged, r.message);
  BOOST_TEST(r.message.find("stable") != std::string::npos, r.message);
  const Pose pose = fk.assembly->platform_pose(r.x, 0);
  BOOST_TEST((pose.position - reference.platforms[0].position).norm() <= 1e-9);
  BOOST_TEST(rotation_angle_between(pose.rotation(), reference.platforms[0].rotation()) <= 1e-9);
  // The minimiser of the Ritz form alone, from the same start.
  VecX xs = straight;
  fk.assembly->set_inputs(xs, model->default_input_values());
  const EnergyModel energy(*fk.assembly, xs);
  VecX e = energy.from_state(xs);
  IpoptOptions o;
  o.constraint_tolerance = 1e-10;
  IpoptSolver ipopt(energy.problem(), o);
  BOOST_TEST_REQUIRE(ipopt.solve(e).converged());
  energy.to_state(e, xs);
  const double ritz_gap =
      (fk.assembly->platform_pose(xs, 0).position - reference.platforms[0].position).norm();
  BOOST_TEST_MESSAGE("Ritz minimiser's platform off the collocation's by " << ritz_gap << " m");
  BOOST_TEST(ritz_gap <= 1e-8);
}

// models/cantilever.urdf (mixed form, degree 4, 8 elements: N, M mapped from the constitutive law; a dead
// force on its free tip, gravity): from the straight rod, the strategy reaches the ordinary FK's tip to
// 1e-9 m (both Newton solutions of the same equations to the tolerance), and the Ritz minimiser alone is
// within 1e-6 m of it (the two discretisations' errors at degree 4, 8 elements; measured 3.9e-8 m, the
// tip sagging 0.039 m).
BOOST_AUTO_TEST_CASE(cantilever_with_a_dead_tip_force) {
  const auto model = load_model("cantilever");
  ForwardKinematics ordinary(model);
  const RobotSolution reference = ordinary.solve(VecX(0));
  BOOST_TEST_REQUIRE(reference.summary.converged());
  const Vec3 tip = reference.rods[0].centerline.back();
  Fk fk(model);
  const RodVariables& vars = fk.assembly->rod_variables(0);
  const auto tip_of = [&](const VecX& x) {
    return fk.assembly->rod(0).state_at(x, vars, fk.assembly->rod(0).length(x, vars)).position;
  };
  const VecX straight = fk.assembly->initial_guess();
  const EnergyFallback r = minimise_energy_then_newton(fk.data, VecX(0), {{&straight, "the straight rod"}});
  BOOST_TEST_REQUIRE(r.converged, r.message);
  BOOST_TEST((tip_of(r.x) - tip).norm() <= 1e-9);
  VecX xs = straight;
  const EnergyModel energy(*fk.assembly, xs);
  VecX e = energy.from_state(xs);
  IpoptOptions o;
  o.constraint_tolerance = 1e-10;
  IpoptSolver ipopt(energy.problem(), o);
  BOOST_TEST_REQUIRE(ipopt.solve(e).converged());
  energy.to_state(e, xs);
  BOOST_TEST_MESSAGE("cantilever: Ritz tip off the collocation's by " << (tip_of(xs) - tip).norm()
                                                                      << " m, sag " << tip.z() << " m");
  BOOST_TEST((tip_of(xs) - tip).norm() <= 1e-6);
}

// passive_hinge at 0.260 0.166 0.416 m: every earlier strategy fails there (a fold of a branch with 2
// unstable modes on the way from the default inputs; docs/benchmarks.md "Random FK sweeps"). From the
// default equilibrium (itself unstable: 1 mode) the energy minimisation reaches an equilibrium out of the
// robot's plane that the verdict calls stable; checked: the collocation residual within the tolerance, the
// rod lengths equal to the inputs (fixed variables: to the last bit), and the independent discrete energy
// model (16 segments per rod, robot_discrete.hpp) relaxed from it: no negative and no zero eigenvalue.
BOOST_AUTO_TEST_CASE(passive_hinge_input_that_all_other_strategies_fail_on) {
  const auto model = load_model("passive_hinge");
  Fk fk(model);
  const VecX& start = default_state(fk);
  const VecX inputs = (VecX(3) << 0.260, 0.166, 0.416).finished();
  const EnergyFallback r =
      minimise_energy_then_newton(fk.data, inputs, {{&start, "the default equilibrium"}});
  BOOST_TEST_REQUIRE(r.converged, r.message);
  VecX c;
  fk.assembly->problem().evaluate_residuals(r.x, c);
  BOOST_TEST(c.cwiseAbs().maxCoeff() <= KinematicsOptions{}.tolerance);
  BOOST_TEST((fk.assembly->inputs(r.x) - inputs).cwiseAbs().maxCoeff() == 0.0);
  for (int i = 0; i < fk.assembly->num_rods(); ++i)
    BOOST_TEST(fk.assembly->rod(i).length(r.x, fk.assembly->rod_variables(i)) == inputs[i]);
  const Stability verdict = robot_stability(*fk.assembly, r.x);
  BOOST_TEST(to_string(verdict.verdict) == std::string("stable"), verdict.reason);
  // The verdict the result carries (FK reports it instead of computing it again) is that of r.x.
  BOOST_TEST(to_string(r.verdict.verdict) == std::string("stable"));
  BOOST_TEST(r.verdict.margin == verdict.margin);
  BOOST_TEST(r.verdict.rod_unstable_modes == verdict.rod_unstable_modes);
  const test::DiscreteRods::Inertia d = test::discrete_robot_inertia(*fk.assembly, r.x, 16);
  BOOST_TEST(d.negative == 0);
  BOOST_TEST(d.zero == 0);
  // Off the robot's plane (y = 0): the in-plane equilibria there are saddles.
  BOOST_TEST(std::abs(fk.assembly->platform_pose(r.x, 0).position.y()) > 1e-3);
}

// universal_passive at two inputs of the random sweeps on which every other strategy fails, warm and cold
// (every continuation stops short of them; the fold-aware one at a fold of the stable branch with nothing
// as stable to snap to). The energy's minimiser there has universal joints turned beyond their +-1 rad
// URDF limits, which FK does not enforce (docs/model_format.md): with the passive joints bounded by them,
// Ipopt stopped on a bound (0.287075 ...: 1.498 J, Newton then reached an equilibrium with 4 unstable
// modes; 0.246028 ...: 1.117 J, no Newton convergence), a point that is no equilibrium of the model. From
// the unbounded minimiser Newton reaches a stable equilibrium. Checked without the code that found it: the
// residual recomputed, the rod lengths equal to the inputs, the verdict computed again, a joint beyond
// its limits (why the minimiser must not be bounded), and Newton from the state with its platform moved
// by 1 mm back to it to 1e-9 m (an isolated, regular equilibrium: two states within the tolerance of one
// differ by its compliance times the residual). About 5 s per input in Release.
BOOST_AUTO_TEST_CASE(universal_passive_inputs_whose_minimiser_lies_beyond_the_joint_limits) {
  const auto model = load_model("universal_passive");
  Fk fk(model);
  const VecX& start = default_state(fk);
  const Problem& problem = fk.assembly->problem();
  const double tolerance = KinematicsOptions{}.tolerance;
  const std::vector<VecX> input_sets{
      (VecX(6) << 0.287075, 0.242793, 0.349163, 0.343611, 0.208591, 0.259523).finished(),
      (VecX(6) << 0.24602791487963457, 0.32788986923828267, 0.26345571802871071, 0.23911398215607094,
       0.32614241623191864, 0.33730220055404914)
          .finished()};
  for (const VecX& inputs : input_sets) {
    const EnergyFallback r =
        minimise_energy_then_newton(fk.data, inputs, {{&start, "the default equilibrium"}});
    BOOST_TEST_MESSAGE("universal_passive at leg0 = " << inputs[0] << ": " << r.message);
    BOOST_TEST_REQUIRE(r.converged, r.message);
    VecX c;
    problem.evaluate_residuals(r.x, c);
    BOOST_TEST(c.cwiseAbs().maxCoeff() <= tolerance);
    for (int i = 0; i < fk.assembly->num_rods(); ++i)
      BOOST_TEST(fk.assembly->rod(i).length(r.x, fk.assembly->rod_variables(i)) == inputs[i]);
    const Stability verdict = robot_stability(*fk.assembly, r.x);
    BOOST_TEST(to_string(verdict.verdict) == std::string("stable"), verdict.reason);
    BOOST_TEST(r.verdict.margin == verdict.margin);
    double beyond = 0.0;  // the largest excess of a passive joint over its limits [rad]
    for (size_t i = 0; i < model->passive_joints().size(); ++i) {
      const Joint& joint = model->joints()[model->passive_joints()[i]];
      const double q = r.x[problem.variable(fk.assembly->passive_joint_variable(static_cast<int>(i))).offset];
      beyond = std::max({beyond, q - joint.upper, joint.lower - q});
    }
    BOOST_TEST(beyond > 0.1);
    VecX x = r.x;
    const int platform = problem.variable(fk.assembly->platform_variable(0)).offset;
    x.segment<3>(platform) += Vec3(1e-3, 0.0, 0.0);
    NewtonOptions no;
    no.tolerance = tolerance;
    NewtonSolver newton(problem, no);
    BOOST_TEST_REQUIRE(newton.solve(x).converged());
    BOOST_TEST((x.segment<3>(platform) - r.x.segment<3>(platform)).norm() < 1e-9);
  }
}

// universal_pair at a cold input of the random sweep on which every other strategy fails (every
// continuation stops at a fold 0.355 of the line from the default inputs with nothing as stable to snap
// to). From the default equilibrium Ipopt reaches a minimiser (1.832 J) and Newton the collocation's
// equilibrium next to it, where leg5 is nearly at a conjugate point with its links held: its probe
// eigenvalue (8.9e-6) lies within the neutral tolerance of the requested mesh (0.1 x its strain mismatch,
// 1.9e-5), so the count there is taken on the energy's Ritz form, which has no equilibrium next to it.
// On twice the elements (refined_verdict.hpp) the mismatch falls to 1.5e-6 and the eigenvalue (3.4e-5)
// is clear of the tolerance (1e-5): stable. Checked without the code that found it: the residual, the
// rod lengths, and on 32 elements (the equilibrium carried there and solved again; its platform moves by
// 1.5e-6 m) the verdict and an energy minimisation started next to it (moved by 1e-3 L0) returning to it:
// the platform within 1e-5 m and the energy to 1e-5 relative (the Ritz minimiser against the
// collocation's equilibrium, as for planar_post below; measured 5e-11 m), i.e. a minimum of the energy.
// On 8 elements the two discretisations differ more (1.1e-5 m, 3.5e-5 relative: leg5 is strongly bent).
// About 7 s in Release.
BOOST_AUTO_TEST_CASE(universal_pair_input_with_a_rod_nearly_at_a_conjugate_point) {
  const auto model = load_model("universal_pair");
  Fk fk(model);
  const VecX& start = default_state(fk);
  const RobotAssembly& a = *fk.assembly;
  const VecX inputs = (VecX(6) << 0.31281147723570213, 0.32566380103291415, 0.29152448581449447,
                       0.31252541526064515, 0.21380791917257755, 0.34806431545992006)
                          .finished();
  const EnergyFallback r =
      minimise_energy_then_newton(fk.data, inputs, {{&start, "the default equilibrium"}});
  BOOST_TEST_MESSAGE("universal_pair: " << r.message);
  BOOST_TEST_REQUIRE(r.converged, r.message);
  VecX c;
  a.problem().evaluate_residuals(r.x, c);
  BOOST_TEST(c.cwiseAbs().maxCoeff() <= KinematicsOptions{}.tolerance);
  for (int i = 0; i < a.num_rods(); ++i) BOOST_TEST(a.rod(i).length(r.x, a.rod_variables(i)) == inputs[i]);
  const Stability requested = robot_stability(a, r.x);
  BOOST_TEST(requested.reason.find("rod 'leg5' is at a conjugate point") == 0u, requested.reason);
  BOOST_TEST(to_string(r.verdict.verdict) == std::string("stable"), r.verdict.reason);
  BOOST_TEST(r.verdict.reason.find("counted on 16 elements per rod") == 0u, r.verdict.reason);
  AssemblyOptions o = a.options();
  o.discretization.elements = 32;
  const RobotAssembly fine(model, o);
  const VecX xf = test::carried_to(a, r.x, fine);
  const Stability v = robot_stability(fine, xf);
  BOOST_TEST_MESSAGE(
      "32 elements: " << to_string(v.verdict) << " (margin " << v.margin << ", platform moved "
                      << (fine.platform_pose(xf, 0).position - a.platform_pose(r.x, 0).position).norm()
                      << " m)");
  BOOST_TEST(to_string(v.verdict) == std::string("stable"), v.reason);
  Vec3 platform;
  const double minimum = test::energy_minimised_from(fine, xf, 1e-3, platform);
  const double V = test::energy_at(fine, xf);
  BOOST_TEST_MESSAGE("minimised again: " << minimum << " J against " << V << " J, platform off by "
                                         << (platform - fine.platform_pose(xf, 0).position).norm() << " m");
  BOOST_TEST((platform - fine.platform_pose(xf, 0).position).norm() <= 1e-5);
  BOOST_TEST(std::abs(minimum - V) <= 1e-5 * std::abs(V));
}

BOOST_AUTO_TEST_SUITE_END()
