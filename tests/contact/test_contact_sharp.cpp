// Sharp obstacles (edges, points): a concentrated contact force at an unknown section (rod_contact.hpp).
// A propped cantilever with an overhang against beam theory, the Jacobians of the new rows against finite
// differences, and bad input in the model format.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <string>

#include "contact_fixtures.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/solve/jacobian_check.hpp"

using namespace pcr;

namespace {

const double kPi = std::acos(-1.0);
const double kArea = kPi * test::kRadius * test::kRadius;
const double kEI = kArea * test::kRadius * test::kRadius / 4.0 * test::kYoungs;  // E pi r^4 / 4
const double kGA = test::kYoungs / (2.0 * (1.0 + test::kPoisson)) * kArea;       // k G A, k = 1

Obstacle sharp(const std::string& name, ObstacleShape shape, const Vec3& point) {
  Obstacle o;
  o.name = name;
  o.shape = shape;
  o.position = point;
  o.direction = Vec3::UnitY();
  return o;
}

}  // namespace

BOOST_AUTO_TEST_CASE(propped_cantilever_with_overhang_on_an_edge) {
  // Clamp at x = 0 (tangent +x), length L, own weight q = rho A g, resting on a sharp edge (a line along y)
  // at x = a < L whose top is at the height of the clamp's lowest fibre (z = -r): the rod's centerline
  // passes through z = 0 there. Timoshenko beam theory (superposition: the prop R cancels the deflection
  // of the cantilever under q at x = a):
  //   w_q(a) = q a^2 (6 L^2 - 4 L a + a^2) / (24 EI) + q (L a - a^2 / 2) / (kGA),
  //   R = w_q(a) / (a^3 / (3 EI) + a / (kGA)),  clamp force q L - R,  clamp moment q L^2 / 2 - R a.
  // Steel r = 1 mm, L = 0.5 m, a = 0.4 m, g = 0.981 m/s^2 (a tenth of gravity): the slope at the prop is
  // theta ~ 3e-4, so the geometric nonlinearity (O(theta^2) ~ 1e-7) and the shift of the contact section
  // by r theta (1e-6 of a) stay below 1e-6 of R.
  const double L = 0.5, a = 0.4, g = 0.981, q = test::kDensity * kArea * g;
  const double wq = q * a * a * (6 * L * L - 4 * L * a + a * a) / (24 * kEI) + q * (L * a - a * a / 2) / kGA;
  const double R = wq / (std::pow(a, 3) / (3 * kEI) + a / kGA);
  for (int elements : {16, 32}) {
    const CollocationRod rod(test::steel_cantilever(L, Vec3(0, 0, -g), Vec3::Zero()),
                             test::contact_discretization(4, elements));
    RodContactOptions options{{sharp("edge", ObstacleShape::Edge, Vec3(a, 0, -test::kRadius))},
                              test::kRadius};
    const auto s = test::solve_rod(rod, &options);
    BOOST_TEST_REQUIRE(s->summary.converged(), s->summary.message);
    const std::vector<ObstacleContact> c = read_rod_contact(rod, s->vars, s->contact, s->x);
    BOOST_TEST_REQUIRE(c.size() == 1u);
    BOOST_TEST(c[0].concentrated);
    BOOST_TEST_REQUIRE(c[0].intervals.size() == 1u);
    const ContactInterval& point = c[0].intervals[0];
    const RodState base = rod.state_at(s->x, s->vars, 0.0), at = rod.state_at(s->x, s->vars, point.centroid);
    const double h = L / elements;
    BOOST_TEST_MESSAGE(elements << " elements: R " << point.force.z() << " (reference " << R
                                << ", relative error " << point.force.z() / R - 1
                                << ") at s = " << point.centroid << "; clamp moment " << base.moment.y()
                                << " (reference " << q * L * L / 2 - R * a << ")");
    // The force is normal to the edge and the rod: vertical to the slope theta (horizontal part theta R).
    BOOST_TEST(std::abs(point.force.x()) <= 1e-3 * R);
    // Where: the section whose normal plane holds the edge, so the centerline point is the edge plus r
    // along the normal: x = a - r t_z with the unit tangent t (arc length = x up to the shortening
    // integral theta^2 / 2 dx < 1e-7 m).
    BOOST_TEST(std::abs(point.centroid - (a - test::kRadius * at.rotation(2, 2))) <= 1e-7);
    BOOST_TEST(std::abs(c[0].min_gap) <= 1e-9);  // touching: 0 to the solver tolerance 1e-10 L
    // The mesh resolves the concentrated force to one cell h: its share of the force balance lies on the
    // support of the derivative basis around a, symmetric to first order (the weights keep the first
    // moment), so the deflections at a, and with them R, change by O((h / a)^2) relatively.
    BOOST_TEST(std::abs(point.force.z() - R) <= R * (h / a) * (h / a));
    BOOST_TEST(std::abs(base.moment.y() - (q * L * L / 2 - R * a)) <= R * a * (h / a) * (h / a));
    // The rod carries the whole concentrated force (the shares are constructed to make the control points
    // of n jump by F): clamp force + R = q L to the solver tolerance (1e-10 F0, F0 = EI / L^2 = 0.6 N).
    BOOST_TEST(std::abs(-base.force.z() + point.force.z() - q * L) <= 1e-10 * kEI / (L * L));
  }
}

BOOST_AUTO_TEST_CASE(sharp_contact_jacobians_match_finite_differences) {
  // The midpoint rows (with the shares of the concentrated forces) and the rows of an infinite edge, a
  // finite edge, a point and a capsule with point contact next to a half-space, at a perturbed state with
  // positive multipliers and the contact sections inside cells (the shares' kinks lie at the midpoints, 1e-3
  // or more away from the sections here, beyond the difference step 1e-6) or beyond the rod's end (the
  // clamped branch of the section row), with both complementarity functions.
  const CollocationRod rod(test::steel_cantilever(0.3, Vec3(0, 0, -9.81), Vec3(0, 0, -0.01)),
                           test::contact_discretization(4, 6));
  Obstacle floor = sharp("floor", ObstacleShape::HalfSpace, Vec3(0, 0, -0.01));
  floor.direction = Vec3::UnitZ();
  Obstacle finite = sharp("finite", ObstacleShape::Edge, Vec3(0.2, -0.01, -0.004));
  finite.finite = true;
  finite.end = Vec3(0.21, 0.01, -0.005);
  Obstacle post = sharp("post", ObstacleShape::Capsule, Vec3(0.15, -0.01, -0.025));  // point contact
  post.end = Vec3(0.15, 0.01, -0.025);
  post.radius = 0.02;
  post.point_contact = true;
  const std::vector<Obstacle> obstacles = {
      floor, sharp("edge", ObstacleShape::Edge, Vec3(0.1, 0, -0.003)), finite,
      sharp("point", ObstacleShape::Point, Vec3(0.31, 0.002, -0.004)), post};
  const double sections[4] = {0.331, 0.6877, 1.05, 0.4789};  // u_c of the four concentrated contacts
  for (ComplementarityFunction f :
       {ComplementarityFunction::FischerBurmeister, ComplementarityFunction::Min}) {
    RodContactOptions options{obstacles, test::kRadius, f};
    Problem problem;
    const RodVariables vars = rod.add_to_problem(problem);
    const RodContactVariables contact = add_rod_contact(problem, rod, vars, options);
    BOOST_TEST_REQUIRE(contact.sharp_blocks.size() == 4u);
    VecX x = problem.initial_values();
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int i = 0; i < x.size(); ++i) x[i] += 1e-3 * unit(rng);
    for (int offset : contact.multiplier_offsets) x[offset] = 0.5 + 0.4 * unit(rng);
    for (int e = 0; e < 4; ++e) {
      const int o = contact.sharp_offsets[e];
      x[o] = sections[e];
      x[o + 1] = 0.5 + 0.4 * unit(rng);
      for (int k = 2; k < 5; ++k) x[o + k] = unit(rng);
    }
    const JacobianCheckResult r = check_problem_jacobian(problem, x);
    BOOST_TEST(r.passed, to_string(f) << ": " << r.to_string());
  }
}

BOOST_AUTO_TEST_CASE(bad_sharp_obstacle_input_names_file_line_element_and_value) {
  auto xml = [](const std::string& obstacle) {
    return R"(<?xml version="1.0"?>
<robot name="r">
  <link name="base"/>
  <pcr_rod name="beam">
    <start link="base" xyz="0 0 0" rpy="0 1.570796326795 0" coupling="clamped"/>
    <end coupling="free" force="0 0 -0.1" moment="0 0 0"/>
    <material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>
    <section type="circle" radius="0.001"/>
    <length value="0.3"/>
    <contact obstacles="e"/>
  </pcr_rod>
  )" + obstacle +
           "\n</robot>";
  };
  // Good input first: an infinite edge, a finite one and a point.
  const RobotModel m =
      parse_robot_model(xml(R"(<pcr_obstacle name="e" type="edge" xyz="0.2 0 -0.01" axis="0 1 0"/>
  <pcr_obstacle name="f" type="edge" xyz="0.2 0 -0.01" end="0.2 0.1 -0.01"/>
  <pcr_obstacle name="p" type="point" xyz="0.1 0 -0.01"/>)"));
  BOOST_TEST_REQUIRE(m.obstacles().size() == 3u);
  BOOST_TEST((m.obstacles()[0].obstacle.shape == ObstacleShape::Edge));
  BOOST_TEST(!m.obstacles()[0].obstacle.finite);
  BOOST_TEST(m.obstacles()[1].obstacle.finite);
  BOOST_TEST(m.obstacles()[1].obstacle.end.y() == 0.1);
  BOOST_TEST((m.obstacles()[2].obstacle.shape == ObstacleShape::Point));
  struct Case {
    std::string obstacle, expected;
  };
  const Case cases[] = {
      {R"(<pcr_obstacle name="e" type="edge" xyz="0.2 0 -0.01"/>)", "needs either axis"},
      {R"(<pcr_obstacle name="e" type="edge" xyz="0.2 0 -0.01" axis="0 1 0" end="0 0 0"/>)", "not both"},
      {R"(<pcr_obstacle name="e" type="edge" xyz="0.2 0 -0.01" axis="0 2 0"/>)",
       "attribute 'axis' = \"0 2 0\" is not a unit vector"},
      {R"(<pcr_obstacle name="e" type="edge" xyz="0.2 0 -0.01" end="0.2 0 -0.01"/>)",
       "attribute 'end' = \"0.2 0 -0.01\" is the same point as xyz"},
      {R"(<pcr_obstacle name="e" type="edge" xyz="0.2 0 -0.01" axis="0 1 0" radius="0.01"/>)", "'radius'"},
      {R"(<pcr_obstacle name="e" type="point" xyz="0.2 0 inf"/>)", "attribute 'xyz'"},
      {R"(<pcr_obstacle name="e" type="half_space" xyz="0 0 -0.01" normal="0 0 1" contact="point"/>)",
       "attribute 'contact' = \"point\" is given on an obstacle that is not a sphere, capsule or cylinder"},
      {R"(<pcr_obstacle name="e" type="sphere" xyz="0 0 -1" radius="0.5" contact="line"/>)",
       "attribute 'contact' = \"line\" is not a contact kind"},
  };
  for (const Case& c : cases) {
    std::string message;
    try {
      parse_robot_model(xml(c.obstacle), "bad.urdf");
    } catch (const InputError& e) {
      message = e.what();
    }
    BOOST_TEST(message.find("bad.urdf:1") == 0, message);
    BOOST_TEST(message.find("pcr_obstacle 'e'") != std::string::npos, message);
    BOOST_TEST(message.find(c.expected) != std::string::npos,
               "expected '" << c.expected << "' in: " << message);
  }
}
