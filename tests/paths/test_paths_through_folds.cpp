// Paths through folds (path_through_folds.hpp): FK along input paths by pseudo-arclength continuation.
// Each event is checked against a method that does not use the continuation: Euler's loads for the
// bifurcations of a fed column, the discrete energy model (tests/stability/robot_discrete.hpp: its
// Hessian's number of negative eigenvalues at its own relaxed equilibrium) for the unstable-mode counts,
// and displacement control (IK on a platform coordinate, the input free) for the fold: the fold is the
// largest input along the branch parametrised by the platform coordinate.
#define BOOST_TEST_MODULE paths_through_folds
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include "kinematics/arclength_corrector.hpp"
#include "paths/path_fixtures.hpp"
#include "pcr/robots/branch_check.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/path_through_folds.hpp"
#include "pcr/robots/robot_stability.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "stability/robot_discrete.hpp"

using namespace pcr;
using test::landing_of;
using test::platform_position;
using test::shipped;
namespace tt = boost::test_tools;

namespace {

// Segments per rod of the discrete model (test_robot_verdict: critical loads within about 0.1 % at 16);
// it is compared only at states far from critical.
constexpr int kDiscreteSegments = 16;

// The fed column of test_robot_verdict: a steel rod, section 2 mm x 1 mm, clamped upright in the base and
// fed through it (input: its length), its upper end clamped to a massless platform under a dead load of
// 1 N down. Clamped-free Euler column (Timoshenko & Gere, Theory of Elastic Stability, 1961, §2.1): the
// straight column has its first unstable mode from L_cr = (pi / 2) sqrt(E I_min / F) (weak plane), its
// second from 2 L_cr (strong plane, I_max = 4 I_min).
constexpr double kE = 200e9, kWidth = 2e-3, kHeight = 1e-3, kLoad = 1.0;  // Pa, m, m, N
const double kEulerLength = M_PI / 2 * std::sqrt(kE * kWidth * std::pow(kHeight, 3) / 12 / kLoad);

std::shared_ptr<const RobotAssembly> fed_column() {
  const std::string xml = R"(<robot name="fed_column">
  <link name="base"/>
  <link name="platform"/>
  <joint name="platform_pose" type="floating">
    <parent link="base"/>
    <child link="platform"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/>
  </joint>
  <pcr_load link="platform" xyz="0 0 0" force="0 0 -1" torque="0 0 0"/>
  <pcr_rod name="column">
    <start link="base" xyz="0 0 0" rpy="0 0 0" coupling="clamped"/>
    <end link="platform" xyz="0 0 0" rpy="0 0 0" coupling="clamped"/>
    <material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>
    <section type="rectangle" width="0.002" height="0.001"/>
    <length value="0.1" actuated="true" lower="0.05" upper="1.0"/>
  </pcr_rod>
</robot>)";
  return std::make_shared<const RobotAssembly>(
      std::make_shared<const RobotModel>(parse_robot_model(xml, "fed_column")));
}

std::vector<VecX> line_path(std::initializer_list<double> lengths) {
  std::vector<VecX> out;
  for (double l : lengths) out.push_back(VecX::Constant(1, l));
  return out;
}

}  // namespace

// The straight fed column: no fold (the load factor grows monotonically along the straight branch), two
// bifurcations where the count of unstable modes steps 0 -> 1 -> 2, at the Euler lengths. The shift of
// the critical lengths by the axial and shear strains is of order F / (E A) and F / (G A), about 1e-5
// relative; the collocation's error on them is far below (test_stability_verdict).
BOOST_AUTO_TEST_CASE(fed_column_bifurcations_at_the_euler_lengths) {
  const PathThroughFoldsResult r =
      solve_path_through_folds(fed_column(), KinematicsOptions{},
                               line_path({0.5 * kEulerLength, 1.5 * kEulerLength, 2.5 * kEulerLength}));
  BOOST_TEST_MESSAGE(r.summary());
  for (const PathEvent& e : r.events) BOOST_TEST_MESSAGE(e.description);
  BOOST_TEST_REQUIRE(r.points.size() == 3u);
  for (const RobotSolution& p : r.points) BOOST_TEST(p.summary.converged(), p.summary.message);
  BOOST_TEST_REQUIRE(r.events.size() == 2u);
  const double expected_length[] = {kEulerLength, 2 * kEulerLength};
  for (int k = 0; k < 2; ++k) {
    const PathEvent& e = r.events[k];
    BOOST_TEST(to_string(e.kind) == std::string("bifurcation"));
    BOOST_TEST(e.unstable_modes_before == k);
    BOOST_TEST(e.unstable_modes_after == k + 1);
    BOOST_TEST(std::abs(e.inputs[0] / expected_length[k] - 1.0) < 1e-4, "at " << e.inputs[0] / kEulerLength);
  }
  // The path stays on the straight branch (no imperfection): the platform above the base.
  for (const RobotSolution& p : r.points) BOOST_TEST(p.platforms[0].position.head<2>().norm() < 1e-9);
}

namespace {

/// The fold by an independent method: bisection in lambda along the segment u_a -> u_b on whether plain
/// Newton on the FK system (NewtonSolver, no continuation), started from the last state found on the
/// branch, converges to an equilibrium near it (platform within `near` of the last one). x_lo: an
/// equilibrium on the branch at lambda_lo; hi: a lambda past the fold. Returns the bracket's lower end.
double fold_by_newton_bisection(const RobotAssembly& a, VecX x_lo, const VecX& u_a, const VecX& u_b,
                                double lo, double hi, double near, double tolerance) {
  NewtonOptions o;
  o.tolerance = 1e-10;
  NewtonSolver newton(a.problem(), o);
  while (hi - lo > tolerance) {
    const double mid = 0.5 * (lo + hi);
    VecX x = x_lo;
    a.set_inputs(x, u_a + mid * (u_b - u_a));
    const SolveSummary s = newton.solve(x, 40);
    if (s.converged() && (platform_position(a, x) - platform_position(a, x_lo)).norm() < near) {
      lo = mid;
      x_lo = x;
    } else {
      hi = mid;
    }
  }
  return lo;
}

}  // namespace

namespace {

/// The last trace point before the first fold (tau > 0, path parameter below it) and the first one on the
/// branch beyond it at least `away` (in path parameter) from the fold.
struct AroundFold {
  const TracePoint* before = nullptr;
  const TracePoint* beyond = nullptr;
};
AroundFold around_fold(const PathThroughFoldsResult& r, double fold, double away) {
  AroundFold out;
  bool passed = false;
  for (const TracePoint& t : r.trace) {
    if (!passed && t.tau > 0.0 && t.path_parameter < fold) out.before = &t;
    if (t.tau <= 0.0) passed = true;
    if (passed && !out.beyond && t.tau < 0.0 && t.path_parameter < fold - away) out.beyond = &t;
  }
  return out;
}

/// The fold of r's first fold event against Newton bisection (fold_by_newton_bisection) from the last trace
/// point before it, on segment 0 of `path`; returns |difference| in the inputs (max-abs).
double fold_error(const RobotAssembly& a, const PathThroughFoldsResult& r, const std::vector<VecX>& path) {
  const PathEvent& fold = r.events.front();
  const AroundFold around = around_fold(r, fold.path_parameter, 0.0);
  BOOST_TEST_REQUIRE(around.before != nullptr);
  const Vec3 p_fold = fold.platforms[0].position;
  const double near = 2.0 * (platform_position(a, around.before->state) - p_fold).norm() + 1e-6;
  const double lambda =
      fold_by_newton_bisection(a, around.before->state, path[0], path[1], around.before->path_parameter,
                               fold.path_parameter + 0.05, near, 1e-10);
  const VecX u = path[0] + lambda * (path[1] - path[0]);
  BOOST_TEST_MESSAGE("fold at inputs " << fold.inputs.transpose() << ", Newton bisection " << u.transpose());
  return (u - fold.inputs).cwiseAbs().maxCoeff();
}

/// The state on the branch beyond a fold of segment 0 of `path` where its path parameter has come back to
/// `lambda_end`: the arclength corrector (kinematics/arclength_corrector.hpp, the path's own) on the line
/// from the trace point `before` (on the branch before the fold: the corrector's start sets its metric
/// there) to path[1], stepped on from the trace point `beyond` (the first past the fold) with its tangent
/// towards decreasing lambda; the step halved where the corrector fails or the tangent turns forward (a
/// second fold: not expected on the arch), grown by 1.5 up to 0.02 where it converges.
VecX along_branch_beyond(const RobotAssembly& a, const std::vector<VecX>& path, const TracePoint& before,
                         const TracePoint& beyond, double lambda_end) {
  const double l0 = before.path_parameter;  // the line's parameter s = (lambda - l0) / (1 - l0)
  const auto s_of = [l0](double lambda) { return (lambda - l0) / (1.0 - l0); };
  kinematics::ArcCorrector arc(a, path[0] + l0 * (path[1] - path[0]), path[1], 1e-10);
  kinematics::ArcPoint p, q;
  BOOST_TEST_REQUIRE(arc.start(before.state, p));
  kinematics::ArcPoint guess = p;
  guess.x = beyond.state;
  guess.lambda = s_of(beyond.path_parameter);
  VecX back = VecX::Zero(p.tangent.size());
  back[back.size() - 1] = -1.0;
  BOOST_TEST_REQUIRE(arc.at_lambda(guess, back, guess.lambda, p));
  double ds = 0.02;
  for (int k = 0; k < 400 && p.lambda > s_of(lambda_end) && ds > 1e-8; ++k) {
    if (arc.arclength_step(p, ds, q) && q.tau() < 0.0) {
      p = q;
      ds = std::min(0.02, 1.5 * ds);
    } else {
      ds *= 0.5;
    }
  }
  BOOST_TEST_REQUIRE(p.lambda <= s_of(lambda_end));
  return p.x;
}

// An arch: a steel strip (0.5 mm in the plane of the arch, 4 mm across it, so that it stays planar) of
// 0.22 m between two clamps 0.2 m apart, joined at its middle by a massless link (the platform, to read the
// arch's middle). The left clamp turns about y (input, rad; positive tilts its tangent down). From -0.2
// (the arch bulging up, its natural shape) turning the clamp down ends the bulged-up branch at a fold
// (the snap-through of a buckled beam with one end rotated, e.g. Pandey et al., "Dynamics of snapping
// beams and jumping poppers", EPL 105, 24001, 2014).
std::shared_ptr<const RobotAssembly> arch() {
  const char* strip = R"(<material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>
    <section type="rectangle" width="0.0005" height="0.004"/>
    <length value="0.11"/>)";
  const std::string xml = std::string(R"(<robot name="arch">
  <link name="base"/>
  <link name="left_clamp"/>
  <link name="middle"/>
  <joint name="left_angle" type="revolute">
    <parent link="base"/>
    <child link="left_clamp"/>
    <origin xyz="0 0 0" rpy="0 0 0"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <pcr_joint name="left_angle" default="-0.2"/>
  <joint name="middle_pose" type="floating">
    <parent link="base"/>
    <child link="middle"/>
    <origin xyz="0.1 0 0.03" rpy="0 0 0"/>
  </joint>
  <pcr_rod name="left">
    <start link="left_clamp" xyz="0 0 0" rpy="0 1.5707963267948966 0" coupling="clamped"/>
    <end link="middle" xyz="0 0 0" rpy="0 1.5707963267948966 0" coupling="clamped"/>
    )") + strip + R"(
  </pcr_rod>
  <pcr_rod name="right">
    <start link="base" xyz="0.2 0 0" rpy="0 -1.5707963267948966 0" coupling="clamped"/>
    <end link="middle" xyz="0 0 0" rpy="0 -1.5707963267948966 0" coupling="clamped"/>
    )" + strip + R"(
  </pcr_rod>
</robot>)";
  return std::make_shared<const RobotAssembly>(
      std::make_shared<const RobotModel>(parse_robot_model(xml, "arch")));
}

}  // namespace

// The arch along its clamp angle: the bulged-up branch is stable (0 unstable modes) up to a fold, where
// it ends; beyond the fold the branch has 1 unstable mode. The fold's input agrees with Newton bisection
// (plain Newton from the branch, no continuation) to 1e-6 rad; the counts on both sides agree with the
// discrete energy model away from the fold. With FoldPolicy::Stop the point past the fold fails and says why.
BOOST_AUTO_TEST_CASE(arch_fold_located_and_counted) {
  const auto a = arch();
  const std::vector<VecX> path = {VecX::Constant(1, -0.2), VecX::Constant(1, 0.8)};
  PathThroughFoldsOptions o;
  o.keep_trace = true;
  const PathThroughFoldsResult r = solve_path_through_folds(a, KinematicsOptions{}, path, o);
  BOOST_TEST_MESSAGE(r.summary());
  BOOST_TEST_REQUIRE(r.events.size() == 1u);
  const PathEvent& fold = r.events[0];
  BOOST_TEST(to_string(fold.kind) == std::string("fold"));
  BOOST_TEST(fold.unstable_modes_before == 0);
  BOOST_TEST(fold.unstable_modes_after == 1);
  // "Located to 1e-6 in the input": the bisection is converged to 1e-10 of the segment (1 rad).
  const double error = fold_error(*a, r, path);
  BOOST_TEST_MESSAGE("arch fold: continuation vs Newton bisection " << error << " rad");
  BOOST_TEST(error < 1e-6);
  BOOST_TEST(r.points[0].summary.converged());
  BOOST_TEST(!r.points[1].summary.converged());
  BOOST_TEST(r.points[1].summary.message.find("fold at path parameter") != std::string::npos);
  // Counts along the branch: stable before the fold, 1 unstable mode on the branch beyond it (the trace
  // point a little past the fold), as the discrete model says.
  const AroundFold around = around_fold(r, fold.path_parameter, 0.0);
  BOOST_TEST_REQUIRE((around.before && around.beyond));
  BOOST_TEST(around.before->unstable_modes == 0);
  BOOST_TEST(around.beyond->unstable_modes == 1);
  BOOST_TEST(test::discrete_robot_inertia(*a, around.before->state, kDiscreteSegments).negative == 0);
  // Farther along the branch beyond the fold, the clamp turned 0.15 rad back from the fold's 0.538 rad:
  // 1 unstable mode both ways. The discrete model (16 segments) has its own fold nearer: on this branch its
  // smallest Jacobi-scaled eigenvalue is +7e-8 at 0.522 rad, -1.4e-7 to -1.6e-7 from 0.415 to 0.357 rad
  // (clear of its zero tolerance, 1e-9); below 0.35 rad its Newton relaxation stops converging.
  const VecX far = along_branch_beyond(*a, path, *around.before, *around.beyond, fold.path_parameter - 0.15);
  const Stability far_verdict = robot_stability(*a, far);
  BOOST_TEST((far_verdict.verdict == StabilityVerdict::Unstable && far_verdict.unstable_modes == 1));
  BOOST_TEST(test::discrete_robot_inertia(*a, far, kDiscreteSegments).negative == 1);
}

// planar_three_rod, its middle rod fed from its default length (0.2912 m) to 0.34 m: the branch (1
// unstable mode: out of the plane, test_stability_verdict) ends at a fold where an in-plane mode turns
// unstable (2 beyond it), located to 1e-6 m against Newton bisection. The robot snaps to an equilibrium
// at the fold's inputs with 1 unstable mode (the out-of-plane one), its platform centimetres away; the
// discrete energy model gives the same counts before the fold, on the branch beyond it and at the landing.
// Fed back to the default length, the robot stays on the snapped branch (hysteresis).
BOOST_AUTO_TEST_CASE(planar_robot_fold_and_snap) {
  const auto a = shipped("planar_three_rod");
  VecX u0 = a->model().default_input_values(), u1 = u0;
  u1[1] = 0.34;                                 // middle
  const std::vector<VecX> path = {u0, u1, u0};  // and back
  PathThroughFoldsOptions o;
  o.at_fold = FoldPolicy::Snap;
  o.keep_trace = true;
  const PathThroughFoldsResult r = solve_path_through_folds(a, KinematicsOptions{}, path, o);
  BOOST_TEST_MESSAGE(r.summary());
  for (const PathEvent& e : r.events) BOOST_TEST_MESSAGE(e.description);
  BOOST_TEST_REQUIRE(r.events.size() >= 2u);
  const PathEvent& fold = r.events[0];
  const PathEvent& snap = r.events[1];
  BOOST_TEST(to_string(fold.kind) == std::string("fold"));
  BOOST_TEST(fold.unstable_modes_before == 1);
  BOOST_TEST(fold.unstable_modes_after == 2);
  const double error = fold_error(*a, r, path);
  BOOST_TEST_MESSAGE("planar fold: continuation vs Newton bisection " << error << " m");
  BOOST_TEST(error < 1e-6);
  BOOST_TEST(to_string(snap.kind) == std::string("snap"));
  BOOST_TEST(snap.path_parameter == fold.path_parameter, tt::tolerance(1e-11));
  BOOST_TEST(snap.unstable_modes_after == 1);
  // The platform jumps: more than the steps of the continuation near the fold would move it (mm).
  BOOST_TEST(snap.jump_position > 5e-3);
  BOOST_TEST(r.points[1].summary.converged(), r.points[1].summary.message);

  const AroundFold around = around_fold(r, fold.path_parameter, 0.0);
  BOOST_TEST_REQUIRE((around.before && around.beyond));
  BOOST_TEST(test::discrete_robot_inertia(*a, r.trace.front().state, kDiscreteSegments).negative == 1);
  // On the branch beyond the fold, 0.02 of the segment (0.97 mm of the middle rod) back from it.
  const VecX beyond =
      along_branch_beyond(*a, path, *around.before, *around.beyond, fold.path_parameter - 0.02);
  const Stability beyond_verdict = robot_stability(*a, beyond);
  BOOST_TEST((beyond_verdict.verdict == StabilityVerdict::Unstable && beyond_verdict.unstable_modes == 2));
  BOOST_TEST(test::discrete_robot_inertia(*a, beyond, kDiscreteSegments).negative == 2);
  // The landing point (in the trace as the point the path goes on from).
  const TracePoint* landed = landing_of(*a, r, snap);
  BOOST_TEST_REQUIRE(landed != nullptr);
  BOOST_TEST(test::discrete_robot_inertia(*a, landed->state, kDiscreteSegments).negative ==
             landed->unstable_modes);

  // Back at the default lengths the robot stays on the branch it snapped to (hysteresis): centimetres
  // from the default pose that a cold solve reaches, and stable (the out-of-plane mode too), as the
  // discrete model says.
  BOOST_TEST_REQUIRE(r.points[2].summary.converged(), r.points[2].summary.message);
  const BranchComparison c = compare_with_cold_solve(ForwardKinematics(a), r.points[2]);
  BOOST_TEST_MESSAGE(c.description);
  BOOST_TEST(c.cold_converged);
  BOOST_TEST(c.different_branch);
  BOOST_TEST(c.platform_distance > 1e-2);
  BOOST_TEST((c.cold.platforms[0].position - r.points[0].platforms[0].position).norm() < 1e-9);
  BOOST_TEST(r.trace.back().path_parameter == 2.0);
  BOOST_TEST(r.trace.back().unstable_modes == 0);
  BOOST_TEST(test::discrete_robot_inertia(*a, r.trace.back().state, kDiscreteSegments).negative == 0);
}

// stewart_gough, legs 0, 2 and 4 fed from 0.45 m to 0.49 m (the other three held): the platform tilts until
// the three short legs, compressed, buckle: no fold, the count of unstable modes steps from 0 to 2 at once
// (round legs: both bending planes together, a double bifurcation) and then to 3. The counts at the path
// points agree with the discrete energy model.
BOOST_AUTO_TEST_CASE(stewart_gough_legs_buckle_without_a_fold) {
  const auto a = shipped("stewart_gough");
  VecX u0 = a->model().default_input_values(), u1 = u0, u_mid = u0;
  for (int leg : {0, 2, 4}) {
    u1[leg] = 0.49;
    u_mid[leg] = 0.47;
  }
  KinematicsOptions ko;
  ko.stability_verdict = true;
  PathThroughFoldsOptions o;
  o.keep_trace = true;
  o.event_tolerance = 1e-6;  // of the segment (0.02 m): where the counts change is not asserted here
  const PathThroughFoldsResult r = solve_path_through_folds(a, ko, {u0, u_mid, u1}, o);
  BOOST_TEST_MESSAGE(r.summary());
  for (const PathEvent& e : r.events) BOOST_TEST_MESSAGE(e.description);
  for (const RobotSolution& p : r.points) BOOST_TEST_REQUIRE(p.summary.converged(), p.summary.message);
  BOOST_TEST_REQUIRE(r.events.size() == 2u);
  BOOST_TEST(to_string(r.events[0].kind) == std::string("bifurcation"));
  BOOST_TEST(r.events[0].unstable_modes_before == 0);
  BOOST_TEST(r.events[0].unstable_modes_after == 2);
  BOOST_TEST(to_string(r.events[1].kind) == std::string("bifurcation"));
  BOOST_TEST(r.events[1].unstable_modes_after == 3);
  const int expected[] = {0, 0, 3};
  for (int k = 0; k < 3; ++k)
    BOOST_TEST(r.points[k].stability_verdict.unstable_modes == expected[k], "point " << k);
  // The last path point is the last trace point.
  BOOST_TEST_REQUIRE(r.trace.back().path_parameter == 2.0);
  BOOST_TEST(test::discrete_robot_inertia(*a, r.trace.back().state, kDiscreteSegments).negative == 3);
}
