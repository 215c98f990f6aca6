// Paths through folds on shipped models (path_through_folds.hpp): snaps past folds where the branch beyond
// does not come back (Newton from the pushed fold state, the damped motion), steps after a snap in the
// landing's metric, and a corner of a contact switch. Each landing is checked without the code that found
// it: the residual recomputed, Newton from a perturbed landing back to it, and the verdict; the contact
// corner against natural-parameter continuation.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "kinematics/pseudo_transient_snap.hpp"
#include "paths/path_fixtures.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/path_through_folds.hpp"
#include "pcr/robots/robot_stability.hpp"
#include "pcr/solve/newton_solver.hpp"

using namespace pcr;
using test::landing_of;
using test::platform_position;
using test::shipped;
namespace tt = boost::test_tools;

namespace {

/// Checks a snap's landing state without the code that found it: the residual recomputed (converged means
/// max-abs of the dimensionless residuals <= the FK tolerance, newton_solver.hpp); Newton from the landing
/// with its platform moved by 1 mm (0.2-0.3 % of the rods' length, far outside the 1e-10 tolerance) comes
/// back to it to 1e-9 m, six orders below the perturbation and the jump (two states within the tolerance
/// of one regular equilibrium differ by its compliance times the residual; 3e-14 m measured), so it is an
/// isolated, regular equilibrium and not the fold; its verdict is stable.
void check_stable_isolated_landing(const RobotAssembly& a, const VecX& landing, double tolerance) {
  const Problem& problem = a.problem();
  VecX c;
  problem.evaluate_residuals(landing, c);
  BOOST_TEST((c - problem.row_lower()).cwiseAbs().maxCoeff() <= tolerance);
  VecX x = landing;
  x.segment<3>(problem.variable(a.platform_variable(0)).offset) += Vec3(1e-3, 0.0, 0.0);
  NewtonOptions no;
  no.tolerance = tolerance;
  NewtonSolver newton(problem, no);
  BOOST_TEST_REQUIRE(newton.solve(x).converged());
  const double back = (platform_position(a, x) - platform_position(a, landing)).norm();
  BOOST_TEST_MESSAGE("Newton from the perturbed landing: back to " << back << " m");
  BOOST_TEST(back < 1e-9);
  const Stability v = robot_stability(a, landing);
  BOOST_TEST(to_string(v.verdict) == std::string("stable"), v.reason);
  BOOST_TEST(v.margin > 0.0);
}

}  // namespace

/// From the default lengths a quarter of the way towards the failing sweep input below.
std::vector<VecX> planar_pinned_quarter_path(const RobotAssembly& a) {
  const VecX u0 = a.model().default_input_values();
  const VecX far = (VecX(3) << 0.198629, 0.366977, 0.499006).finished();
  return {u0, u0 + 0.25 * (far - u0)};
}

// planar_pinned from its default lengths a quarter of the way towards (0.198629, 0.366977, 0.499006) m, an
// input of the random FK sweep (docs/benchmarks.md, "Random FK sweeps") on which FK failed: the stable
// branch ends at a fold at 0.21471 of the line (0.85884 of this path), the branch beyond it does not
// come back within the snap's steps; Newton from the fold state pushed along its mode so that the
// platform moves by 0.01 and 0.03 of the length scale returns to the singular fold state, from 0.1 it
// lands on another equilibrium, as stable as the ending branch (none unstable), the one the damped
// motion of the platform reaches too (planar_pinned_damped_motion_past_the_fold below), and the path
// goes on from there. Checked without the code that found it: the residual
// recomputed, Newton from a perturbed landing state back to it (an isolated, regular equilibrium, not
// the fold), and the verdict. The discrete energy model does not cover this robot (pinned rod ends).
BOOST_AUTO_TEST_CASE(planar_pinned_snap_past_a_fold) {
  const auto a = shipped("planar_pinned");
  const std::vector<VecX> path = planar_pinned_quarter_path(*a);
  PathThroughFoldsOptions o;
  o.at_fold = FoldPolicy::Snap;
  o.count_unstable_modes = false;  // as FK's last strategy: counted at the folds and the landings only
  o.keep_trace = true;
  KinematicsOptions k;
  k.stability_verdict = true;
  const PathThroughFoldsResult r = solve_path_through_folds(a, k, path, o);
  BOOST_TEST_MESSAGE(r.summary());
  for (const PathEvent& e : r.events) BOOST_TEST_MESSAGE(e.description);
  BOOST_TEST_REQUIRE(r.points[1].summary.converged(), r.points[1].summary.message);
  BOOST_TEST_REQUIRE(r.events.size() >= 2u);
  const PathEvent& fold = r.events[0];
  const PathEvent& snap = r.events[1];
  BOOST_TEST(to_string(fold.kind) == std::string("fold"));
  // Where the continuation along the whole line located it (0.214710, printed to 6 digits: 2.3e-6
  // relative), the fold being the same point of the same curve.
  BOOST_TEST(fold.path_parameter == 0.214710 / 0.25, tt::tolerance(1e-5));
  BOOST_TEST(fold.unstable_modes_before == 0);
  BOOST_TEST(to_string(snap.kind) == std::string("snap"));
  BOOST_TEST(snap.unstable_modes_after == 0);  // as stable as the ending branch
  // Another equilibrium than the fold state: the snap's own threshold is 1e-4 of the length scale.
  BOOST_TEST(snap.jump_position > 1e-4 * a->length_scale());

  const TracePoint* landed = landing_of(*a, r, snap);
  BOOST_TEST_REQUIRE(landed != nullptr);
  check_stable_isolated_landing(*a, landed->state, k.tolerance);
  // The path's end, reached from the landing: a converged FK result with its verdict.
  BOOST_TEST((r.points[1].stability_verdict.verdict != StabilityVerdict::NotChecked));
}

// The damped motion (pseudo_transient_snap.hpp) on its own, at planar_pinned's fold of the case above:
// from the last continuation point before the fold, at the fold's inputs, the platform moved by 1 mm
// along x, it lands on the equilibrium the snap above lands on (1.2 mm from the fold state), stable and
// isolated (checked as above).
BOOST_AUTO_TEST_CASE(planar_pinned_damped_motion_past_the_fold) {
  const auto a = shipped("planar_pinned");
  const std::vector<VecX> path = planar_pinned_quarter_path(*a);
  PathThroughFoldsOptions o;
  o.at_fold = FoldPolicy::Stop;
  o.count_unstable_modes = false;
  o.keep_trace = true;
  const PathThroughFoldsResult stop = solve_path_through_folds(a, KinematicsOptions{}, path, o);
  BOOST_TEST_REQUIRE(stop.events.size() == 1u);
  BOOST_TEST_REQUIRE(!stop.trace.empty());
  VecX x = stop.trace.back().state;
  a->set_inputs(x, stop.events[0].inputs);
  x[a->problem().variable(a->platform_variable(0)).offset] += 1e-3;
  const double tolerance = KinematicsOptions{}.tolerance;
  const kinematics::PseudoTransientResult damped = kinematics::pseudo_transient_equilibrium(*a, x, tolerance);
  BOOST_TEST_MESSAGE("damped motion: " << damped.steps << " pseudo-time steps, "
                                       << damped.jacobian_evaluations << " Jacobians " << damped.stopped);
  BOOST_TEST_REQUIRE(damped.converged, damped.stopped);
  check_stable_isolated_landing(*a, damped.x, tolerance);
  o.at_fold = FoldPolicy::Snap;
  const PathThroughFoldsResult snap = solve_path_through_folds(a, KinematicsOptions{}, path, o);
  BOOST_TEST_REQUIRE(snap.events.size() >= 2u);
  // The snap's landing is at the fold's inputs + 1e-12 of the path: the same equilibrium to ~1e-12 m.
  BOOST_TEST((platform_position(*a, damped.x) - snap.events[1].platforms_after[0].position).norm() < 1e-9);
}

// six_rus from 0.6 to 0.7 of the line from its default crank angles to (0.245646, 0.846723, 0.685542,
// 1.39959, 0.190363, 0.798329) rad, a cold input of the random FK sweep on which FK failed: the stable
// branch ends at a fold at 0.683826 of the line; the branch beyond runs back past the default angles,
// Newton from the pushed fold states returns to the fold state, and the damped platforms alone stall
// (a soft mode of the rods, universal and spherical ends). The second pass of the damped motion, with
// the diagonal shift on the rods' unknowns, lands on an equilibrium with 0 unstable modes. Checked as
// the planar_pinned landing: residual, Newton from a perturbed landing back to it, verdict. Not in CI
// (about 4 s in Release, most of it the stalled first pass, and this executable runs in the sanitizer
// pass too): test_paths_through_folds --run_test=six_rus_snap_by_damped_motion_with_shift
BOOST_AUTO_TEST_CASE(six_rus_snap_by_damped_motion_with_shift, *boost::unit_test::disabled()) {
  const auto a = shipped("six_rus");
  const VecX u0 = a->model().default_input_values();
  VecX far(6);
  far << 0.245646, 0.846723, 0.685542, 1.39959, 0.190363, 0.798329;
  const std::vector<VecX> path = {u0 + 0.6 * (far - u0), u0 + 0.7 * (far - u0)};
  PathThroughFoldsOptions o;
  o.at_fold = FoldPolicy::Snap;
  o.count_unstable_modes = false;
  o.keep_trace = true;
  const KinematicsOptions k;
  const PathThroughFoldsResult r = solve_path_through_folds(a, k, path, o);
  BOOST_TEST_MESSAGE(r.summary());
  for (const PathEvent& e : r.events) BOOST_TEST_MESSAGE(e.description);
  BOOST_TEST_REQUIRE(r.points[1].summary.converged(), r.points[1].summary.message);
  BOOST_TEST_REQUIRE(r.events.size() >= 2u);
  BOOST_TEST(to_string(r.events[0].kind) == std::string("fold"));
  BOOST_TEST(r.events[0].unstable_modes_before == 0);
  // The fold of the whole line at 0.683826 (printed to 6 digits) is at (0.683826 - 0.6) / 0.1 of this
  // segment: 0.83826 +- 5e-6.
  BOOST_TEST(r.events[0].path_parameter == 0.83826, tt::tolerance(1e-4));
  const PathEvent& snap = r.events[1];
  BOOST_TEST(to_string(snap.kind) == std::string("snap"));
  BOOST_TEST(snap.unstable_modes_after == 0);
  BOOST_TEST(snap.jump_position > 1e-4 * a->length_scale());
  const TracePoint* landed = nullptr;
  for (const TracePoint& t : r.trace)
    if ((platform_position(*a, t.state) - snap.platforms_after[0].position).norm() < 1e-12) landed = &t;
  BOOST_TEST_REQUIRE(landed != nullptr);
  check_stable_isolated_landing(*a, landed->state, k.tolerance);
}

namespace {

/// The path from `from` to `to` of the line from the model's default inputs to `far` (fractions of it),
/// solved as FK's last strategy does: snapping at folds, unstable modes counted at folds and landings.
PathThroughFoldsResult along_the_line_to(const std::shared_ptr<const RobotAssembly>& a, const VecX& far,
                                         double from, double to) {
  const VecX u0 = a->model().default_input_values();
  PathThroughFoldsOptions o;
  o.at_fold = FoldPolicy::Snap;
  o.count_unstable_modes = false;
  o.keep_trace = true;
  const PathThroughFoldsResult r =
      solve_path_through_folds(a, KinematicsOptions{}, {u0 + from * (far - u0), u0 + to * (far - u0)}, o);
  BOOST_TEST_MESSAGE(r.summary());
  for (const PathEvent& e : r.events) BOOST_TEST_MESSAGE(e.description);
  return r;
}

}  // namespace

// universal_passive (rods on passive Hooke joints: nearly rigid struts) from 0.4 to 0.5 of the line from
// its default lengths to an input of the random FK sweep on which FK failed (seed 21, 9th input): the
// stable branch ends at a fold at 0.4443 of the line. Newton from the fold state pushed along the fold
// mode by a few times the continuation's step (the weights W of a whole segment) diverged from every
// start, and the damped motion failed its first pseudo-time step; pushed so that the platform moves by
// 1 % of the length scale, Newton lands. Checked as the landings above: residual, Newton from a
// perturbed landing back to it, verdict.
BOOST_AUTO_TEST_CASE(universal_passive_snap_from_a_platform_sized_push) {
  const auto a = shipped("universal_passive");
  VecX far(6);
  far << 0.3248211729848447, 0.20431961805632998, 0.24222357053189286, 0.30691038906065715,
      0.25680586820139717, 0.28960848738742356;
  const PathThroughFoldsResult r = along_the_line_to(a, far, 0.4, 0.5);
  BOOST_TEST_REQUIRE(r.points[1].summary.converged(), r.points[1].summary.message);
  BOOST_TEST_REQUIRE(r.events.size() == 2u);
  BOOST_TEST(to_string(r.events[0].kind) == std::string("fold"));
  BOOST_TEST(r.events[0].unstable_modes_before == 0);
  const PathEvent& snap = r.events[1];
  BOOST_TEST(to_string(snap.kind) == std::string("snap"));
  BOOST_TEST(snap.unstable_modes_after == 0);
  BOOST_TEST(snap.jump_position > 1e-4 * a->length_scale());
  const TracePoint* landed = landing_of(*a, r, snap);
  BOOST_TEST_REQUIRE(landed != nullptr);
  check_stable_isolated_landing(*a, landed->state, KinematicsOptions{}.tolerance);
}

// universal_pair from 0.6 to 0.8 of the line to an input of the random FK sweep on which FK failed (seed
// 20, 4th input): a fold at 0.6147 of the line, a snap, and on the branch it lands on the state moves
// about 500 times faster per input than at the segment's start (the tangent's lambda part 1.9e-3 with
// the start's weights W): steps of the largest arclength advanced the inputs by 5e-4 of the line each,
// and the 400 steps ran out at 0.825 of the line. With W rebalanced at the landing (equal parts in x and
// lambda, arclength_corrector.hpp) the path's end is reached within the default budget. Checked: the
// end's residual recomputed, and Newton at the end's inputs from the end state with the platform moved
// by 1 mm back to it (an isolated equilibrium).
BOOST_AUTO_TEST_CASE(universal_pair_steps_after_a_snap_in_the_landing_metric) {
  const auto a = shipped("universal_pair");
  VecX far(6);
  far << 0.27117865769795202, 0.24080768933943961, 0.24025980748204603, 0.34806715841229696,
      0.33945743324799765, 0.22773841433851447;
  const PathThroughFoldsResult r = along_the_line_to(a, far, 0.6, 0.8);
  BOOST_TEST_REQUIRE(r.points[1].summary.converged(), r.points[1].summary.message);
  BOOST_TEST(r.steps < PathThroughFoldsOptions{}.max_steps);
  BOOST_TEST_REQUIRE(r.events.size() >= 2u);
  BOOST_TEST(to_string(r.events[1].kind) == std::string("snap"));
  const VecX& end = r.trace.back().state;
  const Problem& problem = a->problem();
  const double tolerance = KinematicsOptions{}.tolerance;
  VecX c;
  problem.evaluate_residuals(end, c);
  BOOST_TEST((c - problem.row_lower()).cwiseAbs().maxCoeff() <= tolerance);
  VecX x = end;
  x.segment<3>(problem.variable(a->platform_variable(0)).offset) += Vec3(1e-3, 0.0, 0.0);
  NewtonOptions no;
  no.tolerance = tolerance;
  BOOST_TEST_REQUIRE(NewtonSolver(problem, no).solve(x).converged());
  BOOST_TEST((platform_position(*a, x) - platform_position(*a, end)).norm() < 1e-9);
}

// planar_post (the middle rod in frictionless contact with a post) from 0.1 to 0.15 of the line to an
// input of the random FK sweep on which FK failed (seed 13, 63rd input). At 0.12636 of the line a contact
// switches at a collocation midpoint: a corner of the curve, where the arclength corrector failed at
// every step length down to 1e-8 (the predictor's error falling like the step, not its square). The
// continuation steps past it by the FK Newton solver at fixed inputs (fold_continuation.cpp). Checked
// against the natural-parameter continuation without the arclength code: FK warm-started along the same
// line in 50 steps (NewtonSolver at each), which must reach the same equilibrium.
BOOST_AUTO_TEST_CASE(planar_post_corner_of_a_contact_switch) {
  const auto a = shipped("planar_post");
  const VecX far = (VecX(3) << 0.15238462256805244, 0.22775208522350027, 0.21788750850995625).finished();
  const PathThroughFoldsResult r = along_the_line_to(a, far, 0.1, 0.15);
  BOOST_TEST_REQUIRE(r.points[1].summary.converged(), r.points[1].summary.message);
  BOOST_TEST(r.events.empty());  // no fold, no snap: the branch goes on past the corner

  const VecX u0 = a->model().default_input_values();
  ForwardKinematics fk(a, KinematicsOptions{});
  RobotSolution s;
  for (int k = 0; k <= 50; ++k) {
    s = fk.solve(u0 + (0.1 + 0.05 * k / 50.0) * (far - u0));
    BOOST_TEST_REQUIRE(s.summary.converged(), s.summary.message);
  }
  // Both to the solver tolerance 1e-10 on residuals scaled by the length scale (~0.3 m) and the rods'
  // stiffness: the platforms agree to ~1e-10 m; 1e-8 m leaves room for the conditioning.
  BOOST_TEST((s.platforms[0].position - r.points[1].platforms[0].position).norm() < 1e-8);
}
