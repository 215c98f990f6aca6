// Drawn rods at their divergence speed: the stability verdict of an axially moving beam under tension
// changes where rho A c^2 = T + (x / l)^2 EI, between two clamps, a clamp and a pin, and two pins
// (collocation and shooting); and the universal ends of drawn rods whose state the verdict cannot test.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>
#include <string>

#include "drawn_fixtures.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/rods/drawn_rod.hpp"
#include "pcr/rods/rod_solve.hpp"
#include "pcr/rods/shooting/rod_shooting.hpp"
#include "pcr/rods/stability/rod_stability.hpp"

using namespace pcr;

namespace {

// Steel wire r = 1 mm between two supports a span l = 0.5 m apart, drawn at c, tension T = 10 N in the
// straight state: the reference length l / (1 + T / EA) stretched to l carries n . d3 = EA eps3 = T.
constexpr double kSpan = 0.5, kTension = 10.0;

// The supports: a clamp, a pin (Spherical), or a pin that holds the twist (Universal, first axis d1 of
// the straight rod, second axis d2 = e3 x d1: both bending rotations free). Two spherical ends would
// leave the twist free.
RodModel moving_beam(double c, RodEndKind base, RodEndKind tip) {
  RodModel m = test::steel_wire(1e-3, 1.0);
  m.name = "moving_beam";
  m.length = kSpan / (1.0 + kTension / m.shear_extension_stiffness[2]);
  m.base.kind = base;
  m.tip.kind = tip;
  m.tip.position = Vec3(0.0, 0.0, kSpan);
  m.drawing_speed = c;
  return m;
}

struct Verdicts {
  Stability collocation, shooting;
  RodState middle;  ///< the collocation state at s = L / 2
};

// The verdicts of collocation (mixed, degree 6, 16 elements) and shooting on the solved model.
Verdicts verdicts(const RodModel& m) {
  RodSolveOptions o;
  o.discretization = {RodFormulation::Mixed, 6, 16};
  o.tolerance = 1e-12;
  o.stability_verdict = true;
  const RodSolution col = solve_rod(m, o);
  BOOST_REQUIRE(col.summary.converged());
  const ShootingSolution sh = solve_rod_shooting(m);
  BOOST_REQUIRE(sh.summary.converged());
  return {col.stability_verdict, rod_stability(m, sh), col.at(0.5 * m.length)};
}

// The verdicts just below and above the divergence speed c_d: stable at 0.995 c_d; at 1.005 c_d unstable
// with `modes_above` unstable modes (the lowest buckling mode of the span in each of the round wire's two
// bending planes: 2).
void check_verdicts_around(double c_d, RodEndKind base, RodEndKind tip, int modes_above) {
  for (double factor : {0.995, 1.005}) {
    const Verdicts v = verdicts(moving_beam(factor * c_d, base, tip));
    // The straight state: section force T along the axis (n = N + rho A c^2 p', drawn_rod.hpp).
    BOOST_TEST(v.middle.force[2] == kTension, boost::test_tools::tolerance(1e-9));
    BOOST_TEST(v.middle.position.head<2>().norm() < 1e-12);
    const Stability &sc = v.collocation, &ss = v.shooting;
    BOOST_TEST_MESSAGE("c = " << factor << " c_d: collocation " << to_string(sc.verdict) << " ("
                              << sc.unstable_modes << " unstable modes, margin " << sc.margin
                              << "), shooting " << to_string(ss.verdict) << " (" << ss.unstable_modes
                              << ", margin " << ss.margin << ") " << sc.reason << " " << ss.reason);
    const StabilityVerdict expected = factor < 1.0 ? StabilityVerdict::Stable : StabilityVerdict::Unstable;
    BOOST_TEST((sc.verdict == expected), "collocation at " << factor << " c_d: " << to_string(sc.verdict));
    BOOST_TEST((ss.verdict == expected), "shooting at " << factor << " c_d: " << to_string(ss.verdict));
    const int modes = factor < 1.0 ? 0 : modes_above;
    BOOST_TEST(sc.unstable_modes == modes);
    BOOST_TEST(ss.unstable_modes == modes);
  }
}

// Euler-Bernoulli divergence of the translating beam (Wickert & Mote, "Classical vibration analysis of
// axially moving continua", J. Appl. Mech. 57 (1990) 738-744: the lowest frequency vanishes where the
// axial momentum flux exceeds tension plus the buckling load of the span):
//   rho A c_d^2 = T + (x / l)^2 EI,   x = 2 pi between clamps, x = the smallest root of tan x = x
//   (4.4934) between a clamp and a pin, x = pi between two pins (Timoshenko & Gere, Theory of Elastic
//   Stability, 2.6 and 2.1).
// The Cosserat rod's shear, rotary inertia and extensibility move it by O((r / l)^2, T / EA) ~ 1e-5, far
// inside the +-0.5 % bracket asserted.
double divergence_speed(double x) {
  const RodModel probe = moving_beam(0.0, RodEndKind::Clamped, RodEndKind::Clamped);
  const double EI = probe.bending_torsion_stiffness[0], rhoA = probe.mass_per_length;
  return std::sqrt((kTension + x * x * EI / (kSpan * kSpan)) / rhoA);
}

}  // namespace

BOOST_AUTO_TEST_CASE(divergence_speed_of_an_axially_moving_clamped_beam) {
  const double c_d = divergence_speed(2.0 * M_PI);
  BOOST_TEST_MESSAGE("c_d (Euler-Bernoulli, clamped-clamped) = " << c_d << " m/s");
  check_verdicts_around(c_d, RodEndKind::Clamped, RodEndKind::Clamped, 2);
}

BOOST_AUTO_TEST_CASE(divergence_speed_of_an_axially_moving_clamped_pinned_beam) {
  double x = 4.5;  // tan x = x near 3 pi / 2 - 0.22: Newton on f = sin x - x cos x, f' = x sin x
  for (int i = 0; i < 50; ++i) x -= (std::sin(x) - x * std::cos(x)) / (x * std::sin(x));
  BOOST_REQUIRE(std::abs(std::sin(x) - x * std::cos(x)) < 1e-14);
  const double c_d = divergence_speed(x);
  BOOST_TEST_MESSAGE("c_d (Euler-Bernoulli, clamped-pinned, x = " << x << ") = " << c_d << " m/s");
  check_verdicts_around(c_d, RodEndKind::Clamped, RodEndKind::Spherical, 2);
}

BOOST_AUTO_TEST_CASE(divergence_speed_of_an_axially_moving_pinned_beam) {
  // A spherical base and a universal tip: the tip's joint conditions on the section moment m are those on
  // the effective M in this straight, untwisted state (rod_stability.hpp drawn_joint_state_problem). Two
  // unstable modes above c_d: the tip is a pin in both bending planes (held in one, that plane's c_d would
  // be the clamped-pinned one, 18 % higher, and one mode would remain).
  const double c_d = divergence_speed(M_PI);
  BOOST_TEST_MESSAGE("c_d (Euler-Bernoulli, pinned-pinned) = " << c_d << " m/s");
  check_verdicts_around(c_d, RodEndKind::Spherical, RodEndKind::Universal, 2);
}

BOOST_AUTO_TEST_CASE(drawn_universal_ends_the_verdict_cannot_test) {
  // The model part: an applied moment or intrinsic curvature at a universal end of a drawn rod.
  RodModel loaded = moving_beam(10.0, RodEndKind::Clamped, RodEndKind::Universal);
  BOOST_TEST(drawn_end_problem(loaded).empty());
  loaded.tip.moment = Vec3(0.0, 0.0, 1e-3);
  BOOST_TEST(drawn_end_problem(loaded).find("universal tip") != std::string::npos, drawn_end_problem(loaded));
  RodModel curved = moving_beam(10.0, RodEndKind::Universal, RodEndKind::Clamped);
  curved.intrinsic.curvature = Vec3(0.1, 0.0, 0.0);
  BOOST_TEST(drawn_end_problem(curved).find("universal base") != std::string::npos,
             drawn_end_problem(curved));
  // Not restricted to round sections: m_i = lambda M_i with the same lambda = 1 / (1 - rho c^2 / E) in
  // both bending directions of any homogeneous section (m = M + rho c^2 R J kappa, rho J_i = rho I_i).
  RodModel flat = moving_beam(10.0, RodEndKind::Clamped, RodEndKind::Universal);
  flat.set_material_and_section(Material::from_poisson_ratio(200e9, 0.3, 7850.0),
                                CrossSection::rectangle(4e-3, 2e-3));
  const DrawnConstants d = drawn_constants(flat, Vec3::Zero(), Vec3::Zero());
  const double lambda = 1.0 / (1.0 - 7850.0 * 100.0 / 200e9);
  for (int i = 0; i < 2; ++i)  // round-off of the effective constants
    BOOST_TEST(1.0 + d.flux_moment[i] / d.k_bt[i] == lambda, boost::test_tools::tolerance(1e-13));
  BOOST_TEST(drawn_end_problem(flat).empty(), drawn_end_problem(flat));

  // The state part, below c_d (c = 20 m/s, c_d = 25.6 m/s): a span twisted by 0.3 rad (the universal tip's
  // frame turned about the tangent), and one whose first axis is tilted towards the tangent (d3 . a =
  // 0.5 / sqrt(1.25) = 0.447). Both unknown with the reason; both get a verdict at rest (c = 0).
  RodModel twisted = moving_beam(20.0, RodEndKind::Clamped, RodEndKind::Universal);
  twisted.tip.orientation = quat_from_rotation_vector(Vec3(0.0, 0.0, 0.3));
  RodModel tilted = moving_beam(20.0, RodEndKind::Clamped, RodEndKind::Universal);
  tilted.tip.axis = Vec3(1.0, 0.0, 0.5);
  const std::pair<const RodModel*, const char*> cases[] = {{&twisted, "u3 L = 0.3"},
                                                           {&tilted, "d3 . a = 0.447"}};
  for (const auto& [model, value] : cases) {
    BOOST_TEST(nonconservative_loads(*model).empty());  // only the state decides
    const Verdicts v = verdicts(*model);
    for (const Stability* s : {&v.collocation, &v.shooting}) {
      BOOST_TEST_MESSAGE(to_string(s->verdict) << ": " << s->reason);
      BOOST_TEST((s->verdict == StabilityVerdict::Unknown), to_string(s->verdict));
      for (const char* part : {"'moving_beam'", "universal tip", value})
        BOOST_TEST(s->reason.find(part) != std::string::npos, "'" << part << "' in: " << s->reason);
    }
    RodModel at_rest = *model;
    at_rest.drawing_speed = 0.0;
    const Verdicts r = verdicts(at_rest);
    BOOST_TEST((r.collocation.verdict == StabilityVerdict::Stable), r.collocation.reason);
    BOOST_TEST((r.shooting.verdict == StabilityVerdict::Stable), r.shooting.reason);
  }
}

BOOST_AUTO_TEST_CASE(pinned_span_in_a_robot) {
  // The span of divergence_speed_of_an_axially_moving_pinned_beam as a robot rod. A robot's couplings
  // hold the effective N, M (docs/model_format.md "drawing_speed"), so their conditions are natural ones
  // of the effective energy; the verdict (robot_stability.hpp) changes at c_d as the rod's does.
  const double c_d = divergence_speed(M_PI);
  const RodModel beam = moving_beam(c_d, RodEndKind::Spherical, RodEndKind::Universal);
  KinematicsOptions options;
  options.stability_verdict = true;
  for (double factor : {0.995, 1.005}) {
    std::ostringstream xml;
    xml << std::setprecision(17) << R"(<robot name="span">
  <link name="base"/>
  <link name="support"/>
  <joint name="support_joint" type="fixed">
    <parent link="base"/>
    <child link="support"/>
    <origin xyz="0 0 )"
        << kSpan << R"(" rpy="0 0 0"/>
  </joint>
  <pcr_rod name="span" drawing_speed=")"
        << factor * c_d << R"(">
    <start link="base" xyz="0 0 0" rpy="0 0 0" coupling="spherical"/>
    <end link="support" xyz="0 0 0" rpy="0 0 0" coupling="universal" axis="1 0 0"/>
    <material youngs_modulus="200e9" poisson_ratio="0.3" density="7850"/>
    <section type="circle" radius="0.001"/>
    <length value=")"
        << beam.length << R"("/>
    <discretization formulation="mixed" degree="6" elements="16"/>
  </pcr_rod>
</robot>)";
    ForwardKinematics fk(std::make_shared<const RobotModel>(parse_robot_model(xml.str(), "span.urdf")),
                         options);
    const RobotSolution s = fk.solve(VecX());
    BOOST_REQUIRE(s.summary.converged());
    const Stability& v = s.stability_verdict;
    BOOST_TEST_MESSAGE("robot, c = " << factor << " c_d: " << to_string(v.verdict) << " (" << v.unstable_modes
                                     << " unstable modes, margin " << v.margin << ") " << v.reason);
    const bool below = factor < 1.0;
    BOOST_TEST((v.verdict == (below ? StabilityVerdict::Stable : StabilityVerdict::Unstable)), v.reason);
    BOOST_TEST(v.unstable_modes == (below ? 0 : 2));
  }
}
