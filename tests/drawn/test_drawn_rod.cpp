// Drawn rods (steady axial motion, docs/design.md §1 "Drawn rods"): input checks, c = 0 unchanged, every
// collocation formulation against the shooting reference, finite-difference Jacobians of the blocks
// with the effective constants, and the shooting ODE's conversions between n, m and N, M.
#define BOOST_TEST_MODULE drawn_rod
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "drawn_fixtures.hpp"
#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/rods/collocation_rod.hpp"
#include "pcr/rods/drawn_rod.hpp"
#include "pcr/rods/rod_solve.hpp"
#include "pcr/rods/shooting/rod_ode.hpp"
#include "pcr/rods/shooting/rod_shooting.hpp"
#include "pcr/solve/jacobian_check.hpp"
#include "rods/rod_fixtures.hpp"

using namespace pcr;

namespace {

bool message_has(const InputError& e, std::initializer_list<const char*> parts) {
  const std::string what = e.what();
  for (const char* p : parts)
    if (what.find(p) == std::string::npos) {
      BOOST_TEST_MESSAGE("missing '" << p << "' in: " << what);
      return false;
    }
  return true;
}

std::string wire_model(const std::string& drawing_speed, const std::string& formulation = "mixed",
                       const std::string& radius = "0.001") {
  return R"(<?xml version="1.0"?>
<robot name="drawn">
  <link name="base"/>
  <pcr_rod name="wire" drawing_speed=")" +
         drawing_speed + R"(">
    <start link="base" xyz="0 0 0" rpy="0 1.570796326795 0" coupling="clamped"/>
    <end coupling="free" force="0 0 -0.1"/>
    <material youngs_modulus="200e9" poisson_ratio="0.3" density="7850"/>
    <section type="circle" radius=")" +
         radius + R"("/>
    <length value="0.5"/>
    <discretization formulation=")" +
         formulation + R"(" degree="4" elements="4"/>
  </pcr_rod>
</robot>
)";
}

ShootingOptions tight_shooting() {
  ShootingOptions o;
  o.tolerance = 1e-12;
  o.integration_relative_tolerance = 1e-12;
  o.integration_absolute_tolerance = 1e-14;
  return o;
}

}  // namespace

BOOST_AUTO_TEST_CASE(bad_drawing_speeds_are_rejected_with_the_limit) {
  RodModel m = test::bent_cantilever(std::numeric_limits<double>::quiet_NaN());
  BOOST_CHECK_EXCEPTION(m.validate(), InputError, [](const InputError& e) {
    return message_has(e, {"'bent'", "drawing_speed", "finite"});
  });
  // Steel, k = 1: the shear limit sqrt(k G / rho) = 3130 m/s comes first (bending: sqrt(E / rho) = 5048).
  m.drawing_speed = -3200.0;
  BOOST_CHECK_EXCEPTION(m.validate(), InputError, [](const InputError& e) {
    return message_has(e, {"'bent'", "-3200", "shear stiffness kGA (d1)", "|c| < 3130"});
  });
  m.drawing_speed = 3000.0;
  BOOST_CHECK_NO_THROW(m.validate());
  m.intrinsic.varying = [](double s, Vec3&, Vec3& kappa0) { kappa0[0] += s; };
  BOOST_CHECK_EXCEPTION(m.validate(), InputError, [](const InputError& e) {
    return message_has(e, {"'bent'", "uniform rod"});
  });
  // Torsion: GJ - rho c^2 (I1 + I2) on a section whose polar moment exceeds J (a thin rectangle).
  RodModel r = test::steel_wire(1e-3, 0.4);
  r.set_material_and_section(Material::from_poisson_ratio(200e9, 0.3, 7850.0),
                             CrossSection::rectangle(0.01, 0.001));
  r.drawing_speed = 1500.0;
  BOOST_CHECK_EXCEPTION(r.validate(), InputError, [](const InputError& e) {
    return message_has(e, {"torsional stiffness GJ", "K_BT"});
  });
}

BOOST_AUTO_TEST_CASE(model_file_drawing_speed) {
  const RobotModel ok = parse_robot_model(wire_model("12.5"), "drawn.urdf");
  BOOST_TEST(ok.rods().at(0).rod.drawing_speed == 12.5);
  BOOST_TEST(parse_robot_model(wire_model("0"), "drawn.urdf").rods().at(0).rod.drawing_speed == 0.0);
  BOOST_CHECK_EXCEPTION(
      parse_robot_model(wire_model("4000"), "drawn.urdf"), InputError, [](const InputError& e) {
        return message_has(e,
                           {"drawn.urdf:4", "'wire'", "drawing_speed", "4000", "shear stiffness kGA (d1)"});
      });
  BOOST_CHECK_EXCEPTION(parse_robot_model(wire_model("fast"), "drawn.urdf"), InputError,
                        [](const InputError& e) {
                          return message_has(e, {"drawn.urdf:4", "drawing_speed"});
                        });
}

BOOST_AUTO_TEST_CASE(effective_constants_and_wrench_conversion) {
  // (M4): K_SE,eff (eps - eps0_eff) = K_SE (eps - eps0) - rho A c^2 (e3 + eps) for any eps; likewise
  // K_BT,eff (kappa - kappa0_eff) = K_BT (kappa - kappa0) - rho c^2 J_rho kappa.
  const RodModel m = test::bent_cantilever(30.0);
  const DrawnConstants d = drawn_constants(m, m.intrinsic.shear_extension, m.intrinsic.curvature);
  const double rhoA = m.mass_per_length, c2 = 900.0;
  BOOST_TEST(d.flux_force == rhoA * c2, boost::test_tools::tolerance(1e-15));
  // rho J_rho = rho diag(I, I, 2 I) for the circle, I = pi r^4 / 4 (independent of the stiffness data).
  const double rhoI = 7850.0 * M_PI * 1e-12 / 4.0;
  BOOST_TEST(d.flux_moment[0] == rhoI * c2, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(d.flux_moment[2] == 2.0 * rhoI * c2, boost::test_tools::tolerance(1e-12));
  const Vec3 eps(0.01, -0.02, 0.003), kappa(0.5, 2.0, -1.0);
  const Vec3 lhs_n = d.k_se.cwiseProduct(eps - d.eps0);
  const Vec3 rhs_n = m.shear_extension_stiffness.cwiseProduct(eps - m.intrinsic.shear_extension) -
                     d.flux_force * (Vec3::UnitZ() + eps);
  const Vec3 lhs_m = d.k_bt.cwiseProduct(kappa - d.kappa0);
  const Vec3 rhs_m = m.bending_torsion_stiffness.cwiseProduct(kappa - m.intrinsic.curvature) -
                     d.flux_moment.cwiseProduct(kappa);
  // Round-off of K_SE ~ 2.4e5 N times strains ~1e-2: 1e-9 N absolute.
  BOOST_TEST((lhs_n - rhs_n).norm() < 1e-9);
  BOOST_TEST((lhs_m - rhs_m).norm() < 1e-12);
  // section_wrench / effective_wrench are inverse to each other (round-off).
  const Mat3 R = rotation_matrix(Quat(0.3, -0.5, 0.2, 0.7).normalized());
  const Vec3 N(1.0, -2.0, 0.5), M(0.1, 0.05, -0.02);
  Vec3 n, mm, N2, M2;
  section_wrench(d, R, N, M, n, mm);
  effective_wrench(d, R, n, mm, N2, M2);
  BOOST_TEST((N2 - N).norm() < 1e-12);
  BOOST_TEST((M2 - M).norm() < 1e-15);
  // n - N = rho A c^2 p' with p' = R (e3 + eps) from the effective law.
  const Vec3 p_s = R * (Vec3::UnitZ() + d.eps0 + d.k_se.cwiseInverse().cwiseProduct(R.transpose() * N));
  BOOST_TEST((n - N - d.flux_force * p_s).norm() < 1e-12);
}

namespace {

struct Compared {
  double position = 0.0, rotation = 0.0, force = 0.0, moment = 0.0;  ///< largest relative differences
};

// Collocation against shooting at s = 0, L/3, L: positions relative to L, rotations (Frobenius), the
// section force and moment relative to the largest of each along the rod.
Compared compare_with_shooting(const RodModel& model, const RodDiscretization& d) {
  RodSolveOptions o;
  o.discretization = d;
  o.tolerance = 1e-12;
  o.stability_verdict = false;
  const RodSolution col = solve_rod(model, o);
  const ShootingSolution sh = solve_rod_shooting(model, tight_shooting());
  BOOST_REQUIRE(col.summary.converged());
  BOOST_REQUIRE(sh.summary.converged());
  Compared c;
  double f_max = 0.0, m_max = 0.0;
  for (double s : {0.0, model.length / 3.0, model.length}) {
    const ShootingState b = sh.at(s);
    f_max = std::max(f_max, b.n.norm());
    m_max = std::max(m_max, b.m.norm());
  }
  for (double s : {0.0, model.length / 3.0, model.length}) {
    const RodState a = col.at(s);
    const ShootingState b = sh.at(s);
    c.position = std::max(c.position, (a.position - b.p).norm() / model.length);
    c.rotation = std::max(c.rotation, (a.rotation - b.R()).norm());
    c.force = std::max(c.force, (a.force - b.n).norm() / f_max);
    c.moment = std::max(c.moment, (a.moment - b.m).norm() / m_max);
  }
  return c;
}

}  // namespace

BOOST_AUTO_TEST_CASE(collocation_matches_shooting_on_a_drawn_3d_rod) {
  // Slender wire (r = 1 mm, L = 0.4 m, tip force ~1 N) at c = 3 m/s: rho A c^2 = 0.22 N, about 20 % of
  // the tip force. The drawn terms move the tip by 1e-2 L or more (asserted), so the comparison sees them.
  const RodModel drawn = test::bent_cantilever(3.0);
  RodSolveOptions o;
  o.discretization = {RodFormulation::Mixed, 6, 16};
  const Vec3 tip_static = solve_rod(test::bent_cantilever(0.0), o).tip().position;
  const Vec3 tip_drawn = solve_rod(drawn, o).tip().position;
  BOOST_TEST((tip_drawn - tip_static).norm() / drawn.length > 1e-2);
  // Tolerance 1e-9: the same comparison at c = 0 (also run here) gives differences up to 1.4e-10 (measured;
  // discretisation at degree 6, 16 elements, and shooting at rtol 1e-12); drawing changes neither error
  // source.
  for (const RodDiscretization& d : {RodDiscretization{RodFormulation::Mixed, 6, 16},
                                     RodDiscretization{RodFormulation::Condensed, 6, 16}}) {
    for (double c : {0.0, 3.0}) {
      const Compared r = compare_with_shooting(test::bent_cantilever(c), d);
      BOOST_TEST_MESSAGE(to_string(d.formulation)
                         << " c = " << c << ": position " << r.position << ", rotation " << r.rotation
                         << ", force " << r.force << ", moment " << r.moment);
      BOOST_TEST(r.position < 1e-9);
      BOOST_TEST(r.rotation < 1e-9);
      BOOST_TEST(r.force < 1e-9);
      BOOST_TEST(r.moment < 1e-9);
    }
  }
}

BOOST_AUTO_TEST_CASE(primal_form_matches_shooting_on_a_thick_drawn_rod) {
  // The primal form locks on slender rods (docs/design.md §2): a thick rod (r = 20 mm, L = 0.2 m) whose tip
  // force 1e5 N bends it by some 0.1 rad; c = 60 m/s gives rho A c^2 = 3.6e4 N, a third of the force.
  RodModel m = test::steel_wire(0.02, 0.2);
  m.tip.force = Vec3(6e4, -3e4, -8e4);
  m.tip.moment = Vec3(1e3, 0.0, -500.0);
  m.intrinsic.curvature = Vec3(0.5, 0.0, 0.2);
  for (double c : {0.0, 60.0}) {
    m.drawing_speed = c;
    const Compared r = compare_with_shooting(m, {RodFormulation::Primal, 6, 16});
    BOOST_TEST_MESSAGE("primal c = " << c << ": position " << r.position << ", rotation " << r.rotation
                                     << ", force " << r.force << ", moment " << r.moment);
    // Tolerance 1e-8: the same comparison at c = 0 gives up to 5.1e-10 (measured: the primal form's
    // discretisation error on this mesh, in the force from p'').
    BOOST_TEST(r.position < 1e-8);
    BOOST_TEST(r.rotation < 1e-8);
    BOOST_TEST(r.force < 1e-8);
    BOOST_TEST(r.moment < 1e-8);
  }
}

namespace {

// A rod with every kind of load and end (rod_fixtures.hpp's loaded_rod, constant intrinsic strains;
// without distributed loads its end_loaded_rod), drawn at c: rho A c^2 = 0.2 c^2 = 320 N at c = 40 m/s,
// a tenth of K_SE.
RodModel loaded_drawn_rod(RodEndKind base, RodEndKind tip, bool distributed) {
  RodModel m = distributed ? test::loaded_rod(base, tip) : test::end_loaded_rod(base, tip);
  m.name = "loaded";
  m.drawing_speed = 40.0;
  return m;
}

}  // namespace

BOOST_AUTO_TEST_CASE(every_drawn_block_jacobian_matches_finite_differences) {
  // The blocks with the effective constants (field rows) and the end conditions on the section's n, m,
  // every formulation and end pairing with one clamped end, at a perturbed non-unit-quaternion state.
  const RodEndKind kinds[] = {RodEndKind::Clamped,   RodEndKind::Collar,   RodEndKind::Spherical,
                              RodEndKind::Universal, RodEndKind::Revolute, RodEndKind::Free};
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.05);
  const RodDiscretization discretizations[] = {{RodFormulation::Primal, 3, 3},
                                               {RodFormulation::Mixed, 3, 3, MixedPoints::Midpoints},
                                               {RodFormulation::Mixed, 3, 3, MixedPoints::Greville},
                                               {RodFormulation::Condensed, 3, 3},
                                               {RodFormulation::Condensed, 3, 40},
                                               {RodFormulation::Condensed, 3, 4}};
  for (const RodDiscretization& d : discretizations) {
    const bool distributed = !(d.formulation == RodFormulation::Condensed && d.elements == 4);
    for (RodEndKind other : kinds) {
      for (bool clamped_base : {true, false}) {
        RodModel m = clamped_base ? loaded_drawn_rod(RodEndKind::Clamped, other, distributed)
                                  : loaded_drawn_rod(other, RodEndKind::Clamped, distributed);
        CollocationRod rod(m, d);
        Problem problem;
        rod.add_to_problem(problem, {}, 1.0, /*free_length=*/true);
        VecX x = problem.initial_values();
        for (int i = 0; i < x.size(); ++i) x[i] += noise(rng);
        // Checker defaults 1e-6 abs + 1e-6 rel, as for the static blocks (test_collocation_rod.cpp): central
        // differences with relative step 1e-6 on residuals of O(1)..O(1e3).
        const JacobianCheckResult r = check_problem_jacobian(problem, x);
        BOOST_TEST(r.passed, to_string(d.formulation)
                                 << " (" << to_string(d.mixed_points) << ") base " << to_string(m.base.kind)
                                 << " tip " << to_string(m.tip.kind) << ": " << r.to_string());
        BOOST_TEST(r.entries_checked > 0);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(shooting_state_conversion_and_its_tangents) {
  // RodOde::to_effective / to_section: inverse to each other, and the tangent columns are the
  // derivative of the state map (central differences, step 1e-6: error ~1e-11 relative).
  const RodOde ode(test::bent_cantilever(30.0));
  BOOST_REQUIRE(ode.drawn());
  RodStateWithTangents Y = RodStateWithTangents::Random();
  Y.col(0).segment<4>(RodStateIndex::q) = Quat(0.8, 0.2, -0.4, 0.3);
  const RodStateVector y0 = Y.col(0);
  RodStateWithTangents Z = Y;
  ode.to_effective(Z);
  RodStateVector back = Z.col(0);
  ode.to_section(back);
  BOOST_TEST((back - y0).norm() < 1e-13 * y0.norm());
  for (int j = 1; j <= kRodTangentCount; ++j) {
    const double h = 1e-6;
    RodStateVector plus = y0 + h * Y.col(j), minus = y0 - h * Y.col(j);
    ode.to_effective(plus);
    ode.to_effective(minus);
    const RodStateVector fd = (plus - minus) / (2.0 * h);
    BOOST_TEST((fd - Z.col(j)).norm() < 1e-7 * (1.0 + Z.col(j).norm()), "tangent " << j);
  }
  // And to_section's tangents, from the effective state.
  RodStateWithTangents W = Z;
  ode.to_section(W);
  BOOST_TEST((W - Y).norm() < 1e-12 * Y.norm());
}

BOOST_AUTO_TEST_CASE(drawn_rod_in_a_robot_jacobian) {
  // The robot coupling reads the rod end through RodEndEvaluator (the primal form with the effective
  // constants); every block of the FK problem against central differences at a perturbed initial state
  // (checker defaults, as in test_kinematics).
  // The primal form on a thick rod (d / L = 0.2): on the slender wire its force balance rows (K_SE times
  // p'') are too ill-conditioned for central differences, drawn or not.
  for (const auto& [formulation, radius] : {std::pair("primal", "0.05"), std::pair("mixed", "0.001")}) {
    const auto model = std::make_shared<const RobotModel>(
        parse_robot_model(wire_model("20", formulation, radius), "drawn.urdf"));
    ForwardKinematics fk(model);
    VecX x = fk.state();  // the initial guess: the slender wire locks in the primal form, no solve needed
    for (int i = 0; i < x.size(); ++i) x[i] += 1e-3 * (std::abs(x[i]) + 1e-2) * std::sin(1.0 + i);
    const JacobianCheckResult r = check_problem_jacobian(fk.assembly().problem(), x);
    BOOST_TEST(r.passed, formulation << ": " << r.to_string());
  }
}

BOOST_AUTO_TEST_CASE(zero_drawing_speed_is_bit_identical_to_the_static_rod) {
  // At c = 0 the code path is the static one: tip position, base force and base moment of the bent
  // cantilever (mixed and condensed, degree 4, 8 elements; shooting) and of a thick rod (primal), as the
  // code before drawn rods (commit a9a3e82) computed them, printed in hexadecimal. No tolerance. The
  // condensed row was recorded again when the loaded condensed rows' Jacobian was written out
  // (condensed_jacobian.cpp) instead of taken by Dual numbers: Newton's iterates differ by rounding, and
  // the result moved by at most 1.3e-16 relative (tip and base moment; the base force kept its bits).
  const Vec3 expected[4][3] = {{{0x1.df9bc5200ddb9p-3, -0x1.3100be0b95dc7p-2, 0x1.2dc5abaa62fbep-2},
                                {0x1.999999999999bp-2, -0x1.3333333333334p-2, -0x1.cb25aa34dadddp-1},
                                {0x1.3fa807eac0717p-2, 0x1.f59cc011bdfe9p-3, 0x1.4ef16f7fa1defp-5}},
                               {{0x1.df9bc4ac438e2p-3, -0x1.3100bde261802p-2, 0x1.2dc5ac36e2e45p-2},
                                {0x1.999999999999ap-2, -0x1.3333333333333p-2, -0x1.cb25aa34dadddp-1},
                                {0x1.3fa80703cbba2p-2, 0x1.f59cbd9daca27p-3, 0x1.4ef16f86b9e11p-5}},
                               {{0x1.c56467c1c2f4p-8, -0x1.e4333375857e9p-7, 0x1.97bbf7ae109f2p-3},
                                {0x1.d4be2510f8151p+15, -0x1.d4bc926c1ce5fp+14, -0x1.3883d22c87f7p+16},
                                {0x1.fda9e9e309195p+12, 0x1.8694be11477e4p+13, 0x1.6615fd3499c22p+7}},
                               {{0x1.df9bc4acf4416p-3, -0x1.3100c60919aedp-2, 0x1.2dc5a9dad348ep-2},
                                {0x1.999999999999ap-2, -0x1.3333333333333p-2, -0x1.cb25aa34daddep-1},
                                {0x1.3fa80d9b1f1d3p-2, 0x1.f59cbbfa196e5p-3, 0x1.4ef1899b666e1p-5}}};
  RodModel thick = test::steel_wire(0.02, 0.2);
  thick.name = "thick";
  thick.tip.force = Vec3(6e4, -3e4, -8e4);
  thick.tip.moment = Vec3(1e3, 0.0, -500.0);
  thick.intrinsic.curvature = Vec3(0.5, 0.0, 0.2);
  const RodModel models[3] = {test::bent_cantilever(0.0), test::bent_cantilever(0.0), thick};
  const RodFormulation formulations[3] = {RodFormulation::Mixed, RodFormulation::Condensed,
                                          RodFormulation::Primal};
  for (int k = 0; k < 3; ++k) {
    RodSolveOptions o;
    o.discretization = {formulations[k], 4, 8};
    // The settings of the recorded solves: from the stress-free shape, a fresh Jacobian every iteration.
    o.shooting_start = false;
    o.reuse_factorization = false;
    const RodSolution s = solve_rod(models[k], o);
    const Vec3 got[3] = {s.tip().position, s.base().force, s.base().moment};
    for (int i = 0; i < 3; ++i)
      BOOST_TEST((got[i].array() == expected[k][i].array()).all(), to_string(formulations[k]) << " " << i);
  }
  const ShootingSolution sh = solve_rod_shooting(models[0]);
  const Vec3 got[3] = {sh.tip.p, sh.base.n, sh.base.m};
  for (int i = 0; i < 3; ++i) BOOST_TEST((got[i].array() == expected[3][i].array()).all(), "shooting " << i);
}
