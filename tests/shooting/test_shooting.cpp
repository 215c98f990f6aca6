// Shooting reference for single rods: analytic solutions (R1 arc, R3 helix), the Bisshopp-Drucker
// elastica (R2, table and elliptic integrals), every end pairing, closed forms for joint ends (propped
// cantilever, simply supported beam, universal-spherical rod in tension and in torsion), global
// equilibrium, tangents against finite differences, RK4 order, bad input, non-convergence and
// integration failure.
#define BOOST_TEST_MODULE shooting
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/rods/shooting/joint_ends.hpp"
#include "pcr/rods/shooting/rod_integrator.hpp"
#include "pcr/rods/shooting/rod_shooting.hpp"
// The solver's private end conditions, to check their Jacobians against finite differences.
#include "../../rods/src/shooting/shooting_ends.hpp"

using namespace pcr;

namespace {

// Clamped at the origin with R(0) = I (tangent e3), free tip; stiffnesses given directly.
RodModel cantilever(double length, const Vec3& bending_torsion, const Vec3& shear_extension) {
  RodModel rod;
  rod.name = "test";
  rod.length = length;
  rod.bending_torsion_stiffness = bending_torsion;
  rod.shear_extension_stiffness = shear_extension;
  rod.base.kind = RodEndKind::Clamped;
  rod.tip.kind = RodEndKind::Free;
  return rod;
}

// Tight settings for reference solutions: local error 1e-12 per step, residual 1e-12 (scaled).
ShootingOptions tight_options() {
  ShootingOptions o;
  o.integration_relative_tolerance = 1e-12;
  o.integration_absolute_tolerance = 1e-14;
  o.tolerance = 1e-12;
  return o;
}

double max_abs(const Vec3& v) {
  return v.cwiseAbs().maxCoeff();
}

bool all_finite(const ShootingState& x) {
  return x.p.allFinite() && x.q.allFinite() && x.n.allFinite() && x.m.allFinite();
}

// The global error of Dormand-Prince at integration_relative_tolerance = 1e-12 over the few hundred steps of
// these rods is bounded by (steps) x 1e-12 < 1e-9 relative to the rod length (measured: ~1e-13).
constexpr double kTightIntegration = 1e-9;

// ---- R2: Bisshopp & Drucker elastica by elliptic integrals (independent of the solver) -----------
// Tip angle phi0 from sqrt(alpha) = K(k) - F(psi1, k), k = sin(pi/4 + phi0/2), sin psi1 = 1/(sqrt2 k);
// then x/L = sqrt(2 sin(phi0) / alpha) (along the undeformed axis), y/L = 1 - 2 (E(k) - E(psi1, k)) /
// sqrt(alpha) (Bisshopp & Drucker 1945, Q. Appl. Math. 3(3), eqs. for the cantilever with a tip force).
struct Elastica {
  double x, y, angle;
};
Elastica elastica(double alpha) {
  auto parts = [](double phi0, double& k, double& psi1) {
    k = std::sin(M_PI / 4 + phi0 / 2);
    psi1 = std::asin(std::min(1.0, 1.0 / (std::sqrt(2.0) * k)));
  };
  auto g = [&](double phi0) {
    double k, psi1;
    parts(phi0, k, psi1);
    return boost::math::ellint_1(k) - boost::math::ellint_1(k, psi1) - std::sqrt(alpha);
  };
  double lo = 1e-9, hi = M_PI / 2 - 1e-12;  // g(lo) < 0 < g(hi): bisection to machine precision
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) < 0 ? lo : hi) = mid;
  }
  const double phi0 = 0.5 * (lo + hi);
  double k, psi1;
  parts(phi0, k, psi1);
  Elastica e;
  e.angle = phi0;
  e.x = std::sqrt(2.0 * std::sin(phi0) / alpha);
  e.y = 1.0 - 2.0 * (boost::math::ellint_2(k) - boost::math::ellint_2(k, psi1)) / std::sqrt(alpha);
  return e;
}

// R2 cantilever: axis e3 (the table's x), force P along e1 (the table's y), EI = 1, L = 1, and
// EA = GA = 1e8 EI / L^2: the inextensible, unshearable limit up to strains P / EA <= 1.5e-7.
constexpr double kR2AxialStiffness = 1e8;
RodModel bisshopp_drucker(double alpha) {
  RodModel rod = cantilever(1.0, Vec3(1, 1, 1), Vec3::Constant(kR2AxialStiffness));
  rod.tip.force = Vec3(alpha, 0, 0);
  return rod;
}

// Rodrigues: exp(t hat(kappa)) e3 integrated from 0 to s in closed form (R3 helix), with
// k = |kappa|, a = kappa / k: int_0^s exp(t hat(kappa)) dt = s I + (1 - cos ks)/k hat(a) +
// (s - sin(ks)/k) hat(a)^2.
Vec3 helix_point(const Vec3& kappa, double s) {
  const double k = kappa.norm();
  const Mat3 A = hat(kappa / k);
  return (s * Mat3::Identity() + (1.0 - std::cos(k * s)) / k * A + (s - std::sin(k * s) / k) * A * A) *
         Vec3::UnitZ();
}

}  // namespace

// ---- R1: end moment rolls the cantilever into an exact arc (any EA, GA) ----------------------------
BOOST_AUTO_TEST_CASE(r1_end_moment_gives_exact_arc) {
  // Simo & Vu-Quoc 1986: EI = 2, L = 1, M = phi EI / L; finite EA = 100, GA = 50 (n = 0, so exact).
  for (double phi : {M_PI / 2, 2 * M_PI, 4 * M_PI}) {
    RodModel rod = cantilever(1.0, Vec3(2, 2, 2), Vec3(50, 50, 100));
    rod.tip.moment = Vec3(phi * 2.0, 0, 0);
    for (auto method : {IntegratorMethod::DormandPrince, IntegratorMethod::RK4}) {
      ShootingOptions o = tight_options();
      o.integrator = method;
      o.rk4_steps = 2000;
      const ShootingSolution sol = solve_rod_shooting(rod, o);
      BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
      // RK4, N = 2000: global error ~ L (phi h)^4 / 120 with phi h <= 4 pi / 2000, i.e. < 1e-11; the
      // same 1e-9 bound as for Dormand-Prince holds with margin.
      const double k = phi;  // curvature phi / L about d1: the arc turns d3 towards -e2
      for (int i = 0; i <= 20; ++i) {
        const double s = i / 20.0;
        const ShootingState x = sol.at(s);
        const Vec3 exact(0.0, -(1.0 - std::cos(k * s)) / k, std::sin(k * s) / k);
        BOOST_TEST(max_abs(x.p - exact) < kTightIntegration, "phi " << phi << " s " << s);
        BOOST_TEST(rotation_angle_between(x.R(), rotation_x(k * s)) < kTightIntegration);
        // n = 0 and m = M along the whole rod (exact; roundoff of |M| ~ 25 times 1e-15 per step).
        BOOST_TEST(max_abs(x.n) < 1e-12);
        BOOST_TEST(max_abs(x.m - rod.tip.moment) < 1e-12 * phi * 2.0 * 1e3);
      }
      // Tip: L sin(phi)/phi along the initial tangent, L (1 - cos(phi))/phi across it.
      BOOST_TEST(std::abs(sol.tip.p.z() - std::sin(phi) / phi) < kTightIntegration);
      BOOST_TEST(std::abs(sol.tip.p.y() + (1.0 - std::cos(phi)) / phi) < kTightIntegration);
    }
  }
}

// ---- a precurved rod without loads keeps its stress-free arc ----------------------------------------------
BOOST_AUTO_TEST_CASE(precurved_rod_without_loads_is_its_intrinsic_arc) {
  // kappa0 = (2, 0, 0) (constant, and the same through the s-dependent hook): n = m = 0 and the rod is
  // the arc p(s) = (0, -(1 - cos 2s)/2, sin(2s)/2), R(s) = R_x(2s), for any stiffness.
  for (bool varying : {false, true}) {
    RodModel rod = cantilever(1.0, Vec3(1.0, 1.5, 0.7), Vec3(40, 50, 90));
    if (varying)
      rod.intrinsic.varying = [](double, Vec3&, Vec3& kappa0) { kappa0 = Vec3(2.0, 0.0, 0.0); };
    else
      rod.intrinsic.curvature = Vec3(2.0, 0.0, 0.0);
    const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
    BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
    for (int i = 0; i <= 10; ++i) {
      const double s = i / 10.0;
      const ShootingState x = sol.at(s);
      const Vec3 exact(0.0, -(1.0 - std::cos(2 * s)) / 2, std::sin(2 * s) / 2);
      BOOST_TEST(max_abs(x.p - exact) < kTightIntegration, "varying " << varying << " s " << s);
      BOOST_TEST(rotation_angle_between(x.R(), rotation_x(2 * s)) < kTightIntegration);
      // Residual tolerance 1e-12 times F_c = M_c = 1.5 (bending scales).
      BOOST_TEST(max_abs(x.n) < 1e-11);
      BOOST_TEST(max_abs(x.m) < 1e-11);
    }
  }
}

// ---- R2: Bisshopp-Drucker table --------------------------------------------------------------------
BOOST_AUTO_TEST_CASE(r2_bisshopp_drucker_table) {
  // alpha, (L - x_tip)/L, y_tip/L, tip angle (Bisshopp & Drucker 1945; docs/benchmarks.md, Scenes R2).
  const double table[14][4] = {
      {0.2, 0.00265, 0.06636, 0.0996}, {0.4, 0.01035, 0.13098, 0.1972}, {0.6, 0.02249, 0.19235, 0.2907},
      {0.8, 0.03817, 0.24945, 0.3791}, {1, 0.05643, 0.30172, 0.4614},   {1.5, 0.10794, 0.41098, 0.6395},
      {2, 0.16064, 0.49346, 0.7818},   {3, 0.25442, 0.60325, 0.9860},   {4, 0.32894, 0.66996, 1.1212},
      {5, 0.38763, 0.71379, 1.2154},   {6, 0.43459, 0.74457, 1.2837},   {8, 0.50483, 0.78498, 1.3744},
      {10, 0.55500, 0.81061, 1.4303},  {15, 0.63529, 0.84772, 1.5018}};
  for (const auto& row : table) {
    const double alpha = row[0];
    const ShootingSolution sol = solve_rod_shooting(bisshopp_drucker(alpha), tight_options());
    BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
    const Vec3 d3 = sol.tip.R().col(2);
    const double dx = 1.0 - sol.tip.p.z(), y = sol.tip.p.x(), angle = std::atan2(d3.x(), d3.z());
    // Extensibility: strains |n| / EA, |n| / GA <= alpha / 1e8 move the tip by at most 2 alpha 1e-8 L.
    const double extensibility = 2.0 * alpha / kR2AxialStiffness;
    // Table: half a unit of the last published digit (5 decimals for x, y; 4 for the angle), plus a
    // 2e-7 allowance for double rounding: at alpha = 2 the exact angle 0.78174983 (elliptic integrals,
    // below) is published as 0.7818, i.e. rounded 0.781750 -> 0.78175 -> 0.7818.
    const double double_rounding = 2e-7;
    BOOST_TEST(std::abs(dx - row[1]) < 0.5e-5 + extensibility + double_rounding, "alpha " << alpha);
    BOOST_TEST(std::abs(y - row[2]) < 0.5e-5 + extensibility + double_rounding, "alpha " << alpha);
    BOOST_TEST(std::abs(angle - row[3]) < 0.5e-4 + extensibility + double_rounding, "alpha " << alpha);
    // Against the elliptic-integral solution: only extensibility and integration error remain.
    const Elastica e = elastica(alpha);
    BOOST_TEST(std::abs(dx - (1.0 - e.x)) < extensibility + kTightIntegration, "alpha " << alpha);
    BOOST_TEST(std::abs(y - e.y) < extensibility + kTightIntegration, "alpha " << alpha);
    BOOST_TEST(std::abs(angle - e.angle) < extensibility + kTightIntegration, "alpha " << alpha);
  }
}

// ---- R3: exact helix ---------------------------------------------------------------------------------
BOOST_AUTO_TEST_CASE(r3_end_moment_gives_exact_helix) {
  const double k_b = 0.086332350, k_t = 0.034350551, L = 135.245580489;
  RodModel rod;
  rod.name = "helix";
  rod.length = L;
  Material material{1.0, 0.5, 0.0};  // E = 1, G = 0.5: GJ = G 2I = EI
  rod.set_material_and_section(material, CrossSection::circle(1.0));
  rod.base.kind = RodEndKind::Clamped;
  rod.tip.kind = RodEndKind::Free;
  const double EI = rod.bending_torsion_stiffness[0];
  const Vec3 kappa(k_b, 0.0, k_t);
  // At s = L: m = R(L) K_BT kappa = EI R(L) kappa = EI kappa, since kappa is the axis of R(L).
  rod.tip.moment = EI * kappa;
  for (auto method : {IntegratorMethod::DormandPrince, IntegratorMethod::RK4}) {
    ShootingOptions o = tight_options();
    o.integrator = method;
    o.rk4_steps = 4000;
    const ShootingSolution sol = solve_rod_shooting(rod, o);
    BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
    double worst_p = 0.0, worst_R = 0.0;
    for (int i = 0; i <= 100; ++i) {
      const double s = L * i / 100.0;
      const ShootingState x = sol.at(s);
      worst_p = std::max(worst_p, max_abs(x.p - helix_point(kappa, s)));
      worst_R = std::max(worst_R, rotation_angle_between(x.R(), so3_exp(s * kappa)));
    }
    // Relative to the length (135): the 1e-9 integration bound times L for positions; angles are
    // relative to the total turning k L ~ 12.6 rad, so 1e-9 times that.
    BOOST_TEST(worst_p < kTightIntegration * L, to_string(method) << " position error " << worst_p);
    BOOST_TEST(worst_R < kTightIntegration * kappa.norm() * L, to_string(method)
                                                                   << " angle error " << worst_R);
    // Radius 10, pitch 25, two coils: the tip is 50 above the base on the helix axis direction.
    const Vec3 axis = kappa.normalized();
    BOOST_TEST(std::abs(sol.tip.p.dot(axis) - 50.0) < 1e-6);  // the published values carry 9 digits
  }
}

// ---- every end pairing reproduces one equilibrium ------------------------------------------------------
// Reference: clamped base, free tip with a distributed load and tip loads. Every other pairing that
// RodModel::validate accepts is set up with the reference's own boundary values (tip pose, base
// reaction) as its prescribed data, so all must converge to the same state, and each must satisfy its
// own boundary equations. Joint ends: the end frame is the reference frame turned back by joint angles
// the solver must find, and the applied moment leaves the transmitted part of the reference moment to
// the joint (universal: along t = (R_T a) x (R b); revolute: normal to the pin).
namespace {

const RodEndKind kAllKinds[] = {RodEndKind::Clamped,   RodEndKind::Collar,   RodEndKind::Spherical,
                                RodEndKind::Universal, RodEndKind::Revolute, RodEndKind::Free};

bool accepted(RodModel rod, RodEndKind base, RodEndKind tip) {
  rod.base.kind = base;
  rod.tip.kind = tip;
  try {
    rod.validate();
  } catch (const InputError&) {
    return false;
  }
  return true;
}

// Axes of the joint ends in these tests (in the end frame, not along e3).
const Vec3 kUniversalAxis = Vec3(1.0, 0.3, 0.2).normalized();
const Vec3 kRevoluteAxis = Vec3(0.2, 1.0, 0.3).normalized();

Mat3 about(const Vec3& axis, double angle) {
  return so3_exp(angle * axis);
}

// A joint end whose rod frame is R with the internal moment m (m(L) at a tip, -m(0) at a base, i.e. the
// moment on the rod from outside): the end frame R_T = R (R_a(theta1) R_b(theta2))^T, and the applied
// moment that leaves the transmitted part of m to the joint.
void set_joint_end(RodEnd& end, const Mat3& R, const Vec3& m_outside, double theta1, double theta2) {
  const bool universal = end.kind == RodEndKind::Universal;
  end.axis = universal ? kUniversalAxis : kRevoluteAxis;
  const Vec3 a = end.axis, b = Vec3::UnitZ().cross(a).normalized();
  const Mat3 R_rel = universal ? Mat3(about(a, theta1) * about(b, theta2)) : about(a, theta1);
  const Mat3 R_T = R * R_rel.transpose();
  end.orientation = quat_from_rotation(R_T);
  const Vec3 a_world = R_T * a;
  if (universal) {
    const Vec3 t = a_world.cross(R * b);
    end.moment = m_outside - m_outside.dot(t) * t;
  } else {
    end.moment = m_outside.dot(a_world) * a_world;
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(every_pairing_converges_to_the_same_equilibrium) {
  RodModel ref_model = cantilever(1.0, Vec3(1.0, 1.5, 0.8), Vec3(50, 50, 100));
  ref_model.loads.force_per_length = Vec3(0.5, -1.0, 0.2);
  ref_model.tip.force = Vec3(0.3, 0.2, -0.1);
  ref_model.tip.moment = Vec3(0.1, -0.2, 0.05);
  ref_model.base.orientation = quat_from_rotation(rotation_from_rpy(0.1, 0.2, -0.3));
  ref_model.base.position = Vec3(0.1, -0.2, 0.3);
  const ShootingSolution ref = solve_rod_shooting(ref_model, tight_options());
  BOOST_TEST_REQUIRE(ref.summary.converged(), ref.summary.brief_report());
  // Its own boundary equations (the applied tip loads to the residual tolerance 1e-12 x F_c, M_c = 1).
  BOOST_TEST(max_abs(ref.tip.n - ref_model.tip.force) < 1e-11);
  BOOST_TEST(max_abs(ref.tip.m - ref_model.tip.moment) < 1e-11);

  const Vec3 d3_tip = ref.tip.R().col(2);
  int pairings = 0;
  for (RodEndKind base_kind : kAllKinds) {
    for (RodEndKind tip_kind : kAllKinds) {
      if (!accepted(ref_model, base_kind, tip_kind)) continue;
      ++pairings;
      RodModel rod = ref_model;
      rod.base.kind = base_kind;
      rod.tip.kind = tip_kind;
      // Prescribed tip: the reference tip pose; the tip loads stay (used by spherical, collar torsion).
      rod.tip.position = ref.tip.p;
      rod.tip.orientation = ref.tip.q;
      // Loads at the base: the reference's n(0) = -force, m(0) = -moment.
      rod.base.force = -ref.base.n;
      rod.base.moment = -ref.base.m;
      // A non-clamped base starts from a different guess than the answer: perturb the prescribed
      // orientation of a collar by a twist (the collar only fixes the axis); joint ends are turned back
      // by joint angles.
      if (base_kind == RodEndKind::Collar)
        rod.base.orientation =
            quat_multiply(rod.base.orientation, quat_from_rotation_vector(Vec3(0, 0, 0.3)));
      if (joint_end::is_joint(base_kind)) set_joint_end(rod.base, ref.base.R(), -ref.base.m, 0.3, -0.2);
      if (joint_end::is_joint(tip_kind)) set_joint_end(rod.tip, ref.tip.R(), ref.tip.m, -0.25, 0.15);
      const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
      const std::string name = std::string(to_string(base_kind)) + "-" + to_string(tip_kind);
      BOOST_TEST_REQUIRE(sol.summary.converged(), name << ": " << sol.summary.brief_report());
      // Boundary equations, checked on the returned states (tolerance: residual 1e-12 scaled by
      // L = 1, F_c = M_c = 1.5, plus the integration bound).
      const double tol = kTightIntegration;
      const ShootingState& b = sol.base;
      const ShootingState& t = sol.tip;
      const Mat3 R_base = rotation_matrix(rod.base.orientation), R_tip = rotation_matrix(rod.tip.orientation);
      const Vec3 b_u = Vec3::UnitZ().cross(kUniversalAxis).normalized();
      switch (base_kind) {
        case RodEndKind::Clamped:
          BOOST_TEST(max_abs(b.p - rod.base.position) < tol, name);
          BOOST_TEST(rotation_angle_between(b.R(), R_base) < tol, name);
          break;
        case RodEndKind::Collar:
          BOOST_TEST(max_abs(b.p - rod.base.position) < tol, name);
          BOOST_TEST(b.R().col(2).cross(R_base.col(2)).norm() < tol, name);
          BOOST_TEST(std::abs((b.m + rod.base.moment).dot(b.R().col(2))) < tol, name);
          break;
        case RodEndKind::Spherical:
          BOOST_TEST(max_abs(b.p - rod.base.position) < tol, name);
          BOOST_TEST(max_abs(b.m + rod.base.moment) < tol, name);
          break;
        case RodEndKind::Universal:
          // Turns only about R_T a and R b; no moment about either but the applied one.
          BOOST_TEST(max_abs(b.p - rod.base.position) < tol, name);
          BOOST_TEST(std::abs((R_base * kUniversalAxis).dot(b.R() * b_u)) < tol, name);
          BOOST_TEST(std::abs((b.m + rod.base.moment).dot(R_base * kUniversalAxis)) < tol, name);
          BOOST_TEST(std::abs((b.m + rod.base.moment).dot(b.R() * b_u)) < tol, name);
          break;
        case RodEndKind::Revolute:
          BOOST_TEST(max_abs(b.p - rod.base.position) < tol, name);
          BOOST_TEST(max_abs(b.R() * kRevoluteAxis - R_base * kRevoluteAxis) < tol, name);
          BOOST_TEST(std::abs((b.m + rod.base.moment).dot(R_base * kRevoluteAxis)) < tol, name);
          break;
        case RodEndKind::Free:
          BOOST_TEST(max_abs(b.n + rod.base.force) < tol, name);
          BOOST_TEST(max_abs(b.m + rod.base.moment) < tol, name);
          break;
      }
      switch (tip_kind) {
        case RodEndKind::Clamped:
          BOOST_TEST(max_abs(t.p - rod.tip.position) < tol, name);
          BOOST_TEST(rotation_angle_between(t.R(), R_tip) < tol, name);
          break;
        case RodEndKind::Collar:
          BOOST_TEST(max_abs(t.p - rod.tip.position) < tol, name);
          BOOST_TEST(t.R().col(2).cross(d3_tip).norm() < tol, name);
          BOOST_TEST(std::abs((t.m - rod.tip.moment).dot(t.R().col(2))) < tol, name);
          break;
        case RodEndKind::Spherical:
          BOOST_TEST(max_abs(t.p - rod.tip.position) < tol, name);
          BOOST_TEST(max_abs(t.m - rod.tip.moment) < tol, name);
          break;
        case RodEndKind::Universal:
          BOOST_TEST(max_abs(t.p - rod.tip.position) < tol, name);
          BOOST_TEST(std::abs((R_tip * kUniversalAxis).dot(t.R() * b_u)) < tol, name);
          BOOST_TEST(std::abs((t.m - rod.tip.moment).dot(R_tip * kUniversalAxis)) < tol, name);
          BOOST_TEST(std::abs((t.m - rod.tip.moment).dot(t.R() * b_u)) < tol, name);
          break;
        case RodEndKind::Revolute:
          BOOST_TEST(max_abs(t.p - rod.tip.position) < tol, name);
          BOOST_TEST(max_abs(t.R() * kRevoluteAxis - R_tip * kRevoluteAxis) < tol, name);
          BOOST_TEST(std::abs((t.m - rod.tip.moment).dot(R_tip * kRevoluteAxis)) < tol, name);
          break;
        case RodEndKind::Free: break;
      }
      // Same equilibrium as the reference (unique near this mildly loaded state): the whole state at
      // both ends; the integration bound scaled by the problem's sizes (forces and moments ~ 1).
      for (const auto& pair : {std::make_pair(&b, &ref.base), std::make_pair(&t, &ref.tip)}) {
        BOOST_TEST(max_abs(pair.first->p - pair.second->p) < 10 * tol, name);
        BOOST_TEST(rotation_angle_between(pair.first->R(), pair.second->R()) < 10 * tol, name);
        BOOST_TEST(max_abs(pair.first->n - pair.second->n) < 10 * tol, name);
        BOOST_TEST(max_abs(pair.first->m - pair.second->m) < 10 * tol, name);
      }
    }
  }
  // Accepted by RodModel::validate (one end holds the twist, the two ends hold the rod as a rigid body):
  // clamped x 6; collar, spherical x 3 (clamped, universal, revolute tips); universal, revolute x 5 (not
  // free); free x 1 (clamped).
  BOOST_TEST(pairings == 23);
}

// ---- joint ends against closed forms ----------------------------------------------------------------
namespace {

// Straight rod along e3 from the origin, EI = 1, L = 1, under a small transverse load w e1 per length,
// for the Euler-Bernoulli beam formulas. kGA = 1e8 EI / L^2 makes shear negligible (relative
// EI / (kGA L^2) = 1e-8). With both ends held in position the deflection stretches the centreline by
// ~(1/2) int w'^2 ~ 5 (delta / L)^2 (delta < w L^4 / (77 EI) = 1.3e-5), an axial force of up to
// EA 5 (delta/L)^2 = 8.5e-7 N for EA = 1e3, which changes the transverse reactions (3e-4 N and up) by a
// relative N L^2 / (10 EI) < 1e-7; geometric nonlinearity is O(slope^2) < 1e-9. Bound for the
// comparisons: 1e-6 relative.
constexpr double kBeamLoad = 1e-3;
constexpr double kBeamTheory = 1e-6;
RodModel pinned_beam(RodEndKind base, RodEndKind tip) {
  RodModel rod = cantilever(1.0, Vec3(1.0, 1.0, 1.0), Vec3(1e8, 1e8, 1e3));
  rod.loads.force_per_length = Vec3(kBeamLoad, 0.0, 0.0);
  rod.base.kind = base;
  rod.tip.kind = tip;
  rod.tip.position = Vec3(0.0, 0.0, 1.0);
  // Pins about e2: normal to the load plane x-z.
  rod.base.axis = rod.tip.axis = Vec3::UnitY();
  return rod;
}

}  // namespace

BOOST_AUTO_TEST_CASE(propped_cantilever_matches_euler_bernoulli) {
  // Clamped at s = 0, pinned at s = L (revolute about e2): reaction at the pin 3/8 w L, at the clamp
  // 5/8 w L and w L^2 / 8, slope at the pin w L^3 / (48 EI) (Roark's Formulas for Stress and Strain,
  // beam fixed at one end and supported at the other, uniform load).
  const RodModel rod = pinned_beam(RodEndKind::Clamped, RodEndKind::Revolute);
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  const double w = kBeamLoad;
  // The pin pushes against the load: n(L) = -3/8 w L e1; the clamp: base_force = -n(0) = -5/8 w L e1.
  BOOST_TEST(std::abs(sol.tip.n.x() + 3.0 / 8.0 * w) < kBeamTheory * w, "n(L) " << sol.tip.n.transpose());
  BOOST_TEST(std::abs(sol.base_force().x() + 5.0 / 8.0 * w) < kBeamTheory * w);
  BOOST_TEST(std::abs(std::abs(sol.base_moment().y()) - w / 8.0) < kBeamTheory * w);
  // Nothing out of the load plane (the pin transmits the moments about e1, e3; they vanish here).
  // (Unknowns found to the residual tolerance 1e-12 x M_c = 1 times the map's condition, < 100.)
  BOOST_TEST(std::abs(sol.base_moment().x()) + std::abs(sol.base_moment().z()) < 1e-10);
  BOOST_TEST(std::abs(sol.tip.m.y()) < 1e-11);  // no moment about the pin: a residual row, 1e-12 x M_c = 1
  const double slope = rotation_angle_between(sol.tip.R(), Mat3::Identity());
  BOOST_TEST(std::abs(slope - w / 48.0) < kBeamTheory * w / 48.0 + kTightIntegration, "slope " << slope);
}

BOOST_AUTO_TEST_CASE(simply_supported_beam_matches_euler_bernoulli) {
  // Revolute at both ends about e2: reactions w L / 2, end slopes w L^3 / (24 EI), midspan deflection
  // 5 w L^4 / (384 EI) (Roark, simply supported beam, uniform load).
  const RodModel rod = pinned_beam(RodEndKind::Revolute, RodEndKind::Revolute);
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  const double w = kBeamLoad;
  BOOST_TEST(std::abs(sol.tip.n.x() + w / 2.0) < kBeamTheory * w);
  BOOST_TEST(std::abs(sol.base.n.x() - w / 2.0) < kBeamTheory * w);
  // The pins pass no bending moment here (to the residual tolerance 1e-12 x M_c = 1 times the map's
  // condition, < 100).
  BOOST_TEST(max_abs(sol.base.m) < 1e-10);
  for (const ShootingState* end : {&sol.base, &sol.tip}) {
    const double slope = rotation_angle_between(end->R(), Mat3::Identity());
    BOOST_TEST(std::abs(slope - w / 24.0) < kBeamTheory * w / 24.0 + kTightIntegration, "slope " << slope);
  }
  const double deflection = sol.at(0.5).p.x();
  BOOST_TEST(std::abs(deflection - 5.0 * w / 384.0) < kBeamTheory * 5.0 * w / 384.0 + kTightIntegration,
             "deflection " << deflection);
}

BOOST_AUTO_TEST_CASE(universal_spherical_rod_in_tension_is_straight_along_the_chord) {
  // Universal base (first axis e1, so b = e3 x e1 = e2) at the origin, spherical tip at l d: the rod is a
  // two-force member, straight along d with n = N d, m = 0 and stretch 1 + N / EA (an exact Cosserat
  // solution: v = (0, 0, 1 + N / EA)), and R(0) = R_x(theta1) R_y(theta2) with
  // d = (sin theta2, -sin theta1 cos theta2, cos theta1 cos theta2).
  RodModel rod = cantilever(1.0, Vec3(1.0, 1.2, 0.8), Vec3(60, 70, 100));
  rod.base.kind = RodEndKind::Universal;
  rod.base.axis = Vec3::UnitX();
  rod.tip.kind = RodEndKind::Spherical;
  const Vec3 d = Vec3(0.3, -0.4, 1.0).normalized();
  const double N = 2.0, stretch = 1.0 + N / 100.0;
  rod.tip.position = stretch * d;
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  const double theta2 = std::asin(d.x()), theta1 = std::atan2(-d.y(), d.z());
  const Mat3 R0 = rotation_x(theta1) * rotation_y(theta2);
  BOOST_TEST(rotation_angle_between(sol.base.R(), R0) < kTightIntegration);
  BOOST_TEST(max_abs(sol.base.n - N * d) < kTightIntegration * N);
  BOOST_TEST(max_abs(sol.base.m) < kTightIntegration);
  for (int i = 0; i <= 10; ++i) {
    const ShootingState x = sol.at(0.1 * i);
    BOOST_TEST(max_abs(x.p - 0.1 * i * stretch * d) < kTightIntegration);
    BOOST_TEST(rotation_angle_between(x.R(), R0) < kTightIntegration);
  }
}

BOOST_AUTO_TEST_CASE(universal_joint_holds_the_twist_of_a_rod_in_torsion) {
  // Universal base (first axis e1) at the origin, the rod along d = R_x(0.4) e3 to a spherical tip at d
  // that applies the torque T d: the joint transmits the torsion along t = e1 x R b = d (theta2 = 0),
  // so the rod stays straight with m = T d and twists at the rate T / GJ:
  // R(s) = R_x(0.4) R_z(T s / GJ) (exact: n = 0, u = (0, 0, T / GJ)).
  RodModel rod = cantilever(1.0, Vec3(1.0, 1.2, 0.8), Vec3(60, 70, 100));
  rod.base.kind = RodEndKind::Universal;
  rod.base.axis = Vec3::UnitX();
  rod.tip.kind = RodEndKind::Spherical;
  const Mat3 R0 = rotation_x(0.4);
  const Vec3 d = R0.col(2);
  const double T = 0.5, GJ = 0.8;
  rod.tip.position = d;
  rod.tip.moment = T * d;
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  BOOST_TEST(max_abs(sol.base.m - T * d) < kTightIntegration);
  BOOST_TEST(max_abs(sol.base.n) < kTightIntegration);
  BOOST_TEST(rotation_angle_between(sol.base.R(), R0) < kTightIntegration);
  BOOST_TEST(rotation_angle_between(sol.tip.R(), R0 * rotation_z(T / GJ)) < kTightIntegration);
}

BOOST_AUTO_TEST_CASE(pinned_beam_with_end_moment_matches_beam_theory) {
  // Revolute base about e2 at the origin (pin), spherical tip at L e3 loaded by the moment M e2: the
  // bending moment grows linearly from 0 at the pin to M, the section rotation is
  // psi(s) = -M L / (6 EI) + M s^2 / (2 EI L) about e2 (Roark, simply supported beam with an end couple):
  // the pin turns by -M L / (6 EI), the tip by M L / (3 EI). Bound as for pinned_beam (no distributed
  // load here; slope M L / (3 EI) = 3.3e-4, geometric nonlinearity O(slope^2) ~ 1e-7 relative; shear
  // V / kGA = 1e-11): kBeamTheory relative.
  RodModel rod = pinned_beam(RodEndKind::Revolute, RodEndKind::Spherical);
  rod.loads.force_per_length.setZero();
  const double M = 1e-3;  // EI = 1, L = 1
  rod.tip.moment = Vec3(0.0, M, 0.0);
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  const double pin = rotation_angle_between(sol.base.R(), rotation_y(-M / 6.0));
  const double tip = rotation_angle_between(sol.tip.R(), rotation_y(M / 3.0));
  BOOST_TEST(pin < kBeamTheory * M / 6.0 + kTightIntegration, "pin rotation error " << pin);
  BOOST_TEST(tip < kBeamTheory * M / 3.0 + kTightIntegration, "tip rotation error " << tip);
  // Exact statics (the tip stays at L e3): e2 . (m(L) - m(0) + L e3 x n) = 0 with m(0) . e2 = 0 gives
  // n_x = -M / L; nothing out of the plane. Residual rows 1e-12 x F_c, M_c = 1 times the map's condition
  // (< 100).
  BOOST_TEST(std::abs(sol.base.n.x() + M) < 1e-10);
  BOOST_TEST(std::abs(sol.base.n.y()) + std::abs(sol.base.m.y()) < 1e-10);
}

BOOST_AUTO_TEST_CASE(revolute_rod_in_tension_turns_rigidly_about_its_pin) {
  // Revolute base at the origin with the default axis (the end frame's x axis), spherical tip at
  // stretch R_x(theta) e3: a straight two-force member turned rigidly by theta about the pin,
  // R(s) = R_x(theta), n = N d, m = 0, stretch 1 + N / EA (exact, as for the universal rod below).
  RodModel rod = cantilever(1.0, Vec3(1.0, 1.2, 0.8), Vec3(60, 70, 100));
  rod.base.kind = RodEndKind::Revolute;
  rod.tip.kind = RodEndKind::Spherical;
  const double theta = 0.5, N = 2.0, stretch = 1.0 + N / 100.0;
  const Mat3 R = rotation_x(theta);
  rod.tip.position = stretch * R.col(2);
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  for (int i = 0; i <= 10; ++i) {
    const ShootingState x = sol.at(0.1 * i);
    BOOST_TEST(max_abs(x.p - 0.1 * i * stretch * R.col(2)) < kTightIntegration);
    BOOST_TEST(rotation_angle_between(x.R(), R) < kTightIntegration);
    BOOST_TEST(max_abs(x.n - N * R.col(2)) < kTightIntegration * N);
    BOOST_TEST(max_abs(x.m) < kTightIntegration);
  }
}

// ---- global equilibrium of a gravity-loaded cantilever ---------------------------------------------
BOOST_AUTO_TEST_CASE(gravity_cantilever_base_wrench_balances_the_loads) {
  // Steel rod, radius 1 mm, 0.5 m, horizontal (d3 = e1), gravity -9.81 e3, a tip weight 0.05 N.
  RodModel rod;
  rod.name = "steel";
  rod.length = 0.5;
  rod.set_material_and_section(Material{200e9, 80e9, 8000.0}, CrossSection::circle(1e-3));
  rod.loads.gravity = Vec3(0, 0, -9.81);
  rod.base.kind = RodEndKind::Clamped;
  rod.base.orientation = quat_from_rotation(rotation_y(M_PI / 2));
  rod.tip.kind = RodEndKind::Free;
  rod.tip.force = Vec3(0, 0, -0.05);
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
  // Linear beam theory: w L^4 / (8 EI) + P L^3 / (3 EI) = 25.5 mm; deflection / L = 5 %, so the
  // geometric nonlinearity changes it by O(theta_tip^2) ~ 0.5 %: allow 2 %.
  const double EI = rod.bending_torsion_stiffness[0], w = rod.mass_per_length * 9.81;
  const double linear = w * std::pow(rod.length, 4) / (8 * EI) + 0.05 * std::pow(rod.length, 3) / (3 * EI);
  BOOST_TEST(std::abs(-sol.tip.p.z() - linear) < 0.02 * linear,
             "tip z " << sol.tip.p.z() << " linear " << linear);
  const Vec3 f = rod.distributed_force();
  const double L = rod.length;
  // Forces: base reaction + tip force + total weight = 0 (n' = -f is integrated exactly: roundoff).
  const Vec3 force_sum = sol.base_force() + rod.tip.force + f * L;
  BOOST_TEST(max_abs(force_sum) < 1e-12 * max_abs(f * L));
  // Moments about p(0): base moment + (p(L) - p(0)) x F + int (p - p(0)) x f ds = 0. The integral by
  // composite Simpson on 400 intervals of the dense output: error <= L h^4 max|g''''| / 180 with
  // g = (p - p0) x f, |g''''| <= |f| |p''''| ~ |f| kappa_max^3 (kappa_max ~ 1 / m): < 1e-14 |f| L^2,
  // so the 1e-9 integration bound dominates.
  const int N = 400;
  const double h = L / N;
  Vec3 integral = Vec3::Zero();
  for (int i = 0; i <= N; ++i) {
    const double w = (i == 0 || i == N) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    integral += w * (sol.at(i * h).p - sol.base.p).cross(f);
  }
  integral *= h / 3.0;
  const Vec3 moment_sum = sol.base_moment() + (sol.tip.p - sol.base.p).cross(rod.tip.force) + integral;
  const double moment_size = max_abs(f) * L * L + max_abs(rod.tip.force) * L;
  BOOST_TEST(max_abs(moment_sum) < kTightIntegration * moment_size, "moment sum " << moment_sum.transpose());
}

// ---- tangents (variational equations) against central finite differences ---------------------------
BOOST_AUTO_TEST_CASE(tangents_match_finite_differences) {
  RodModel rod = cantilever(1.0, Vec3(1.0, 2.0, 1.5), Vec3(30, 40, 100));
  rod.loads.force_per_length = Vec3(0.3, -1.0, 0.5);
  rod.loads.moment_per_length = Vec3(0.1, 0.0, -0.2);
  rod.intrinsic.curvature = Vec3(0.5, 0.2, 0.1);
  const RodOde ode(rod);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  RodStateWithTangents Y;
  for (int i = 0; i < Y.size(); ++i) Y.data()[i] = normal(rng);
  Y.col(0).segment<4>(RodStateIndex::q).normalize();
  IntegratorOptions o;
  o.method = IntegratorMethod::RK4;  // fixed steps: the tangents are the exact derivative of the map
  o.rk4_steps = 50;
  RodStateWithTangents Y1 = Y;
  BOOST_TEST_REQUIRE(integrate_rod(ode, 0.0, 1.0, Y1, o).success);
  const Quat q1 = Y1.col(0).segment<4>(RodStateIndex::q);
  for (int j = 1; j <= kRodTangentCount; ++j) {
    const double eps = 1e-6;
    RodStateVector a = Y.col(0) + eps * Y.col(j), b = Y.col(0) - eps * Y.col(j);
    integrate_rod(ode, 0.0, 1.0, a, o);
    integrate_rod(ode, 0.0, 1.0, b, o);
    const RodStateVector fd = (a - b) / (2 * eps);
    // Central differences: truncation eps^2 |y'''| ~ 1e-12 x O(10), roundoff 1e-16 / eps ~ 1e-10,
    // relative to the tangent's size (~ 10): 1e-8.
    const double tol = 1e-8 * Y1.col(j).norm();
    BOOST_TEST(max_abs(fd.segment<3>(RodStateIndex::p) - Y1.col(j).segment<3>(RodStateIndex::p)) < tol);
    BOOST_TEST(max_abs(fd.segment<3>(RodStateIndex::n) - Y1.col(j).segment<3>(RodStateIndex::n)) < tol);
    BOOST_TEST(max_abs(fd.segment<3>(RodStateIndex::m) - Y1.col(j).segment<3>(RodStateIndex::m)) < tol);
    // Orientation: compare dR (the radial part of dq is a gauge, normalised away after each step).
    const Mat3 dR_fd =
        (rotation_matrix(a.segment<4>(RodStateIndex::q)) - rotation_matrix(b.segment<4>(RodStateIndex::q))) /
        (2 * eps);
    Mat3 R1;
    QuatRotationJacobian dR;
    rotation_matrix_derivatives(q1, R1, dR);
    Mat3 dR_tangent = Mat3::Zero();
    for (int k = 0; k < 4; ++k) dR_tangent += dR[k] * Y1(RodStateIndex::q + k, j);
    BOOST_TEST((dR_fd - dR_tangent).cwiseAbs().maxCoeff() < tol);
  }
}

// ---- the shooting Jacobian of every pairing against finite differences ------------------------------------
BOOST_AUTO_TEST_CASE(shooting_jacobian_matches_finite_differences_for_every_pairing) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto random_vec = [&]() { return Vec3(normal(rng), normal(rng), normal(rng)); };
  for (RodEndKind base_kind : kAllKinds) {
    for (RodEndKind tip_kind : kAllKinds) {
      RodModel rod = cantilever(1.0, Vec3(1.0, 1.3, 0.9), Vec3(40, 50, 80));
      if (!accepted(rod, base_kind, tip_kind)) continue;
      rod.base.kind = base_kind;
      rod.tip.kind = tip_kind;
      rod.base.axis = Vec3(0.9, -0.4, 0.3);  // joint axes, not unit (normalised by the solver)
      rod.tip.axis = Vec3(-0.2, 0.8, 0.5);
      rod.loads.force_per_length = 0.5 * random_vec();
      rod.base.orientation = quat_from_rotation_vector(0.5 * random_vec());
      rod.base.moment = 0.3 * random_vec();
      rod.base.force = 0.3 * random_vec();
      rod.tip.orientation = quat_from_rotation_vector(0.5 * random_vec());
      rod.tip.position = Vec3(0.2, 0.1, 0.8);
      rod.tip.moment = 0.3 * random_vec();
      rod.tip.force = 0.3 * random_vec();
      const RodOde ode(rod);
      ShootingState guess;
      guess.p = 0.1 * random_vec();
      guess.q = quat_from_rotation_vector(0.4 * random_vec());
      guess.n = random_vec();
      guess.m = random_vec();
      RodStateVector y0 = guess.to_vector();
      shooting::enforce_base(rod.base, y0);
      IntegratorOptions o;
      o.method = IntegratorMethod::RK4;  // fixed steps: the map is smooth in the unknowns
      o.rk4_steps = 40;
      RodStateWithTangents Y;
      shooting::base_tangents(rod.base, y0, Y);
      BOOST_TEST_REQUIRE(integrate_rod(ode, 0.0, 1.0, Y, o).success);
      const shooting::Mat6 J = shooting::tip_residual_jacobian(rod.tip, Y);
      for (int j = 0; j < 6; ++j) {
        const double eps = 1e-6;
        shooting::Vec6 dz = shooting::Vec6::Zero();
        dz[j] = eps;
        RodStateVector a = y0, b = y0;
        shooting::retract_base(rod.base, dz, a);
        shooting::retract_base(rod.base, -dz, b);
        integrate_rod(ode, 0.0, 1.0, a, o);
        integrate_rod(ode, 0.0, 1.0, b, o);
        const shooting::Vec6 fd =
            (shooting::tip_residual(rod.tip, a) - shooting::tip_residual(rod.tip, b)) / (2 * eps);
        // Central differences: eps^2 truncation and 1e-16 / eps roundoff on entries of size ~1-10.
        BOOST_TEST(
            (fd - J.col(j)).cwiseAbs().maxCoeff() < 1e-7 * std::max(1.0, J.col(j).cwiseAbs().maxCoeff()),
            to_string(base_kind) << "-" << to_string(tip_kind) << " column " << j << ": fd " << fd.transpose()
                                 << " vs " << J.col(j).transpose());
      }
    }
  }
}

// ---- a tip turned by a half turn: U-shaped rod
// -------------------------------------------------------------
BOOST_AUTO_TEST_CASE(u_shaped_rod_reaches_a_tip_flipped_by_pi) {
  // Base clamped at 0 along e3, tip at (0.4, 0, 0) pointing down (-e3): the rod bends into a U. By
  // symmetry about the plane x = 0.2, the midpoint s = L/2 lies on it with the tangent along +e1.
  for (RodEndKind tip_kind : {RodEndKind::Clamped, RodEndKind::Collar}) {
    RodModel rod = cantilever(1.0, Vec3(1, 1, 1), Vec3(100, 100, 100));
    rod.tip.kind = tip_kind;
    rod.tip.position = Vec3(0.4, 0.0, 0.0);
    rod.tip.orientation = quat_from_rotation(rotation_y(M_PI));
    const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
    BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
    BOOST_TEST(max_abs(sol.tip.p - rod.tip.position) < kTightIntegration);
    BOOST_TEST(sol.tip.R().col(2).dot(Vec3(0, 0, -1)) > 1.0 - 1e-12);  // pointing down, not up
    const ShootingState mid = sol.at(0.5);
    // The symmetry holds to the integration accuracy.
    BOOST_TEST(std::abs(mid.p.x() - 0.2) < kTightIntegration, "mid " << mid.p.transpose());
    BOOST_TEST(mid.R().col(2).dot(Vec3::UnitX()) > 1.0 - kTightIntegration);
  }
}

// ---- RK4 converges with order 4 --------------------------------------------------------------------------
BOOST_AUTO_TEST_CASE(rk4_error_decreases_as_n_to_the_minus_4) {
  // Precurved, gravity-loaded, tip-loaded cantilever (no closed form): reference by Dormand-Prince at
  // tolerance 1e-13.
  RodModel rod = cantilever(1.0, Vec3(1.0, 1.0, 0.8), Vec3(1e3, 1e3, 2e3));
  rod.intrinsic.curvature = Vec3(1.0, 0.0, 0.5);
  rod.loads.force_per_length = Vec3(0.0, -2.0, 0.0);
  rod.tip.force = Vec3(1.5, 0.0, 0.0);
  ShootingOptions ref_options = tight_options();
  ref_options.integration_relative_tolerance = 1e-13;
  ref_options.integration_absolute_tolerance = 1e-15;
  ref_options.tolerance = 1e-13;
  const ShootingSolution ref = solve_rod_shooting(rod, ref_options);
  BOOST_TEST_REQUIRE(ref.summary.converged(), ref.summary.brief_report());
  std::vector<double> errors;
  for (int N : {10, 20, 40, 80, 160}) {
    ShootingOptions o = ref_options;
    o.integrator = IntegratorMethod::RK4;
    o.rk4_steps = N;
    const ShootingSolution sol = solve_rod_shooting(rod, o);
    BOOST_TEST_REQUIRE(sol.summary.converged(), sol.summary.brief_report());
    const double error = (sol.tip.p - ref.tip.p).norm();
    errors.push_back(error);
    BOOST_TEST_MESSAGE("RK4 N = " << N << ": tip error " << error);
  }
  for (size_t i = 0; i + 1 < errors.size(); ++i) {
    const double order = std::log2(errors[i] / errors[i + 1]);
    // Classical RK4 has order 4; +-0.3 allows the pre-asymptotic range at N = 10.
    BOOST_TEST(std::abs(order - 4.0) < 0.3,
               "order between N = " << (10 << i) << " and " << (20 << i) << ": " << order);
  }
}

// ---- dense output ---------------------------------------------------------------------------------------
BOOST_AUTO_TEST_CASE(dense_output_matches_stored_steps_and_a_direct_integration) {
  RodModel rod = cantilever(1.0, Vec3(1, 1, 1), Vec3(100, 100, 100));
  rod.tip.force = Vec3(2.0, 0.0, 0.0);
  const ShootingSolution sol = solve_rod_shooting(rod, tight_options());
  BOOST_TEST_REQUIRE(sol.summary.converged());
  BOOST_TEST_REQUIRE(sol.s.size() == sol.states.size());
  BOOST_TEST(sol.s.front() == 0.0);
  BOOST_TEST(sol.s.back() == 1.0);
  for (size_t i = 0; i < sol.s.size(); i += 7)
    BOOST_TEST(max_abs(sol.at(sol.s[i]).p - sol.states[i].p) == 0.0);
  // At s = 0.37: integrate the ODE directly from the base with tight Dormand-Prince up to 0.37.
  const RodOde ode(rod);
  RodStateVector y = sol.base.to_vector();
  IntegratorOptions o;
  o.relative_tolerance = 1e-13;
  o.absolute_tolerance = 1e-15;
  integrate_rod(ode, 0.0, 0.37, y, o);
  BOOST_TEST(max_abs(sol.at(0.37).p - y.head<3>()) < kTightIntegration);
  const auto samples = sol.sample({0.9, 0.1});
  BOOST_TEST(samples.size() == 2u);
  BOOST_TEST(max_abs(samples[1].p - sol.at(0.1).p) == 0.0);
  BOOST_CHECK_THROW(sol.at(1.5), InputError);
  BOOST_CHECK_THROW(sol.at(-0.1), InputError);
  // Round-off beyond the ends (s = L i / N computed by a caller) gives the end states.
  BOOST_TEST(max_abs(sol.at(1.0 + 1e-15).p - sol.states.back().p) == 0.0);
  BOOST_TEST(max_abs(sol.at(-1e-15).p - sol.states.front().p) == 0.0);
}

// ---- warm start
// --------------------------------------------------------------------------------------------
BOOST_AUTO_TEST_CASE(warm_start_needs_fewer_iterations) {
  const ShootingSolution cold = solve_rod_shooting(bisshopp_drucker(3.0), tight_options());
  const ShootingSolution near = solve_rod_shooting(bisshopp_drucker(3.05), tight_options(), &cold);
  const ShootingSolution near_cold = solve_rod_shooting(bisshopp_drucker(3.05), tight_options());
  BOOST_TEST_REQUIRE(near.summary.converged());
  BOOST_TEST_REQUIRE(near_cold.summary.converged());
  BOOST_TEST(near.summary.iterations < near_cold.summary.iterations);
  BOOST_TEST(max_abs(near.tip.p - near_cold.tip.p) < kTightIntegration);
}

// ---- load stepping ----------------------------------------------------------------------------------------
BOOST_AUTO_TEST_CASE(load_stepping_reaches_large_loads) {
  // alpha = 100: Newton alone (capped steps, LM) stalls; continuation reaches the full load.
  const double alpha = 100.0;
  ShootingOptions o = tight_options();
  const ShootingSolution with = solve_rod_shooting(bisshopp_drucker(alpha), o);
  BOOST_TEST_REQUIRE(with.summary.converged(), with.summary.brief_report());
  BOOST_TEST(with.summary.load_steps > 1);
  const Elastica e = elastica(alpha);
  // Extensibility bound as in the table test, plus the integration bound.
  BOOST_TEST(std::abs(with.tip.p.x() - e.y) < 2 * alpha / kR2AxialStiffness + kTightIntegration);
  BOOST_TEST(std::abs(with.tip.p.z() - e.x) < 2 * alpha / kR2AxialStiffness + kTightIntegration);
  o.load_stepping = false;
  const ShootingSolution without = solve_rod_shooting(bisshopp_drucker(alpha), o);
  BOOST_TEST(!without.summary.converged(), without.summary.brief_report());
}

// ---- bad input, non-convergence, integration failure ------------------------------------------------------
BOOST_AUTO_TEST_CASE(bad_input_throws_input_error) {
  RodModel rod = bisshopp_drucker(1.0);
  rod.length = -1.0;
  BOOST_CHECK_THROW(solve_rod_shooting(rod), InputError);
  rod = bisshopp_drucker(1.0);
  rod.bending_torsion_stiffness[2] = 0.0;
  BOOST_CHECK_THROW(solve_rod_shooting(rod), InputError);
  // No clamped end: the pairing is unsupported (free twist or rigid motion), with a message.
  rod = bisshopp_drucker(1.0);
  rod.base.kind = RodEndKind::Spherical;
  rod.tip.kind = RodEndKind::Collar;
  try {
    solve_rod_shooting(rod);
    BOOST_FAIL("spherical-collar accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("clamp") != std::string::npos, e.what());
  }
  // A universal base with a free tip: the rod could swing about the joint as a rigid body.
  rod = bisshopp_drucker(1.0);
  rod.base.kind = RodEndKind::Universal;
  try {
    solve_rod_shooting(rod);
    BOOST_FAIL("universal-free accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("rigid body") != std::string::npos, e.what());
  }
  // A universal axis along the rod tangent (no second axis), and a zero revolute axis.
  rod = bisshopp_drucker(1.0);
  rod.tip.kind = RodEndKind::Universal;
  rod.tip.axis = Vec3(0.0, 0.0, 2.0);
  try {
    solve_rod_shooting(rod);
    BOOST_FAIL("universal axis along the tangent accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("universal axis") != std::string::npos, e.what());
  }
  rod.tip.kind = RodEndKind::Revolute;
  rod.tip.axis = Vec3::Zero();
  BOOST_CHECK_THROW(solve_rod_shooting(rod), InputError);
  ShootingOptions o;
  o.integrator = IntegratorMethod::RK4;
  o.rk4_steps = 0;
  BOOST_CHECK_THROW(solve_rod_shooting(bisshopp_drucker(1.0), o), InputError);
  o = ShootingOptions();
  o.integration_relative_tolerance = -1.0;
  BOOST_CHECK_THROW(solve_rod_shooting(bisshopp_drucker(1.0), o), InputError);
  o = ShootingOptions();
  o.tolerance = 0.0;
  BOOST_CHECK_THROW(solve_rod_shooting(bisshopp_drucker(1.0), o), InputError);
  RodStateVector y = ShootingState().to_vector();
  BOOST_CHECK_THROW(integrate_rod(RodOde(bisshopp_drucker(1.0)), 1.0, 0.5, y, IntegratorOptions()),
                    InputError);
}

BOOST_AUTO_TEST_CASE(non_converging_solve_reports_status_without_nan) {
  ShootingOptions o = tight_options();
  o.max_iterations = 1;
  for (bool stepping : {false, true}) {
    o.load_stepping = stepping;
    const ShootingSolution sol = solve_rod_shooting(bisshopp_drucker(15.0), o);
    BOOST_TEST(!sol.summary.converged(), sol.summary.brief_report());
    BOOST_TEST(!sol.summary.message.empty());
    BOOST_TEST(std::isfinite(sol.summary.residual_max_abs));
    BOOST_TEST(sol.summary.residual_max_abs > o.tolerance);
    BOOST_TEST(all_finite(sol.base));
    BOOST_TEST(all_finite(sol.tip));
  }
}

BOOST_AUTO_TEST_CASE(integration_failure_is_reported) {
  ShootingOptions o = tight_options();
  o.max_integration_steps = 5;  // far too few for integration_relative_tolerance = 1e-12
  const ShootingSolution sol = solve_rod_shooting(bisshopp_drucker(2.0), o);
  BOOST_TEST(!sol.summary.converged());
  BOOST_TEST(sol.summary.message.find("max_steps") != std::string::npos, sol.summary.message);
  BOOST_TEST(all_finite(sol.base));
  BOOST_TEST(all_finite(sol.tip));
  // Minimum step guard: a step floor of half the rod cannot meet a relative tolerance of 1e-12 on a bent rod.
  IntegratorOptions io;
  io.relative_tolerance = 1e-12;
  io.min_step_fraction = 0.5;
  ShootingState bent;
  bent.m = Vec3(5, 0, 0);
  RodStateVector y = bent.to_vector();
  const IntegrationReport floor = integrate_rod(RodOde(bisshopp_drucker(2.0)), 0.0, 1.0, y, io);
  BOOST_TEST(!floor.success);
  BOOST_TEST(floor.message.find("underflow") != std::string::npos, floor.message);
  y = ShootingState().to_vector();
  io = IntegratorOptions();
  io.max_steps = 3;
  io.relative_tolerance = 1e-12;
  const IntegrationReport report = integrate_rod(RodOde(bisshopp_drucker(2.0)), 0.0, 1.0, y, io);
  BOOST_TEST(!report.success);
  BOOST_TEST(report.message.find("max_steps") != std::string::npos, report.message);
}
