// The rod formulation a robot assembly chooses: by slenderness (primal for thick rods, mixed - condensed
// where it applies - for slender ones) unless an option or the model names it, and the locking study
// behind the threshold (primal against mixed on a tip-loaded cantilever of decreasing diameter).
#include <boost/test/unit_test.hpp>

#include <iostream>
#include <memory>
#include <vector>

#include "../rods/rod_fixtures.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/rods/rod_solve.hpp"
#include "robot_fixtures.hpp"

using namespace pcr;
using test::load_model;
using test::planar_with_radius;

BOOST_AUTO_TEST_CASE(primal_locking_study) {
  // Cantilever, solid circle of diameter d, E = 1e7, nu = 0.3, tip force P L^2 / EI = 1, at the robot
  // default discretisation (AssemblyOptions), against mixed with degree 5, 64 elements. Prints the table
  // quoted at formulation_by_slenderness (robot_assembly.hpp).
  const double L = 1.0;
  const Material mat = Material::from_poisson_ratio(1e7, 0.3, 0.0);
  const AssemblyOptions defaults;
  for (double d : {0.4, 0.25, 0.2, 0.05, 0.01, 0.005}) {
    RodModel m = test::cantilever(L, Vec3::Ones(), Vec3::Ones());
    m.set_material_and_section(mat, CrossSection::circle(d / 2));
    m.tip.force = Vec3(0.0, m.bending_torsion_stiffness[0] / (L * L), 0.0);
    RodSolveOptions o;
    o.discretization = {RodFormulation::Mixed, 5, 64};
    o.tolerance = 1e-11;
    const RodSolution reference = solve_rod(m, o);
    BOOST_REQUIRE(reference.summary.converged());
    double error[2];
    bool converged[2];
    int iterations[2];
    for (RodFormulation f : {RodFormulation::Primal, RodFormulation::Mixed}) {
      o.discretization = {f, defaults.discretization.degree, defaults.discretization.elements};
      o.tolerance = 1e-10;
      o.max_iterations = 200;
      const RodSolution sol = solve_rod(m, o);
      const int k = f == RodFormulation::Mixed;
      converged[k] = sol.summary.converged();
      iterations[k] = sol.summary.iterations;
      error[k] = (sol.tip().position - reference.tip().position).norm() / L;
    }
    std::cout << "locking d/L = " << d << " (gyration ratio " << d / 4 << "): tip error / L primal "
              << error[0] << (converged[0] ? "" : " (not converged)") << " in " << iterations[0]
              << " iterations, mixed " << error[1] << " in " << iterations[1] << "\n";
    BOOST_TEST(converged[1]);
    // Mixed, degree 6, 8 elements: measured 1.20e-9 .. 1.25e-9 for all d; bound 1e-8 (8x).
    BOOST_TEST(error[1] < 1e-8);
    // Primal at and above the threshold d / L = 1/4: the threshold's criterion 1e-5 L (measured 1.8e-7
    // with degree 6, 1.0e-5 with degree 5).
    if (d / (4 * L) >= defaults.primal_min_gyration_ratio) BOOST_TEST((converged[0] && error[0] < 1e-5));
    // Well below it the primal form degrades (measured 2.1e-4 at d/L = 0.01) or does not converge.
    if (d <= 0.01) BOOST_TEST((!converged[0] || error[0] > 100 * error[1]));
  }
}

BOOST_AUTO_TEST_CASE(formulation_is_chosen_by_slenderness_unless_given) {
  // planar_three_rod: lengths up to 0.5 m. Radius 0.5 mm -> gyration ratio 2.5e-4 / 0.5 = 5e-4
  // (mixed); radius 0.07 m -> 0.035 / 0.5 = 0.07 >= 1/16 (primal).
  auto formulations = [](const std::shared_ptr<const RobotModel>& model, const AssemblyOptions& o) {
    const RobotAssembly a(model, o);
    std::vector<RodFormulation> f;
    for (int i = 0; i < a.num_rods(); ++i) f.push_back(a.rod(i).discretization().formulation);
    return f;
  };
  const auto slender = load_model("planar_three_rod");
  const auto thick = planar_with_radius(0.07);
  // sqrt(EI / EA) = r / 2 for a circle: equal up to round-off (1e-12 relative).
  BOOST_TEST(gyration_ratio(slender->rods()[0]) == 2.5e-4 / 0.5, boost::test_tools::tolerance(1e-12));
  // Slender rods: mixed, solved in the condensed form (AssemblyOptions::condense_mixed_rods) unless that
  // is switched off or the mixed form is at the Greville points (the condensed form is the midpoint
  // scheme only).
  for (RodFormulation f : formulations(slender, {})) BOOST_TEST((f == RodFormulation::Condensed));
  for (RodFormulation f : formulations(thick, {})) BOOST_TEST((f == RodFormulation::Primal));
  AssemblyOptions keep_mixed;
  keep_mixed.condense_mixed_rods = false;
  AssemblyOptions greville;
  greville.discretization.mixed_points = MixedPoints::Greville;
  // Every shipped model is slender, with gravity (R5a, ...) or without (R5b); the cantilever model names
  // the mixed form in its discretisation hint and keeps it.
  for (RodFormulation f : formulations(load_model("cantilever"), {}))
    BOOST_TEST((f == RodFormulation::Mixed));
  for (const char* name : {"stewart_gough", "stewart_gough_teleop", "two_stage", "slider_actuated"}) {
    for (RodFormulation f : formulations(load_model(name), {}))
      BOOST_TEST((f == RodFormulation::Condensed), name);
    for (RodFormulation f : formulations(load_model(name), keep_mixed))
      BOOST_TEST((f == RodFormulation::Mixed), name);
    for (RodFormulation f : formulations(load_model(name), greville))
      BOOST_TEST((f == RodFormulation::Mixed), name);
  }
  // Options switch the choice off.
  AssemblyOptions explicit_primal;
  explicit_primal.formulation_by_slenderness = false;
  explicit_primal.discretization.formulation = RodFormulation::Primal;
  for (RodFormulation f : formulations(slender, explicit_primal)) BOOST_TEST((f == RodFormulation::Primal));
  // A model hint wins over the choice.
  const std::vector<RodFormulation> hinted =
      formulations(planar_with_radius(0.07, "<discretization formulation=\"mixed\"/>"), {});
  BOOST_TEST((hinted[0] == RodFormulation::Mixed));
  BOOST_TEST((hinted[1] == RodFormulation::Primal));
  AssemblyOptions bad;
  bad.primal_min_gyration_ratio = 0.0;
  BOOST_CHECK_THROW(RobotAssembly(slender, bad), InputError);
}
