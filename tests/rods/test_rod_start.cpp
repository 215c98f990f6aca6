// The start of a cold solve_rod (RodSolveOptions::shooting_start): from a coarse shooting solve the
// collocation Newton reaches the same solution as from the stress-free shape, in fewer iterations.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "pcr/rods/rod_solve.hpp"
#include "rod_fixtures.hpp"

namespace pcr {
namespace {

// max |p_a(s) - p_b(s)| over 101 equally spaced s.
double centerline_difference(const RodSolution& a, const RodSolution& b, double length) {
  double worst = 0.0;
  for (int i = 0; i <= 100; ++i) {
    const double s = length * i / 100.0;
    worst = std::max(worst, (a.at(s).position - b.at(s).position).norm());
  }
  return worst;
}

// Solves `model` from both starts; both converge to the same discrete solution and the shooting start
// takes fewer Newton iterations. Both solves end at a dimensionless residual max-abs <= 1e-10; their
// difference is that times the condition of the Jacobian (order 1-100 for these rods): 1e-8 L bounds it
// (measured: below 1e-12 L).
void check_starts_agree(const RodModel& model, const RodDiscretization& discretization) {
  RodSolveOptions o;
  o.discretization = discretization;
  o.stability_verdict = false;
  const RodSolution from_shooting = solve_rod(model, o);
  o.shooting_start = false;
  const RodSolution from_stress_free = solve_rod(model, o);
  BOOST_REQUIRE(from_shooting.summary.converged() && from_stress_free.summary.converged());
  BOOST_TEST(from_shooting.load_steps == 0);
  BOOST_TEST(centerline_difference(from_shooting, from_stress_free, model.length) < 1e-8 * model.length);
  BOOST_TEST(from_shooting.summary.iterations < from_stress_free.summary.iterations,
             to_string(discretization.formulation) << ": " << from_shooting.summary.iterations << " against "
                                                   << from_stress_free.summary.iterations);
}

}  // namespace

BOOST_AUTO_TEST_CASE(shooting_start_reaches_the_same_solution) {
  // A full circle (tip moment 2 pi EI / L about e1, the benchmarks' R1) in each formulation.
  RodModel circle = test::cantilever(1.0, Vec3(50.0, 50.0, 100.0), Vec3(2.0, 2.0, 2.0));
  circle.tip.moment = Vec3(2.0 * M_PI * 2.0, 0.0, 0.0);
  check_starts_agree(circle, {RodFormulation::Condensed, 5, 16});
  check_starts_agree(circle, {RodFormulation::Mixed, 4, 8});
  check_starts_agree(circle, {RodFormulation::Primal, 4, 8});
  // The condensed form with a distributed load, long enough for the running integrals T (more than
  // CollocationRod::kMaxBandedCondensedPoints control points) and short enough for the summed integral.
  RodModel loaded = test::cantilever(1.0, Vec3(1e3, 1e3, 2e3), Vec3(1.0, 1.0, 0.8));
  loaded.loads.force_per_length = Vec3(2.0, 0.0, -1.0);
  loaded.tip.force = Vec3(0.0, 1.0, 0.0);
  check_starts_agree(loaded, {RodFormulation::Condensed, 4, 48});
  check_starts_agree(loaded, {RodFormulation::Condensed, 4, 8});
}

}  // namespace pcr
