// Universal (Hooke) and revolute (pin) rod ends of a single collocation rod: the zero sets of their
// orientation rows, every residual block's Jacobian against finite differences in every formulation,
// closed-form beams (propped cantilever, torsion shared by two supports, clamped-clamped beam), and
// the model checks (axes, twist rule, rigid motions).
#define BOOST_TEST_MODULE joint_ends
#include <boost/test/unit_test.hpp>

#include <random>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/rods/collocation/end_equations.hpp"
#include "pcr/rods/collocation_rod.hpp"
#include "pcr/rods/end_axes.hpp"
#include "pcr/rods/rod_solve.hpp"
#include "pcr/solve/jacobian_check.hpp"
#include "rod_fixtures.hpp"

using namespace pcr;

namespace {

Quat quat_of(const Mat3& R) {
  return quat_from_rotation_vector(so3_log(R));
}

// The 7 end rows at a rod frame R (q of R), with p at the target and zero wrench.
std::array<double, 7> end_rows(RodEndKind kind, const Mat3& R_T, const Vec3& axis, const Mat3& R) {
  collocation::EndTarget<double> t;
  t.position = Vec3(0.1, 0.2, 0.3);
  t.frame = R_T;
  t.orientation = quat_of(R_T);
  t.axes = joint_axes(axis);
  std::array<double, 7> r;
  collocation::end_conditions<double>(kind, t, {}, collocation::PointConstants{}, t.position, quat_of(R),
                                      Vec3::Zero(), Vec3::Zero(), r.data());
  return r;
}

// A loaded rod between two held ends: rod_fixtures.hpp's loaded_rod with joint axes, the base off the
// origin, no intrinsic shear-extension and, without distributed loads, no mass.
RodModel joint_rod(RodEndKind base, RodEndKind tip, bool distributed_loads) {
  RodModel m = distributed_loads ? test::loaded_rod(base, tip) : test::end_loaded_rod(base, tip);
  if (!distributed_loads) m.mass_per_length = 0.0;
  m.intrinsic.shear_extension.setZero();
  m.base.position = Vec3(0.05, -0.1, 0.2);
  m.base.axis = Vec3(0.6, 0.7, 0.2);
  m.tip.axis = Vec3(-0.3, 0.9, -0.4);
  return m;
}

// Straight rod of length L along +x from the origin (frames turned by Ry(pi/2): d3 = x, d2 = y), clamped
// at the base, held at the tip (L, 0, 0) by `tip` with axis `axis` (end frame); EI = 1 N m^2, GJ = 0.8,
// EA = 1e6 N, GA = 4e5 N.
RodModel beam(RodEndKind tip, const Vec3& axis) {
  RodModel m = test::cantilever(0.5, Vec3(4e5, 4e5, 1e6), Vec3(1.0, 1.0, 0.8));
  m.base.orientation = m.tip.orientation = quat_from_rotation_vector(Vec3(0, M_PI / 2, 0));
  m.tip.kind = tip;
  m.tip.position = Vec3(0.5, 0, 0);
  m.tip.axis = axis;
  return m;
}

RodSolution solve_beam(const RodModel& m, RodFormulation formulation) {
  RodSolveOptions o;
  o.discretization = {formulation, 6, 8};
  o.tolerance = 1e-12;
  const RodSolution s = solve_rod(m, o);
  BOOST_REQUIRE_MESSAGE(s.summary.converged(), s.summary.brief_report());
  return s;
}

// Linear-beam references hold to ~1e-5 here: shear flexibility EI / (GA L^2) = 1e-5 (times factors
// <= 3 in the reactions), geometric nonlinearity ~ rotations^2 <= 1e-8, membrane tension of the held
// ends ~ EA (deflection / L)^2 L^2 / EI <= 1e-5; the discretisation (degree 6) reproduces the
// polynomial beam solutions. Tolerance 1e-4 relative.
constexpr double kBeam = 1e-4;

bool close(double actual, double expected) {
  return std::abs(actual - expected) <= kBeam * std::abs(expected);
}

}  // namespace

BOOST_AUTO_TEST_CASE(orientation_rows_vanish_exactly_on_the_joint_configurations) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Mat3 R_T = so3_exp(Vec3(g(rng), g(rng), g(rng)));
    const Vec3 a = Vec3(g(rng), g(rng), g(rng));
    const Mat3 axes = joint_axes(a);
    const double t1 = 3 * g(rng), t2 = 3 * g(rng);
    // Universal: R = R_T R_a(t1) R_b(t2) (a fixed in the end frame, b in the rod's): row 3 is zero (to
    // round-off of O(1) products, 1e-14), and so are the position rows; any other turn breaks it.
    const Mat3 hooke = R_T * so3_exp(t1 * axes.col(0)) * so3_exp(t2 * axes.col(1));
    std::array<double, 7> r = end_rows(RodEndKind::Universal, R_T, a, hooke);
    BOOST_TEST(std::abs(r[3]) < 1e-14);
    const Mat3 twisted = hooke * so3_exp(0.3 * axes.col(2));  // about the normal a x b: not a Hooke turn
    r = end_rows(RodEndKind::Universal, R_T, a, twisted);
    BOOST_TEST(std::abs(r[3]) > 1e-3);
    // Revolute: R = R_T R_a(t1), and the flipped branch R_T R_a(t1) R_c1(pi) (R a = -R_T a).
    for (const Mat3& R : {Mat3(R_T * so3_exp(t1 * axes.col(0))),
                          Mat3(R_T * so3_exp(t1 * axes.col(0)) * so3_exp(M_PI * axes.col(1)))}) {
      r = end_rows(RodEndKind::Revolute, R_T, a, R);
      BOOST_TEST(std::abs(r[3]) < 1e-14);
      BOOST_TEST(std::abs(r[4]) < 1e-14);
    }
    r = end_rows(RodEndKind::Revolute, R_T, a, hooke);  // a second axis turned: not a pin turn
    BOOST_TEST(std::abs(r[3]) + std::abs(r[4]) > 1e-3 * std::abs(std::sin(t2)));
  }
}

BOOST_AUTO_TEST_CASE(every_joint_end_block_jacobian_matches_finite_differences) {
  // Every pairing with a universal or revolute end that holds the rod, every formulation (the condensed
  // one with distributed loads on 3 and 40 elements: summed and running integrals; and without),
  // free length, at a randomly perturbed, non-unit-quaternion state.
  const std::pair<RodEndKind, RodEndKind> pairs[] = {
      {RodEndKind::Clamped, RodEndKind::Universal},   {RodEndKind::Clamped, RodEndKind::Revolute},
      {RodEndKind::Universal, RodEndKind::Clamped},   {RodEndKind::Revolute, RodEndKind::Clamped},
      {RodEndKind::Universal, RodEndKind::Spherical}, {RodEndKind::Spherical, RodEndKind::Revolute},
      {RodEndKind::Universal, RodEndKind::Revolute},  {RodEndKind::Revolute, RodEndKind::Universal},
      {RodEndKind::Universal, RodEndKind::Universal}, {RodEndKind::Revolute, RodEndKind::Revolute},
      {RodEndKind::Collar, RodEndKind::Universal}};
  const RodDiscretization discretizations[] = {{RodFormulation::Primal, 3, 3},
                                               {RodFormulation::Mixed, 3, 3, MixedPoints::Midpoints},
                                               {RodFormulation::Mixed, 3, 3, MixedPoints::Greville},
                                               {RodFormulation::Condensed, 3, 3},
                                               {RodFormulation::Condensed, 3, 40},
                                               {RodFormulation::Condensed, 3, 4}};
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (const RodDiscretization& d : discretizations) {
    const bool loads = !(d.formulation == RodFormulation::Condensed && d.elements == 4);
    for (const auto& [base, tip] : pairs) {
      const RodModel m = joint_rod(base, tip, loads);
      CollocationRod rod(m, d);
      Problem problem;
      rod.add_to_problem(problem, {}, 1.0, /*free_length=*/true);
      VecX x = problem.initial_values();
      for (int i = 0; i < x.size(); ++i) x[i] += noise(rng);
      // Default checker tolerances 1e-6 abs + 1e-6 rel: central differences with relative step 1e-6
      // have truncation ~1e-12 and round-off ~1e-10 on these O(1)..O(1e3) residuals.
      const JacobianCheckResult r = check_problem_jacobian(problem, x);
      BOOST_TEST(r.passed, to_string(d.formulation) << " " << d.elements << " base " << to_string(base)
                                                    << " tip " << to_string(tip) << ": " << r.to_string());
      int joint_blocks = 0;
      for (ResidualId b = 0; b < problem.num_residual_blocks(); ++b)
        joint_blocks += problem.residual(b).kind() == "rod.end_universal" ||
                        problem.residual(b).kind() == "rod.end_revolute";
      BOOST_TEST(joint_blocks == (base == RodEndKind::Universal || base == RodEndKind::Revolute) +
                                     (tip == RodEndKind::Universal || tip == RodEndKind::Revolute));
    }
  }
}

BOOST_AUTO_TEST_CASE(pinned_tip_gives_the_propped_cantilever) {
  // Uniform load w along -z, pin axis y at the tip: the propped cantilever of Euler-Bernoulli theory,
  // tip reaction 3 w L / 8, base reaction 5 w L / 8, base moment w L^2 / 8 (about +y for the moment
  // m(0) the rod exerts on the clamp), tip slope w L^3 / (48 EI) upwards, no moment about the pin. A
  // universal tip with first axis y frees the same rotation. w L^3 / EI = 1e-3.
  const double L = 0.5, EI = 1.0, w = 1e-3 * EI / (L * L * L);
  for (RodEndKind kind : {RodEndKind::Revolute, RodEndKind::Universal}) {
    for (RodFormulation f : {RodFormulation::Mixed, RodFormulation::Condensed}) {
      RodModel m = beam(kind, Vec3::UnitY());
      m.loads.force_per_length = Vec3(0, 0, -w);
      const RodSolution s = solve_beam(m, f);
      const RodState base = s.base(), tip = s.tip();
      const std::string label = std::string(to_string(kind)) + " " + to_string(f);
      BOOST_TEST(close(tip.force.z(), 3 * w * L / 8), label << ": tip reaction " << tip.force.z());
      BOOST_TEST(close(base.force.z(), -5 * w * L / 8), label << ": base reaction " << base.force.z());
      BOOST_TEST(close(base.moment.y(), w * L * L / 8), label << ": base moment " << base.moment.y());
      const Vec3 d3 = tip.rotation.col(2);
      BOOST_TEST(close(std::atan2(d3.z(), d3.x()), w * L * L * L / (48 * EI)), label << ": tip slope");
      // The pin row itself: zero moment about y at the tip (solver tolerance 1e-12 x moment scale 2 N m).
      BOOST_TEST(std::abs(tip.moment.y()) < 1e-11, label);
    }
  }
}

BOOST_AUTO_TEST_CASE(rod_pinned_at_both_ends_is_the_simply_supported_beam) {
  // Pins about y at both ends (or universal joints with first axis y: their second axis is world z, free
  // too), uniform load w along -z: the simply supported beam. Reactions w L / 2 at each end (statics);
  // end section rotations -+ w L^3 / (24 EI) (the section rotation of a Timoshenko beam, which shear
  // does not change for this statically determinate beam); midpoint deflection 5 w L^4 / (384 EI) +
  // w L^2 / (8 GA) (bending + shear: the shear term is 1e-4 of the total here, so it is included);
  // no moment about the pins. Tolerance kBeam (1e-4 relative; the membrane tension of the two held
  // ends is ~EA (deflection / L)^2 ~ 4e-4 N, a relative change N L^2 / (pi^2 EI) ~ 1e-5).
  const double L = 0.5, EI = 1.0, GA = 4e5, w = 1e-3 * EI / (L * L * L);
  for (RodEndKind kind : {RodEndKind::Revolute, RodEndKind::Universal}) {
    RodModel m = beam(kind, Vec3::UnitY());
    m.base.kind = kind;
    m.base.axis = Vec3::UnitY();
    m.loads.force_per_length = Vec3(0, 0, -w);
    const RodSolution s = solve_beam(m, RodFormulation::Condensed);
    const RodState base = s.base(), tip = s.tip(), mid = s.at(L / 2);
    const std::string label = to_string(kind);
    BOOST_TEST(close(tip.force.z(), w * L / 2), label << ": tip reaction " << tip.force.z());
    BOOST_TEST(close(base.force.z(), -w * L / 2), label << ": base reaction " << base.force.z());
    const Vec3 d3_base = base.rotation.col(2), d3_tip = tip.rotation.col(2);
    BOOST_TEST(close(std::atan2(d3_base.z(), d3_base.x()), -w * L * L * L / (24 * EI)),
               label << ": base slope");
    BOOST_TEST(close(std::atan2(d3_tip.z(), d3_tip.x()), w * L * L * L / (24 * EI)), label << ": tip slope");
    const double deflection = 5 * w * std::pow(L, 4) / (384 * EI) + w * L * L / (8 * GA);
    BOOST_TEST_MESSAGE(label << " pinned-pinned midpoint deflection relative error "
                             << (-mid.position.z() - deflection) / deflection);
    BOOST_TEST(close(mid.position.z(), -deflection),
               label << ": midpoint " << mid.position.z() << " vs " << -deflection);
    // The pin rows: zero moment about y (solver tolerance 1e-12 x moment scale 2 N m).
    BOOST_TEST(std::abs(base.moment.y()) < 1e-11, label);
    BOOST_TEST(std::abs(tip.moment.y()) < 1e-11, label);
  }
}

BOOST_AUTO_TEST_CASE(universal_and_revolute_ends_hold_torsion_and_differ_in_the_second_bending_plane) {
  // A distributed torque l about the rod axis (x): with the twist held at both ends (universal or pin
  // normal to the rod), GJ phi'' = -l with phi(0) = phi(L) = 0: each support takes l L / 2, so the tip
  // moment m(L) . x = -l L / 2; a spherical tip takes none (all l L at the clamp).
  // A uniform load w along -y (bending about z): the universal's second axis b = e3 x a is world z
  // (free: propped cantilever, tip reaction 3 w L / 8); the pin about y holds it (clamped-clamped
  // beam: w L / 2 at each end, end moments w L^2 / 12).
  const double L = 0.5, GJ = 0.8, EI = 1.0, l = 8e-4 * GJ / (L * L), w = 1e-3 * EI / (L * L * L);
  for (RodEndKind kind : {RodEndKind::Universal, RodEndKind::Revolute, RodEndKind::Spherical}) {
    RodModel m = beam(kind, Vec3::UnitY());
    m.loads.moment_per_length = Vec3(l, 0, 0);
    m.loads.force_per_length = Vec3(0, -w, 0);
    const RodSolution s = solve_beam(m, RodFormulation::Condensed);
    const RodState tip = s.tip();
    const std::string label = to_string(kind);
    if (kind == RodEndKind::Spherical) {
      BOOST_TEST(std::abs(tip.moment.x()) < 1e-11, label);
      BOOST_TEST(close(s.base().moment.x(), l * L), label);
      continue;
    }
    BOOST_TEST(close(tip.moment.x(), -l * L / 2), label << ": tip torque " << tip.moment.x());
    if (kind == RodEndKind::Universal) {
      BOOST_TEST(close(tip.force.y(), 3 * w * L / 8), label << ": tip reaction " << tip.force.y());
      BOOST_TEST(std::abs(tip.moment.z()) < 1e-11, label);
    } else {
      BOOST_TEST(close(tip.force.y(), w * L / 2), label << ": tip reaction " << tip.force.y());
      BOOST_TEST(close(std::abs(tip.moment.z()), w * L * L / 12), label << ": tip moment " << tip.moment.z());
    }
  }
}

namespace {
void check_rejected(const RodModel& m, const std::vector<std::string>& parts) {
  try {
    m.validate();
    BOOST_ERROR("accepted: " << parts.front());
  } catch (const InputError& e) {
    for (const std::string& part : parts)
      BOOST_TEST(std::string(e.what()).find(part) != std::string::npos,
                 "'" << part << "' not in: " << e.what());
  }
}
}  // namespace

BOOST_AUTO_TEST_CASE(ill_posed_joint_ends_are_rejected_with_the_rod_and_value) {
  RodModel m = beam(RodEndKind::Universal, Vec3(0, 0, 2));  // along the tangent
  check_rejected(m, {"rod 'cantilever'", "tip universal axis", "0 0 2", "along"});
  m = beam(RodEndKind::Revolute, Vec3::Zero());
  check_rejected(m, {"rod 'cantilever'", "tip revolute axis", "0 0 0", "non-zero"});
  m = beam(RodEndKind::Revolute, Vec3(NAN, 0, 1));
  check_rejected(m, {"rod 'cantilever'", "tip revolute axis", "nan"});
  // Twist: collars and spherical joints, or a pin along the tangent (a swivel), leave it free.
  m = beam(RodEndKind::Revolute, Vec3::UnitZ());
  m.base.kind = RodEndKind::Spherical;
  check_rejected(m, {"rod 'cantilever'", "base spherical, tip revolute", "twist", "clamp at least one end"});
  m = beam(RodEndKind::Collar, Vec3::UnitX());
  m.base.kind = RodEndKind::Collar;
  check_rejected(m, {"rod 'cantilever'", "base collar, tip collar", "twist"});
  // Rigid motion: a universal or revolute end with the other end free is a pendulum.
  for (RodEndKind kind : {RodEndKind::Universal, RodEndKind::Revolute}) {
    m = beam(RodEndKind::Free, Vec3::UnitX());
    m.base.kind = kind;
    check_rejected(m,
                   {"rod 'cantilever'", std::string("base ") + to_string(kind) + ", tip free", "rigid body"});
  }
  // Held: the same ends with the other end attached.
  m = beam(RodEndKind::Universal, Vec3::UnitX());
  m.base.kind = RodEndKind::Spherical;
  BOOST_CHECK_NO_THROW(m.validate());
  m = beam(RodEndKind::Revolute, Vec3::UnitY());
  m.base.kind = RodEndKind::Revolute;
  m.base.axis = Vec3::UnitY();
  BOOST_CHECK_NO_THROW(m.validate());
}
