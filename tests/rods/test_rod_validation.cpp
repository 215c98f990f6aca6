// Collocation rods against analytic solutions and published tables (scenes R1-R3 of
// docs/benchmarks.md (Scenes)), the helical spring, shear locking and the convergence orders.
#define BOOST_TEST_MODULE rod_validation
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <iostream>

#include "pcr/rods/rod_solve.hpp"
#include "rod_fixtures.hpp"

using namespace pcr;

namespace {

RodSolution solve_or_fail(const RodModel& m, RodFormulation f, int degree, int elements, double tol = 1e-11) {
  RodSolveOptions o;
  o.discretization = {f, degree, elements};
  o.tolerance = tol;
  RodSolution sol = solve_rod(m, o);
  BOOST_REQUIRE_MESSAGE(sol.summary.converged(), sol.summary.brief_report());
  return sol;
}

/// Max over 201 points of |p_h(s) - p_exact(s)|.
template <typename Exact>
double centerline_error(const RodSolution& sol, double L, Exact exact) {
  double e = 0.0;
  for (int i = 0; i <= 200; ++i) {
    const double s = L * i / 200.0;
    e = std::max(e, (sol.at(s).position - exact(s)).norm());
  }
  return e;
}

// R1: EI = 2, L = 1, moment about e1 at the tip; finite EA, GA (n = 0, so exact regardless).
RodModel end_moment_rod(double phi) {
  RodModel m = test::cantilever(1.0, Vec3(50.0, 50.0, 100.0), Vec3(2.0, 2.0, 1.5));
  m.tip.moment = Vec3(phi * 2.0 / 1.0, 0.0, 0.0);
  return m;
}

double end_moment_error(const RodSolution& sol, double phi) {
  const Vec3 kappa(phi, 0.0, 0.0);  // M / EI with L = 1
  return centerline_error(sol, 1.0, [&](double s) { return test::constant_curvature_position(kappa, s); });
}

}  // namespace

BOOST_AUTO_TEST_CASE(r1_end_moment_rolls_the_rod_into_exact_arcs) {
  // Tolerances: 10x the max centerline error measured at this discretisation (p = 6, 16 elements)
  // when the test was written; the arc is exact, so these bound the discretisation error.
  struct Case {
    double phi, tol_mixed, tol_primal;
  };
  for (const Case c : {Case{M_PI / 2, 1e-9, 1e-8}, Case{2 * M_PI, 1e-7, 4e-6}, Case{4 * M_PI, 1e-5, 4e-4}}) {
    for (RodFormulation f : {RodFormulation::Mixed, RodFormulation::Primal}) {
      const double tol = f == RodFormulation::Mixed ? c.tol_mixed : c.tol_primal;
      const RodSolution sol = solve_or_fail(end_moment_rod(c.phi), f, 6, 16, f == RodFormulation::Mixed ? 1e-11 : 1e-10);
      const double e = end_moment_error(sol, c.phi);
      BOOST_TEST(e < tol, to_string(f) << " phi = " << c.phi << ": centerline error " << e);
      // The full circle brings the tip back to the base with the tangent restored.
      if (std::abs(c.phi - 2 * M_PI) < 1e-12) {
        BOOST_TEST(sol.tip().position.norm() < tol);
        BOOST_TEST((sol.tip().rotation.col(2) - Vec3::UnitZ()).norm() < 10 * tol);
      }
      // n = 0 along the exact solution; the discrete n is a derivative quantity, one order of h
      // less accurate than the centerline (measured |n(0)| / F0 <= 200x the centerline error).
      BOOST_TEST(sol.base().force.norm() / 2.0 < 1e3 * tol, to_string(f) << " |n(0)| = " << sol.base().force.norm());
    }
  }
}

BOOST_AUTO_TEST_CASE(r2_bisshopp_drucker_table) {
  // alpha = P L^2 / EI, (L - x_tip)/L, y_tip/L, tip angle: the inextensible elastica (Bisshopp &
  // Drucker 1945 at alpha = 1, 2; elliptic-integral quadrature to 5 digits for the other rows).
  const double table[14][4] = {{0.2, 0.00265, 0.06636, 0.0996}, {0.4, 0.01035, 0.13098, 0.1972},
                               {0.6, 0.02249, 0.19235, 0.2907}, {0.8, 0.03817, 0.24945, 0.3791},
                               {1, 0.05643, 0.30172, 0.4614},   {1.5, 0.10794, 0.41098, 0.6395},
                               {2, 0.16064, 0.49346, 0.7818},   {3, 0.25442, 0.60325, 0.9860},
                               {4, 0.32894, 0.66996, 1.1212},   {5, 0.38763, 0.71379, 1.2154},
                               {6, 0.43459, 0.74457, 1.2837},   {8, 0.50483, 0.78498, 1.3744},
                               {10, 0.55500, 0.81061, 1.4303},  {15, 0.63529, 0.84772, 1.5018}};
  // Inextensible, unshearable limit: EA = GA = 1e8 EI / L^2, so axial/shear strains are at most
  // alpha * 1e-8 <= 1.5e-7, below half a unit of the table's last digit (5e-6 for positions, 5e-5
  // for the angle), which is the tolerance used (plus 1e-6 for the discretisation error, measured
  // below 2e-8 at p = 6, 32 elements for alpha = 10). Independently, the elastica is recomputed
  // from its elliptic-integral solution and matched to 5e-7 (extensibility 1.5e-7 + discretisation).
  const double EI = 1.0, L = 1.0;
  for (const auto& row : table) {
    RodModel m = test::cantilever(L, Vec3::Constant(1e8 * EI / (L * L)), Vec3(EI, EI, EI));
    m.tip.force = Vec3(row[0] * EI / (L * L), 0.0, 0.0);  // perpendicular dead force along e1
    const RodSolution sol = solve_or_fail(m, RodFormulation::Mixed, 6, 32);
    const RodState tip = sol.tip();
    const double axial = (L - tip.position.z()) / L, lateral = tip.position.x() / L;
    const double angle = std::atan2(tip.rotation(0, 2), tip.rotation(2, 2));
    BOOST_TEST(std::abs(axial - row[1]) < 5e-6 + 1e-6, "alpha " << row[0] << ": (L-x)/L " << axial << " vs " << row[1]);
    BOOST_TEST(std::abs(lateral - row[2]) < 5e-6 + 1e-6, "alpha " << row[0] << ": y/L " << lateral << " vs " << row[2]);
    BOOST_TEST(std::abs(angle - row[3]) < 5e-5 + 1e-6, "alpha " << row[0] << ": angle " << angle << " vs " << row[3]);
    const test::Elastica exact = test::bisshopp_drucker(row[0]);
    BOOST_TEST(std::abs(axial - exact.axial) < 5e-7, "alpha " << row[0] << ": elliptic (L-x)/L " << exact.axial);
    BOOST_TEST(std::abs(lateral - exact.lateral) < 5e-7, "alpha " << row[0] << ": elliptic y/L " << exact.lateral);
    BOOST_TEST(std::abs(angle - exact.angle) < 5e-7, "alpha " << row[0] << ": elliptic angle " << exact.angle);
  }
}

BOOST_AUTO_TEST_CASE(r3_exact_helix_whole_centerline) {
  // E = 1, G = 0.5, circle of radius 1: EI = GJ = pi / 4; EA = pi, GA = pi / 2 (k = 1).
  const double kb = 0.086332350, kt = 0.034350551, L = 135.245580489;
  const double EI = M_PI / 4;
  RodModel m = test::cantilever(L, Vec3(M_PI / 2, M_PI / 2, M_PI), Vec3(EI, EI, EI));
  const Vec3 kappa(kb, 0.0, kt);
  m.tip.moment = EI * kappa;  // R(L) kappa = kappa, so the dead moment m(L) = R K_BT kappa = EI kappa
  const RodSolution sol = solve_or_fail(m, RodFormulation::Mixed, 6, 64);
  const double e = centerline_error(sol, L, [&](double s) { return test::constant_curvature_position(kappa, s); });
  // Measured 3.8e-8 at p = 6, 64 elements (4.9e-6 at 32: order ~7); tolerance 10x that.
  BOOST_TEST(e < 4e-7, "helix centerline error " << e);
  const Vec3 top = test::constant_curvature_position(kappa, L);
  BOOST_TEST(std::abs(top.norm() - std::hypot(0.0, 50.0)) < 1.0);  // sanity: height 50 (two coils end on the axis)
}

BOOST_AUTO_TEST_CASE(helical_spring_small_load_stiffness) {
  // A stress-free helix (intrinsic curvature kappa0 = (k, 0, tau)) pulled along its axis by a force F
  // acting on the axis (a dead force at the wire tip plus the moment of the arm to the axis). The
  // classical spring deflection (inextensible, unshearable; Weeger et al. 2017 §7):
  //   delta = F R^2 L (cos^2 alpha / GJ + sin^2 alpha / EI),
  // with helix radius R and pitch angle alpha: k = cos^2(alpha)/R, tau = sin(alpha) cos(alpha)/R.
  // delta is measured between the loaded and the unloaded discrete solutions (same discretisation,
  // so the geometric discretisation error cancels), and the linear stiffness is extracted by
  // Richardson extrapolation from F and 2F: delta_lin(F) = 2 delta(F) - delta(2F) / 2, error O(F^3).
  for (double alpha_deg : {5.0, 20.0, 45.0}) {
    const test::HelicalSpring spring = test::helical_spring(alpha_deg);
    const Vec3 axis = spring.axis;
    // The load acts at the axis point, rigidly attached to the wire tip by an arm; Castigliano's
    // deflection is that of this point: p_tip + R_tip a, with the arm a fixed in the tip frame.
    RodState unloaded;
    auto load_point_for = [&](double F) {
      const RodState tip = solve_or_fail(spring.model(1e9, F), RodFormulation::Mixed, 6, 24, 1e-12).tip();
      if (F == 0.0) unloaded = tip;
      const Vec3 arm_body = unloaded.rotation.transpose() * (spring.on_axis - unloaded.position);
      return Vec3(tip.position + tip.rotation * arm_body);
    };
    const double F = 1e-3 * spring.radius / spring.compliance;  // delta / R ~ 1e-3
    const Vec3 p0 = load_point_for(0.0);
    const double d1 = (load_point_for(F) - p0).dot(axis), d2 = (load_point_for(2 * F) - p0).dot(axis);
    const double linear = 2 * d1 - d2 / 2, expected = F * spring.compliance;
    // Relative tolerance 1e-4: Richardson leaves O((delta/R)^2) ~ 1e-6, extension/shear give 1e-9,
    // the discretisation of three coils at p = 6, 24 elements (measured ~1e-6 on the geometry).
    BOOST_TEST(std::abs(linear - expected) < 1e-4 * expected,
               "alpha " << alpha_deg << " deg: delta " << linear << " vs classical " << expected);
  }
}

BOOST_AUTO_TEST_CASE(mixed_form_does_not_lock_for_thin_rods) {
  // Square cantilever (E = 1e7, nu = 0.3, side t) with the Bisshopp-Drucker load P L^2 / EI = 1
  // (elastica reference from elliptic integrals). Shear and extension change the tip by about
  // 0.26 (t/L)^2, so the elastica is the reference to 3e-7 for t/L <= 1e-3, and to 3e-5 at 1e-2.
  const double L = 1.0;
  const Material mat = Material::from_poisson_ratio(1e7, 0.3, 0.0);
  const test::Elastica exact = test::bisshopp_drucker(1.0);
  double mixed_thin[2] = {0, 0};
  for (double t : {1e-2, 1e-3, 1e-4}) {
    RodModel m = test::cantilever(L, Vec3::Ones(), Vec3::Ones());
    m.set_material_and_section(mat, CrossSection::rectangle(t, t));
    m.tip.force = Vec3(0.0, m.bending_torsion_stiffness[0] / (L * L), 0.0);
    double error[2];
    bool converged[2];
    for (RodFormulation f : {RodFormulation::Primal, RodFormulation::Mixed}) {
      RodSolveOptions o;
      o.discretization = {f, 4, 8};
      o.tolerance = 1e-10;
      const RodSolution sol = solve_rod(m, o);
      const int k = f == RodFormulation::Mixed;
      converged[k] = sol.summary.converged();
      error[k] = std::abs(sol.tip().position.y() / L - exact.lateral);
    }
    std::cout << "locking t/L = " << t << ": tip error primal " << error[0] << (converged[0] ? "" : " (not converged)")
              << ", mixed " << error[1] << "\n";
    // Mixed, p = 4, 8 elements: measured 2.3e-5 at t/L = 1e-2 (the shear/extension effect, 2.6e-5),
    // 6.3e-7 and 4.1e-7 at 1e-3 and 1e-4 (the discretisation error at the Greville points was 2.4e-5).
    BOOST_TEST(converged[1]);
    BOOST_TEST(error[1] < 1e-4, "mixed error at t/L = " << t << ": " << error[1]);
    if (t < 5e-3) {
      mixed_thin[t < 5e-4] = error[1];
      // The primal form locks: it fails to converge or is far less accurate (measured 0.2).
      BOOST_TEST((!converged[0] || error[0] > 100 * error[1]), "primal at t/L = " << t << ": " << error[0]);
    }
  }
  // Same accuracy for the same discretisation at t/L = 1e-3 and 1e-4: within 5 % plus the reference's
  // own error at t/L = 1e-3 (shear and extension, 0.26 (t/L)^2 = 2.6e-7; 2.6e-9 at 1e-4). Locking
  // would make the thinner rod's error grow by orders of magnitude (the primal form's: 0.2).
  BOOST_TEST(std::abs(mixed_thin[0] - mixed_thin[1]) < 0.05 * mixed_thin[0] + 0.26e-6,
             "mixed errors " << mixed_thin[0] << " (t/L = 1e-3), " << mixed_thin[1] << " (1e-4)");
}
