// Shooting reference for single rods (the test_shooting module, one executable of several files):
// analytic solutions (R1 arc, R3 helix), the Bisshopp-Drucker elastica (R2, table and elliptic integrals,
// and load stepping to alpha = 100), a precurved rod, global equilibrium of a gravity-loaded cantilever
// and a U-shaped rod. The other files: every end pairing (test_shooting_pairings.cpp), closed forms for
// joint ends (test_shooting_joint_ends.cpp), the integrator, warm starts and failures
// (test_shooting_integration.cpp).
#define BOOST_TEST_MODULE shooting
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/rods/shooting/rod_integrator.hpp"
#include "pcr/rods/shooting/rod_shooting.hpp"
#include "shooting/shooting_fixtures.hpp"

using namespace pcr;
using namespace pcr::shooting_test;

namespace {

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
    RodModel rod = test::cantilever(1.0, Vec3(50, 50, 100), Vec3(2, 2, 2));
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
    RodModel rod = test::cantilever(1.0, Vec3(40, 50, 90), Vec3(1.0, 1.5, 0.7));
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

// ---- a tip turned by a half turn: U-shaped rod
// -------------------------------------------------------------
BOOST_AUTO_TEST_CASE(u_shaped_rod_reaches_a_tip_flipped_by_pi) {
  // Base clamped at 0 along e3, tip at (0.4, 0, 0) pointing down (-e3): the rod bends into a U. By
  // symmetry about the plane x = 0.2, the midpoint s = L/2 lies on it with the tangent along +e1.
  for (RodEndKind tip_kind : {RodEndKind::Clamped, RodEndKind::Collar}) {
    RodModel rod = test::cantilever(1.0, Vec3(100, 100, 100), Vec3(1, 1, 1));
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
