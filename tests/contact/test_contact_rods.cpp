// Obstacles and frictionless contact of collocation rods (rod_contact.hpp): gap functions, the
// complementarity function, Jacobians of the new residual blocks against finite differences, inactive
// contact, and rejected input.
#define BOOST_TEST_MODULE contact
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

#include "contact/edge_contact.hpp"
#include "contact_fixtures.hpp"
#include "pcr/core/error.hpp"
#include "pcr/solve/jacobian_check.hpp"

using namespace pcr;

namespace {

Obstacle make_obstacle(const std::string& name, ObstacleShape shape, const Vec3& position,
                       const Vec3& direction, double radius, const Vec3& end = Vec3::Zero()) {
  Obstacle o;
  o.name = name;
  o.shape = shape;
  o.position = position;
  o.direction = direction;
  o.radius = radius;
  o.end = end;
  return o;
}

// One obstacle of each shape near the first 0.3 m of a cantilever along +x.
std::vector<Obstacle> all_shapes() {
  return {make_obstacle("floor", ObstacleShape::HalfSpace, Vec3(0, 0, -0.002), Vec3(0, 0, 1), 0.0),
          make_obstacle("ball", ObstacleShape::Sphere, Vec3(0.1, 0.0, -0.052), Vec3::UnitZ(), 0.05),
          make_obstacle("post", ObstacleShape::Capsule, Vec3(0.2, 0.0, -0.03), Vec3::UnitZ(), 0.02,
                        Vec3(0.2, 0.05, -0.03)),
          make_obstacle("roller", ObstacleShape::Cylinder, Vec3(0.05, 0.0, 0.04), Vec3(0, 1, 0), 0.035)};
}

}  // namespace

BOOST_AUTO_TEST_CASE(gap_functions_match_their_geometry) {
  const double r = 0.001;
  // Values from the geometry (obstacle.hpp's table), exact in double precision up to round-off (1e-15).
  const std::vector<Obstacle> o = all_shapes();
  BOOST_TEST(obstacle_gap(o[0], Vec3(3, 4, 0.01), r).gap == 0.011, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(obstacle_gap(o[1], Vec3(0.1, 0.03, -0.012), r).gap == 0.05 - 0.05 - r + 0.0,
             boost::test_tools::tolerance(1e-14));
  // Capsule: beside the segment (distance 0.01 in x) and beyond its end (distance 0.05 along y).
  BOOST_TEST(obstacle_gap(o[2], Vec3(0.21, 0.02, -0.03), r).gap == 0.01 - 0.02 - r,
             boost::test_tools::tolerance(1e-14));
  BOOST_TEST(obstacle_gap(o[2], Vec3(0.2, 0.1, -0.03), r).gap == 0.05 - 0.02 - r,
             boost::test_tools::tolerance(1e-14));
  // Cylinder: the y coordinate does not count.
  BOOST_TEST(obstacle_gap(o[3], Vec3(0.05, 7.0, 0.0), r).gap == 0.04 - 0.035 - r,
             boost::test_tools::tolerance(1e-14));

  // d g / d p = nu and d nu / d p against central differences (h = 1e-6: truncation O(h^2 / d^2) ~ 1e-9
  // at the distances >= 0.02 m used here, round-off 1e-16 / h = 1e-10).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  const Vec3 points[] = {Vec3(0.0, 0.0, 0.01), Vec3(0.12, 0.01, 0.0), Vec3(0.23, 0.02, -0.005),
                         Vec3(0.2, 0.09, -0.0), Vec3(0.06, 0.3, -0.01)};
  for (const Obstacle& obstacle : o) {
    for (Vec3 p : points) {
      p += Vec3(jitter(rng), jitter(rng), jitter(rng));
      const ObstacleGap g = obstacle_gap(obstacle, p, r);
      const double h = 1e-6;
      for (int c = 0; c < 3; ++c) {
        Vec3 dp = Vec3::Zero();
        dp[c] = h;
        const ObstacleGap gp = obstacle_gap(obstacle, p + dp, r), gm = obstacle_gap(obstacle, p - dp, r);
        BOOST_TEST(std::abs((gp.gap - gm.gap) / (2 * h) - g.normal[c]) < 1e-7,
                   obstacle.name << " d g / d p_" << c);
        const Vec3 dnu = (gp.normal - gm.normal) / (2 * h);
        BOOST_TEST((dnu - g.normal_derivative.col(c)).norm() < 1e-6, obstacle.name << " d nu / d p_" << c);
      }
      BOOST_TEST(std::abs(g.normal.norm() - 1.0) < 1e-14);
    }
  }
}

// Fischer-Burmeister phi(a, b) = a + b - sqrt(a^2 + b^2) to full relative precision where one argument
// dwarfs the other (a touching contact under a large force: a ~ 0, b >> 1), against its series
// a (1 - a / (2 b) + ...) for b >> a > 0 and the closed form at (3, 4) and (-3, 4) (rho = 5); the
// derivatives 1 - a / rho, 1 - b / rho.
BOOST_AUTO_TEST_CASE(fischer_burmeister_without_cancellation) {
  const auto fb = ComplementarityFunction::FischerBurmeister;
  double phi, phi_a, phi_b;
  for (const double b : {1e3, 1e6, 1e9}) {
    const double a = 1e-12;
    contact::complementarity(fb, a, b, phi, phi_a, phi_b);
    BOOST_TEST(phi == a * (1.0 - a / (2.0 * b)), boost::test_tools::tolerance(1e-15));
    contact::complementarity(fb, b, a, phi, phi_a, phi_b);  // symmetric
    BOOST_TEST(phi == a * (1.0 - a / (2.0 * b)), boost::test_tools::tolerance(1e-15));
  }
  contact::complementarity(fb, 3.0, 4.0, phi, phi_a, phi_b);
  BOOST_TEST(phi == 2.0, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(phi_a == 1.0 - 3.0 / 5.0, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(phi_b == 1.0 - 4.0 / 5.0, boost::test_tools::tolerance(1e-15));
  contact::complementarity(fb, -3.0, 4.0, phi, phi_a, phi_b);
  BOOST_TEST(phi == -4.0, boost::test_tools::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(contact_blocks_jacobian_match_finite_differences) {
  // The contact rows and the mixed force balance with F_j, at a perturbed state whose multipliers are
  // positive (both terms of every row active), with both complementarity functions. Kinks (FB at (0, 0),
  // min at a = b) are more than 1e-3 away in the scaled variables at this state, far beyond the
  // difference step (JacobianCheckOptions default 1e-6).
  const CollocationRod rod(test::steel_cantilever(0.3, Vec3(0, 0, -9.81), Vec3(0, 0, -0.01)),
                           test::contact_discretization(4, 6));
  for (ComplementarityFunction f :
       {ComplementarityFunction::FischerBurmeister, ComplementarityFunction::Min}) {
    RodContactOptions options{all_shapes(), test::kRadius, f};
    Problem problem;
    const RodVariables vars = rod.add_to_problem(problem);
    const RodContactVariables contact = add_rod_contact(problem, rod, vars, options);
    BOOST_TEST(contact.blocks.size() == static_cast<size_t>(rod.num_control_points() - 1));
    VecX x = problem.initial_values();
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int i = 0; i < x.size(); ++i) x[i] += 1e-3 * unit(rng);
    for (int offset : contact.multiplier_offsets)
      for (int k = 0; k < 4; ++k) x[offset + k] = 0.5 + 0.4 * unit(rng);
    const JacobianCheckResult r = check_problem_jacobian(problem, x);
    BOOST_TEST(r.passed, to_string(f) << ": " << r.to_string());
  }
}

BOOST_AUTO_TEST_CASE(inactive_contact_gives_the_free_solution) {
  // A floor 0.2 m below a cantilever that sags 2.5 mm: no contact. The contact rows decouple exactly
  // (phi(a, 0) = 0 with d phi / d lambda = 1 and d phi / d p = 0 for a > 0: lambda and F stay 0 in every
  // Newton step), so the iterates are those of the rod without the floor up to the round-off of the two
  // LU factorisations (1e-15 L per step, bounded by 1e-12 L).
  const RodModel model = test::steel_cantilever(0.3, Vec3(0, 0, -9.81), Vec3(0, 0, -0.01));
  const CollocationRod free_rod(model, RodDiscretization{RodFormulation::Mixed, 4, 12});
  const CollocationRod rod(model, test::contact_discretization(4, 12));
  RodContactOptions options{
      {make_obstacle("floor", ObstacleShape::HalfSpace, Vec3(0, 0, -0.2), Vec3(0, 0, 1), 0.0)},
      test::kRadius};
  const auto without = test::solve_rod(free_rod, nullptr);
  const auto with = test::solve_rod(rod, &options);
  BOOST_TEST_REQUIRE(without->summary.converged());
  BOOST_TEST_REQUIRE(with->summary.converged());
  for (double s : {0.0, 0.1, 0.2, 0.3}) {
    const RodState a = free_rod.state_at(without->x, without->vars, s),
                   b = rod.state_at(with->x, with->vars, s);
    BOOST_TEST((a.position - b.position).norm() < 1e-12 * 0.3, "s = " << s);
    BOOST_TEST((a.force - b.force).norm() < 1e-12 * rod.force_scale(), "s = " << s);
  }
  const std::vector<ObstacleContact> c = read_rod_contact(rod, with->vars, with->contact, with->x);
  BOOST_TEST_REQUIRE(c.size() == 1u);
  BOOST_TEST(c[0].intervals.empty());
  BOOST_TEST(c[0].force.norm() == 0.0);
  BOOST_TEST(c[0].min_gap > 0.19);  // 0.2 m - sag (< 3 mm) - radius
  BOOST_TEST(with->summary.iterations == without->summary.iterations);
}

BOOST_AUTO_TEST_CASE(bad_contact_input_is_rejected) {
  const RodModel model = test::steel_cantilever(0.3, Vec3::Zero(), Vec3(0, 0, -0.01));
  const Obstacle floor =
      make_obstacle("floor", ObstacleShape::HalfSpace, Vec3(0, 0, -0.01), Vec3(0, 0, 1), 0.0);
  auto add = [&](const RodContactOptions& options, RodDiscretization d) {
    const CollocationRod rod(model, d);
    Problem problem;
    const RodVariables vars = rod.add_to_problem(problem);
    add_rod_contact(problem, rod, vars, options);
  };
  const RodDiscretization d = test::contact_discretization(4, 4);
  // Formulations without contact rows.
  for (RodFormulation f : {RodFormulation::Primal, RodFormulation::Condensed}) {
    RodDiscretization bad = d;
    bad.formulation = f;
    BOOST_CHECK_THROW(CollocationRod(model, bad), InputError);
  }
  RodDiscretization greville = d;
  greville.mixed_points = MixedPoints::Greville;
  BOOST_CHECK_THROW(CollocationRod(model, greville), InputError);
  BOOST_CHECK_THROW(add({{floor}, test::kRadius}, RodDiscretization{RodFormulation::Mixed, 4, 4}),
                    InputError);
  // Radius, obstacle geometry.
  BOOST_CHECK_THROW(add({{floor}, 0.0}, d), InputError);
  BOOST_CHECK_THROW(add({{floor}, -1e-3}, d), InputError);
  BOOST_CHECK_THROW(add({{floor}, std::nan("")}, d), InputError);
  BOOST_CHECK_THROW(add({{}, test::kRadius}, d), InputError);
  Obstacle tilted = floor;
  tilted.direction = Vec3(0, 1, 1);
  BOOST_CHECK_THROW(add({{tilted}, test::kRadius}, d), InputError);
  Obstacle ball = make_obstacle("ball", ObstacleShape::Sphere, Vec3(0, 0, -1), Vec3::UnitZ(), -0.1);
  BOOST_CHECK_THROW(add({{ball}, test::kRadius}, d), InputError);
  ball.radius = 0.1;
  ball.position[0] = std::nan("");
  BOOST_CHECK_THROW(add({{ball}, test::kRadius}, d), InputError);
  // The straight initial rod crosses a floor 0.5 mm below its centerline (radius 1 mm): the message names
  // the rod, the obstacle and the gap.
  Obstacle high = floor;
  high.position.z() = -0.0005;
  try {
    add({{high}, test::kRadius}, d);
    BOOST_FAIL("a penetrating initial guess was accepted");
  } catch (const InputError& e) {
    const std::string what = e.what();
    BOOST_TEST(what.find("'beam'") != std::string::npos, what);
    BOOST_TEST(what.find("penetrates obstacle 'floor'") != std::string::npos, what);
    BOOST_TEST(what.find("gap -0.0005") != std::string::npos, what);
  }
}
