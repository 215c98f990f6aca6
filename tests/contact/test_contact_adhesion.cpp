// Rollers with the adhesion law (no slip; rod_contact.hpp, docs/contact.md "Rollers"): the Jacobian of the
// adhesive contact rows against finite differences in both contact states, a propped cantilever under an
// axial tip load on a frictionless and on an adhesive roller, the roller turned, the contact open, and the
// model format (good and bad input).
#define BOOST_TEST_MODULE contact_adhesion
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "contact_fixtures.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/solve/jacobian_check.hpp"

using namespace pcr;

namespace {

const double kPi = std::acos(-1.0);
const double kArea = kPi * test::kRadius * test::kRadius;
const double kEA = test::kYoungs * kArea;
const double kEI = kArea * test::kRadius * test::kRadius / 4.0 * test::kYoungs;  // E pi r^4 / 4
const double kGA = test::kYoungs / (2.0 * (1.0 + test::kPoisson)) * kArea;       // k G A, k = 1

Obstacle adhesive_roller(const Vec3& centre, double radius, double stuck, double angle) {
  Obstacle o;
  o.name = "roller";
  o.shape = ObstacleShape::Roller;
  o.position = centre;
  o.direction = Vec3::UnitY();
  o.radius = radius;
  o.length = 0.02;
  o.law = RollerLaw::Adhesion;
  o.stuck_section = stuck;
  o.angle = angle;
  return o;
}

// The propped cantilever of the reference cases: clamp at the origin (tangent +x), length L = a (1 +
// 1 / sqrt 6), own weight q = rho A g (g = 0.01 m/s^2) along -z, an axial tip force P = 1e-3 N along +x,
// resting at x = a = 0.4 m on a roller (axis y) under it. With the overhang L - a = a / sqrt 6 the slopes
// of the span [0, a] at the prop under its own load (q a^3 / (48 EI), clamped-pinned) and under the
// overhang's moment q (L - a)^2 / 2 (its a / (4 EI) times it) cancel: the rod is horizontal at the roller.
// That matters for adhesion: a slope psi at the contact moves the centerline point over the contact by
// (R + r) sin psi along the rod, and the roller, rolled over, puts the section a + R psi there, so that a
// held span takes the axial force EA r psi / a (+ O(EA (R + r) psi^3 / a)); EA / EI = 4 / r^2 makes this
// a strong effect of any slope. The contact radius is therefore small (r_c = 1e-5 m, the roller's 2 mm),
// so that the residual slope, at most the single slope psi_q = q a^3 / (48 EI) = 2.1e-7, gives at most
// EA r psi_q / a = 3.3e-6 N.
struct PropCase {
  double a = 0.4, L, g = 0.001, P = 1e-3, R, r = 1e-5;
  double q = test::kDensity * kArea * 0.001;
  int elements = 32;
  CollocationRod rod;
  std::unique_ptr<test::ContactSolve> solve;
  std::vector<ObstacleContact> contact;
  // law: the roller with adhesion (stuck at a, turned by theta), or its side as a frictionless cylinder
  // with point contact (the slip law's concentrated form; a slip roller has only the distributed one).
  PropCase(bool adhesion, double theta, double gravity_sign = 1.0, double roller_radius = 2e-3,
           double overhang = 0.4 / std::sqrt(6.0))
      : L(0.4 + overhang),
        R(roller_radius),
        rod(test::steel_cantilever(0.4 + overhang, Vec3(0, 0, -0.001 * gravity_sign), Vec3(1e-3, 0, 0)),
            test::contact_discretization(4, 32)) {
    Obstacle o = adhesive_roller(Vec3(a, 0, -r - R), R, a, theta);
    if (!adhesion) {
      o.shape = ObstacleShape::Cylinder;
      o.law = RollerLaw::Slip;
      o.point_contact = true;
    }
    RodContactOptions options{{o}, r};
    solve = test::solve_rod(rod, &options);
    if (solve->summary.converged()) contact = read_rod_contact(rod, solve->vars, solve->contact, solve->x);
  }
  double h() const { return L / elements; }
  RodState state(double s) const { return rod.state_at(solve->x, solve->vars, s); }
  // Timoshenko propped cantilever with overhang (as test_contact_sharp.cpp): the prop R cancels the
  // deflection of the cantilever under q at x = a.
  double prop_reaction() const {
    const double wq =
        q * a * a * (6 * L * L - 4 * L * a + a * a) / (24 * kEI) + q * (L * a - a * a / 2) / kGA;
    return wq / (std::pow(a, 3) / (3 * kEI) + a / kGA);
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(adhesive_contact_jacobians_match_finite_differences) {
  // The adhesive rows (and the midpoint rows carrying their force) at perturbed states, closed (normal
  // force large against the gap: the tangency row) and open (gap large, no normal force: mu = 0), the
  // contact section inside a cell (1e-3 or more from the midpoints, the shares' kinks), both
  // complementarity functions.
  const CollocationRod rod(test::steel_cantilever(0.3, Vec3(0, 0, -9.81), Vec3(0, 0, -0.01)),
                           test::contact_discretization(4, 6));
  const Obstacle roller = adhesive_roller(Vec3(0.2, 0, -0.021), 0.02, 0.19, 0.3);  // section 0.196 m
  for (ComplementarityFunction f :
       {ComplementarityFunction::FischerBurmeister, ComplementarityFunction::Min}) {
    for (bool closed : {true, false}) {
      RodContactOptions options{{roller}, test::kRadius, f};
      Problem problem;
      const RodVariables vars = rod.add_to_problem(problem);
      const RodContactVariables contact = add_rod_contact(problem, rod, vars, options);
      BOOST_TEST_REQUIRE(contact.sharp_blocks.size() == 1u);
      BOOST_TEST_REQUIRE(contact.tangential_offsets[0] >= 0);
      VecX x = problem.initial_values();
      std::mt19937 rng(11);
      std::uniform_real_distribution<double> unit(-1.0, 1.0);
      for (int i = 0; i < x.size(); ++i) x[i] += 1e-3 * unit(rng);
      const int o = contact.sharp_offsets[0];
      x[o] = 0.6533;  // u_c
      x[o + 1] = closed ? 2.0 : 0.0;
      if (!closed)  // the whole rod 1 cm above the roller: gap ~ 0.01 m > 0 = lambda, the open branch
        for (int i = 0; i < rod.num_control_points(); ++i)
          x[vars.control_point_offset + i * rod.control_point_size() + rod.point_layout().p + 2] += 0.01;
      for (int k = 2; k < 5; ++k) x[o + k] = unit(rng);
      x[contact.tangential_offsets[0]] = 0.3 * unit(rng);
      const JacobianCheckResult r = check_problem_jacobian(problem, x);
      BOOST_TEST(r.passed, to_string(f) << (closed ? " closed: " : " open: ") << r.to_string());
    }
  }
}

// Shared bounds of the reference cases (PropCase):
//  - solver: forces to 1e-10 F0 (Newton's tolerance on the scaled rows, F0 = EI / L^2);
//  - the axial force of the held span [0, a] from the kinematics: the jump dN of the axial force at the
//    contact lies within one cell h of it in the discrete strain (the concentrated force is spread over the
//    cell), which misplaces the span's stretch by up to h dN / EA, i.e. its force by h |dN| / a; plus the
//    rolling-geometry coupling EA (R + r) psi_q / a of the residual slope (PropCase);
//  - the prop reaction against Timoshenko: (h / a)^2 relative as the edge of test_contact_sharp.cpp, plus
//    the tension's beam-column effect, of relative order P L^2 / EI = 2e-3.
namespace {
double solver_tolerance(const PropCase& p) {
  return 1e-10 * kEI / (p.L * p.L);
}
// psi_q = q a^3 / (48 EI): the slope of the span [0, a] at the prop under its own weight.
double slope_bound(const PropCase& p) {
  return p.q * std::pow(p.a, 3) / (48 * kEI);
}
double held_span_tolerance(const PropCase& p, double jump) {
  return p.h() / p.a * std::abs(jump) + kEA * p.r * slope_bound(p) / p.a;
}
double reaction_tolerance(const PropCase& p) {
  return p.prop_reaction() * (std::pow(p.h() / p.a, 2) + p.P * p.L * p.L / kEI);
}
}  // namespace

BOOST_AUTO_TEST_CASE(slip_roller_leaves_the_axial_load_to_the_clamp) {
  // Frictionless: the roller pushes along its normal (vertical here), so the span [0, a] carries the tip
  // load P to the solver tolerance plus the normal force's horizontal part R psi (R psi_q < 1e-11 N).
  const PropCase p(false, 0.0);
  BOOST_TEST_REQUIRE(p.solve->summary.converged(), p.solve->summary.message);
  const ObstacleContact& c = p.contact[0];
  BOOST_TEST(!c.adhesive);
  BOOST_TEST(c.tangential_force == 0.0);
  BOOST_TEST_REQUIRE(c.intervals.size() == 1u);
  BOOST_TEST(std::abs(p.state(p.a / 2).force.x() - p.P) <= solver_tolerance(p) + 1e-11);
  BOOST_TEST(std::abs(p.state(0.0).force.x() - p.P) <= solver_tolerance(p) + 1e-11);
  BOOST_TEST(std::abs(c.force.z() - p.prop_reaction()) <= reaction_tolerance(p));
}

BOOST_AUTO_TEST_CASE(adhesive_roller_at_rest_takes_the_axial_load) {
  // No slip, roller at rest (theta = 0, stuck at a): the span [0, a] is held at both ends axially and
  // carries no axial force; the roller carries P tangentially (along -t on the rod).
  const PropCase p(true, 0.0);
  BOOST_TEST_REQUIRE(p.solve->summary.converged(), p.solve->summary.message);
  const ObstacleContact& c = p.contact[0];
  BOOST_TEST(c.adhesive);
  BOOST_TEST_REQUIRE(c.intervals.size() == 1u);
  const double N = p.state(p.a / 2).force.x();
  BOOST_TEST_MESSAGE("adhesion at rest: N(a/2) = " << N << " N (tolerance " << held_span_tolerance(p, p.P)
                                                   << "), tangential force " << c.tangential_force << " N");
  BOOST_TEST(std::abs(N) <= held_span_tolerance(p, p.P));
  // The rod's force balance across the contact: n(a-) - n(a+) = tangential force (exact up to the solver).
  BOOST_TEST(std::abs(c.tangential_force - (N - p.P)) <= solver_tolerance(p));
  BOOST_TEST(std::abs(c.tangential_force + p.P) <= held_span_tolerance(p, p.P) + solver_tolerance(p));
  // The contact section is the stuck one, rolled by R psi (|psi| <= psi_q), the normal force the prop's.
  BOOST_TEST(std::abs(c.intervals[0].centroid - p.a) <= 1e-12 + slope_bound(p) * p.R);
  BOOST_TEST(std::abs(c.force.z() - p.prop_reaction()) <= reaction_tolerance(p));
}

BOOST_AUTO_TEST_CASE(turning_an_adhesive_roller_stretches_the_held_span) {
  // Turned by theta > 0 about its axis y, the roller's top moves toward +x, the rod's tip: the section
  // a - R theta comes to the contact, at x = a: the span of reference length a - R theta spans a, strain
  // a / (a - R theta) - 1, axial force N = EA (a / (a - R theta) - 1) (linear elastic in the strain),
  // ~ EA R theta / a = 0.0157 N here.
  const double theta = 5e-6;
  const PropCase p(true, theta);
  BOOST_TEST_REQUIRE(p.solve->summary.converged(), p.solve->summary.message);
  const ObstacleContact& c = p.contact[0];
  const double expected = kEA * (p.a / (p.a - p.R * theta) - 1.0), N = p.state(p.a / 2).force.x();
  BOOST_TEST_MESSAGE("turned: N(a/2) = " << N << " N, reference " << expected);
  BOOST_TEST(std::abs(N - expected) <= held_span_tolerance(p, expected - p.P));
  BOOST_TEST(std::abs(c.tangential_force - (N - p.P)) <= solver_tolerance(p));
  BOOST_TEST_REQUIRE(c.intervals.size() == 1u);
  // The section at the contact: a - R theta, rolled by R psi (|psi| <= psi_q: R psi_q = 4e-10 m).
  BOOST_TEST(std::abs(c.intervals[0].centroid - (p.a - p.R * theta)) <= 1e-12 + slope_bound(p) * p.R);
  // The held span's tension (N a^2 / EI = 1.6e-2) changes its bending: the prop reaction within that.
  BOOST_TEST(std::abs(c.force.z() - p.prop_reaction()) <=
             reaction_tolerance(p) + p.prop_reaction() * N * p.a * p.a / kEI);
}

BOOST_AUTO_TEST_CASE(a_rod_rolls_over_an_adhesive_roller_at_rest) {
  // A short overhang (0.05 m): the slopes no longer cancel, the rod rises toward the prop with the
  // Euler-Bernoulli slope psi = psi_q (1 - 6 l^2 / a^2) (clamped-pinned span under q minus the overhang's
  // moment q l^2 / 2 times a / (4 EI); shear strain V / kGA < 1e-9 of it), so that the contact direction
  // turns by -psi about y and the roller at rest lets the rod roll back: the section a - R psi is at the
  // contact. The span then takes only EA r psi / a (PropCase; without the rolling, EA (R + r) psi / a =
  // 6e-4 N, 60 % of P).
  const double l = 0.05;
  const PropCase p(true, 0.0, 1.0, 2e-3, l);
  BOOST_TEST_REQUIRE(p.solve->summary.converged(), p.solve->summary.message);
  const ObstacleContact& c = p.contact[0];
  BOOST_TEST_REQUIRE(c.intervals.size() == 1u);
  const double psi = slope_bound(p) * (1.0 - 6.0 * l * l / (p.a * p.a)), N = p.state(p.a / 2).force.x();
  BOOST_TEST_MESSAGE("rolled: section " << c.intervals[0].centroid - p.a << " m from a (reference "
                                        << -p.R * psi << "), N(a/2) = " << N << " N");
  // The slope is resolved to (h / a) of the single slopes (the concentrated force spread over one cell).
  BOOST_TEST(std::abs(c.intervals[0].centroid - (p.a - p.R * psi)) <= p.R * slope_bound(p) * p.h() / p.a);
  BOOST_TEST(std::abs(N) <= held_span_tolerance(p, p.P));
  BOOST_TEST(std::abs(c.tangential_force - (N - p.P)) <= solver_tolerance(p));
}

BOOST_AUTO_TEST_CASE(an_open_adhesive_contact_carries_no_force) {
  // Gravity reversed: the rod lifts off the roller (the start touches it: the contact switches from
  // closed to open during the solve); no normal and no tangential force, the clamp carries P.
  const PropCase p(true, 0.0, -1.0);
  BOOST_TEST_REQUIRE(p.solve->summary.converged(), p.solve->summary.message);
  const ObstacleContact& c = p.contact[0];
  BOOST_TEST(c.intervals.empty());
  BOOST_TEST(c.tangential_force == 0.0);
  BOOST_TEST(c.force.norm() == 0.0);
  BOOST_TEST(c.min_gap > 0.0);
  BOOST_TEST(std::abs(p.state(p.a / 2).force.x() - p.P) <= solver_tolerance(p));
  // The multipliers themselves: lambda and mu vanish to the solver tolerance (scaled by L0 / F0).
  const double scale = p.L / (kEI / (p.L * p.L));
  BOOST_TEST(std::abs(p.solve->x[p.solve->contact.sharp_offsets[0] + 1]) * scale <= 1e-10);
  BOOST_TEST(std::abs(p.solve->x[p.solve->contact.tangential_offsets[0]]) * scale <= 1e-10);
}

namespace {

std::string adhesive_model(const std::string& obstacle, const std::string& second_rod = "") {
  return R"(<?xml version="1.0"?>
<robot name="r">
  <link name="base"/>
  <pcr_rod name="beam">
    <start link="base" xyz="0 0 0" rpy="0 1.570796326795 0" coupling="clamped"/>
    <end coupling="free" force="0.001 0 -0.001" moment="0 0 0"/>
    <material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>
    <section type="circle" radius="0.001"/>
    <length value="0.3"/>
    <discretization elements="16"/>
    <contact obstacles="roller"/>
  </pcr_rod>
  )" + second_rod +
         obstacle + "\n</robot>";
}

}  // namespace

BOOST_AUTO_TEST_CASE(adhesive_roller_in_the_model_format) {
  // A cantilever (0.3 m, tip force (1e-3, 0, -1e-3) N) on an adhesive roller (radius 10 mm) at x = 0.2 m
  // at rest, read from the model format and solved by FK: the contact is at the stuck section and carries
  // a tangential force, listed in the JSON and the table. Its value is not P here: the tip load tilts the
  // rod at the roller by psi, and the held span [0, a] takes EA (R + r) psi / a (PropCase); the references
  // are the PropCase tests. A frictionless contact would have none (0 exactly); here it exceeds P.
  const auto model = std::make_shared<const RobotModel>(parse_robot_model(adhesive_model(
      R"(<pcr_obstacle name="roller" type="roller" xyz="0.2 0 -0.011" axis="0 1 0" radius="0.01" length="0.02"
      law="adhesion" stuck_at="0.2"/>)")));
  BOOST_TEST_REQUIRE(model->obstacles().size() == 1u);
  const Obstacle& o = model->obstacles()[0].obstacle;
  BOOST_TEST((o.law == RollerLaw::Adhesion));
  BOOST_TEST(o.stuck_section == 0.2);
  BOOST_TEST(o.angle == 0.0);
  ForwardKinematics fk(model);
  const RobotSolution s = fk.solve(model->default_input_values());
  BOOST_TEST_REQUIRE(s.summary.converged(), s.summary.message);
  BOOST_TEST_REQUIRE(s.contacts.size() == 1u);
  const ObstacleContact& c = s.contacts[0];
  BOOST_TEST(c.adhesive);
  BOOST_TEST_REQUIRE(c.intervals.size() == 1u);
  // Rolled by R psi from the stuck section, psi below the tip load's slope scale P L^2 / EI = 6e-4.
  BOOST_TEST(std::abs(c.intervals[0].centroid - 0.2) <= 0.01 * 6e-4);
  BOOST_TEST(std::abs(c.tangential_force) > 1e-3);
  BOOST_TEST(std::isfinite(c.tangential_force));
  std::ostringstream json, table;
  BOOST_TEST(write_solution_json(json, *model, s) == 0);
  write_solution_table(table, *model, s);
  BOOST_TEST(json.str().find("\"tangential_force\"") != std::string::npos, json.str());
  BOOST_TEST(table.str().find("(adhesion)") != std::string::npos, table.str());
}

BOOST_AUTO_TEST_CASE(bad_adhesion_input_names_file_line_element_and_value) {
  const std::string roller = R"(<pcr_obstacle name="roller" type="roller" xyz="0.2 0 -0.011" axis="0 1 0" )"
                             R"(radius="0.01" length="0.02" )";
  struct Case {
    std::string obstacle, second_rod, expected;
  };
  const std::string other = R"(<pcr_rod name="other">
    <start link="base" xyz="0 0.1 0" rpy="0 1.570796326795 0" coupling="clamped"/>
    <end coupling="free" force="0 0 0" moment="0 0 0"/>
    <material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>
    <section type="circle" radius="0.001"/>
    <length value="0.3"/>
    <contact obstacles="roller"/>
  </pcr_rod>
  )";
  const Case cases[] = {
      {roller + R"(law="glue" stuck_at="0.2"/>)", "", "attribute 'law' = \"glue\" is not a roller law"},
      {R"(<pcr_obstacle name="roller" type="sphere" xyz="0.2 0 -0.02" radius="0.01" law="adhesion"/>)", "",
       "attribute 'law' = \"adhesion\" is given on an obstacle that is not a roller"},
      {roller + R"(law="adhesion"/>)", "", "attribute 'law' = \"adhesion\" needs stuck_at"},
      {roller + R"(stuck_at="0.2"/>)", "", "attribute 'stuck_at' = \"0.2\" is given without law"},
      {roller + R"(law="slip" angle="1"/>)", "", "attribute 'law' = \"slip\" takes no stuck_at or angle"},
      {roller + R"(law="adhesion" stuck_at="-0.1"/>)", "", "attribute 'stuck_at' = \"-0.1\""},
      {roller + R"(law="adhesion" stuck_at="0.2" angle="-20"/>)", "",
       "attribute 'obstacles' = \"roller\" is an adhesive roller whose section at the contact"},
      {roller + R"(law="adhesion" stuck_at="0.2"/>)", other,
       "attribute 'obstacles' = \"roller\" is an adhesive roller already named by pcr_rod 'beam'"},
  };
  for (const Case& c : cases) {
    std::string message;
    try {
      parse_robot_model(adhesive_model(c.obstacle, c.second_rod), "bad.urdf");
    } catch (const InputError& e) {
      message = e.what();
    }
    BOOST_TEST(message.find("bad.urdf:") == 0, message);
    BOOST_TEST(message.find(c.expected) != std::string::npos,
               "expected '" << c.expected << "' in: " << message);
  }
}

BOOST_AUTO_TEST_CASE(adhesion_on_a_drawn_rod_is_rejected) {
  // The no-slip law of a drawn rod prescribes its axial strain at the contact (docs/contact.md), not a
  // material section: not implemented, rejected with the rod, the roller and the speed.
  RodModel m = test::steel_cantilever(0.3, Vec3::Zero(), Vec3(0, 0, -0.01));
  m.drawing_speed = 1.0;
  const CollocationRod rod(m, test::contact_discretization(4, 8));
  Problem problem;
  const RodVariables vars = rod.add_to_problem(problem);
  RodContactOptions options{{adhesive_roller(Vec3(0.2, 0, -0.021), 0.02, 0.2, 0.0)}, test::kRadius};
  std::string message;
  try {
    add_rod_contact(problem, rod, vars, options);
  } catch (const InputError& e) {
    message = e.what();
  }
  BOOST_TEST(message.find("rod 'beam': adhesive roller 'roller' on a drawn rod") != std::string::npos,
             message);
}

BOOST_AUTO_TEST_CASE(shipped_adhesive_roller_model) {
  // models/adhesive_roller.urdf: span a = 0.2 m, overhang l = 0.1 m with the tip force (P, 0, -W) =
  // (1e-3, 0, -0.02) N, roller R = 10 mm turned by theta = 2e-5 rad, contact radius r = 1 mm. Beam theory:
  // the overhang's moment W l at the prop tilts the span there by psi = W l a / (4 EI) (propped
  // cantilever under an end moment), the roller rolls R psi, the centerline over it moves (R + r) psi,
  // so the span is stretched by R theta + r psi: N = EA (R theta + r psi) / a and the roller's tangential
  // force is N - P. Tolerance: the held-span bound h |dN| / a of PropCase (h = 12.5 mm).
  auto model = std::make_shared<const RobotModel>(
      load_robot_model(std::string(PCR_MODEL_DIR) + "/adhesive_roller.urdf"));
  ForwardKinematics fk(model);
  const RobotSolution s = fk.solve(model->default_input_values());
  BOOST_TEST_REQUIRE(s.summary.converged(), s.summary.message);
  BOOST_TEST_REQUIRE(s.contacts.size() == 1u);
  const double a = 0.2, l = 0.1, P = 1e-3, W = 0.02, R = 0.01, theta = 2e-5, r = 1e-3, h = 0.3 / 24;
  const double psi = W * l * a / (4 * kEI), N = kEA * (R * theta + r * psi) / a;
  BOOST_TEST_MESSAGE("shipped model: tangential force " << s.contacts[0].tangential_force << " N, reference "
                                                        << N - P);
  BOOST_TEST(std::abs(s.contacts[0].tangential_force - (N - P)) <= h / a * std::abs(N - P));
}
