// Hard single rods (issue "stress tests of numerical stability"): steel cantilevers over slenderness
// t/L = 1e-1..4e-5 (stiffness ratio EA / (EI / L^2) = 16 (L/t)^2 = 1.6e3..1e10), both formulations,
// under a large lateral tip force, a compressive dead load just below and just above the Euler load of
// a clamped-free column (R4: P_cr = pi^2 EI / (4 L^2)) with a tiny lateral perturbation, and an end
// moment rolling the rod into one and two full loops. What converges is printed as a Markdown table
// (docs/benchmarks.md "Stress tests"). Asserted for every case: a failure is explicit (status + message) and
// leaves finite values; a converged result is finite and satisfies the tip boundary condition.
#define BOOST_TEST_MODULE hard_rods
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include "pcr/rods/rod_solve.hpp"
#include "rods/rod_fixtures.hpp"

using namespace pcr;

namespace {

constexpr double kLength = 1.0;  // [m]
constexpr double kE = 200e9, kG = 80e9;

/// Steel cantilever of diameter t along +z, clamped at the origin, free tip.
RodModel steel_cantilever(double slenderness) {
  const double r = 0.5 * slenderness * kLength;
  RodModel m = test::cantilever(kLength, Vec3::Zero(), Vec3::Zero());
  m.set_material_and_section(Material{kE, kG, 7850.0}, CrossSection::circle(r));
  return m;
}

double bending_stiffness(const RodModel& m) {
  return m.bending_torsion_stiffness[0];
}

struct Case {
  std::string name;
  /// Sets the tip loads; returns a description of the reference for the table.
  std::function<void(RodModel&)> load;
  /// Error of the solution against its reference (relative, see each case).
  std::function<double(const RodModel&, const RodSolution&)> error;
};

/// Beam-column: clamped-free, axial compression P, lateral tip force H; linear tip deflection
/// delta = H / (P k) (tan(kL) - kL), k = sqrt(P / EI) (Timoshenko & Gere, Theory of Elastic
/// Stability, §1.11). Valid while delta / L is small.
double beam_column_deflection(double EI, double P, double H, double L) {
  const double k = std::sqrt(P / EI);
  return H / (P * k) * (std::tan(k * L) - k * L);
}

std::vector<Case> cases() {
  std::vector<Case> c;
  // Lateral dead force alpha = P L^2 / EI = 10: Bisshopp & Drucker's elastica (y_tip / L).
  c.push_back(
      {"lateral force PL^2/EI = 10",
       [](RodModel& m) { m.tip.force = Vec3(10.0 * bending_stiffness(m) / (kLength * kLength), 0, 0); },
       [](const RodModel&, const RodSolution& s) {
         return std::abs(s.tip().position.x() / kLength - test::bisshopp_drucker(10.0).lateral);
       }});
  for (double lambda : {0.95, 1.05}) {
    std::ostringstream name;
    name << "compression " << lambda << " P_cr + 1e-3 lateral";
    c.push_back({name.str(),
                 [lambda](RodModel& m) {
                   const double P = lambda * M_PI * M_PI * bending_stiffness(m) / (4 * kLength * kLength);
                   m.tip.force = Vec3(1e-3 * P, 0.0, -P);
                 },
                 [lambda](const RodModel& m, const RodSolution& s) {
                   const double EI = bending_stiffness(m), P = -m.tip.force.z(), H = m.tip.force.x();
                   const double ref = lambda < 1.0 ? beam_column_deflection(EI, P, H, kLength) / kLength
                                                   : test::clamped_free_elastica_deflection(lambda);
                   return std::abs(std::abs(s.tip().position.x()) / kLength - ref) / ref;  // relative
                 }});
  }
  for (int loops : {1, 2}) {
    // M = 2 pi n EI / L about d1: a circle traversed n times, tip back at the base (|p(L)| / L).
    c.push_back({std::to_string(loops) + (loops == 1 ? " loop" : " loops") + " (end moment)",
                 [loops](RodModel& m) {
                   m.tip.moment = Vec3(2 * M_PI * loops * bending_stiffness(m) / kLength, 0, 0);
                 },
                 [](const RodModel&, const RodSolution& s) { return s.tip().position.norm() / kLength; }});
  }
  return c;
}

bool finite(const RodState& s) {
  return s.position.allFinite() && s.quaternion.allFinite() && s.force.allFinite() && s.moment.allFinite();
}

}  // namespace

BOOST_AUTO_TEST_CASE(slender_stiff_buckling_and_looping_cantilevers) {
  std::ostringstream table;
  table << "\n| t/L | EA L^2/EI | formulation | case | status | iterations | load steps | error |\n"
        << "|---|---|---|---|---|---|---|---|\n";
  int converged = 0, total = 0;
  for (double slenderness : {1e-1, 1e-2, 1e-3, 1e-4, 4e-5}) {
    for (RodFormulation f : {RodFormulation::Mixed, RodFormulation::Primal}) {
      for (const Case& c : cases()) {
        RodModel m = steel_cantilever(slenderness);
        c.load(m);
        RodSolveOptions o;
        // Degree 4, 16 elements: resolves two loops (refined for the loops).
        o.discretization = {f, 4, 16};
        o.tolerance = 1e-10;
        RodSolution sol;
        try {
          sol = solve_rod(m, o);
        } catch (const std::exception& e) {
          BOOST_ERROR("t/L " << slenderness << " " << to_string(f) << " " << c.name << ": exception "
                             << e.what());
          continue;
        }
        ++total;
        const SolveSummary& s = sol.summary;
        const RodState tip = sol.tip();
        BOOST_TEST(sol.x.allFinite(), "t/L " << slenderness << " " << to_string(f) << " " << c.name
                                             << ": non-finite variables, status " << to_string(s.status));
        std::string error = "-";
        if (s.converged()) {
          ++converged;
          BOOST_TEST(finite(tip), c.name << ": converged with a non-finite tip state");
          BOOST_TEST(finite(sol.base()), c.name << ": converged with a non-finite base state");
          // Tip (Neumann) condition n(L) = F, m(L) = M. The residuals are divided by
          // F0 = max(K_BT) / L^2 and M0 = max(K_BT) / L (collocation_rod.hpp) and converged means
          // max-abs <= tolerance (or, at the residuals' round-off, <= residual_round_off): |n(L) - F| <=
          // tolerance F0 (factor 2 for the re-evaluation here) plus round-off 1e-13 |F| (the loads are up
          // to 1e2 F0, ~100 ulp).
          const double F0 = m.bending_torsion_stiffness.maxCoeff() / (kLength * kLength);
          const double M0 = m.bending_torsion_stiffness.maxCoeff() / kLength;
          const double tolerance = std::max(o.tolerance, s.residual_round_off);
          BOOST_TEST((tip.force - m.tip.force).norm() <= 2 * tolerance * F0 + 1e-13 * m.tip.force.norm(),
                     "t/L " << slenderness << " " << to_string(f) << " " << c.name
                            << ": n(L) = " << tip.force.transpose() << " vs " << m.tip.force.transpose());
          BOOST_TEST((tip.moment - m.tip.moment).norm() <= 2 * tolerance * M0 + 1e-13 * m.tip.moment.norm(),
                     "t/L " << slenderness << " " << to_string(f) << " " << c.name
                            << ": m(L) = " << tip.moment.transpose() << " vs " << m.tip.moment.transpose());
          // Clamped base: p(0) = 0, R(0) = I (the Dirichlet rows, scaled by L; same bound).
          BOOST_TEST(sol.base().position.norm() <= 2 * tolerance * kLength);
          std::ostringstream e;
          e.precision(2);
          e << std::scientific << c.error(m, sol);
          error = e.str();
        } else {
          BOOST_TEST(!s.message.empty(), "t/L " << slenderness << " " << to_string(f) << " " << c.name
                                                << ": failure without a message");
        }
        std::ostringstream ratio;
        ratio.precision(2);
        ratio << std::scientific << m.shear_extension_stiffness[2] * kLength * kLength / bending_stiffness(m);
        table << "| " << slenderness << " | " << ratio.str() << " | " << to_string(f) << " | " << c.name
              << " | " << to_string(s.status) << " | " << s.iterations << " | " << sol.load_steps << " | "
              << error << " |\n";
        if (!s.converged()) table << "|  |  |  |  | " << s.message << " |  |  |  |\n";
      }
    }
  }
  BOOST_TEST_MESSAGE(table.str() << converged << "/" << total << " converged");
  // The thick rods (t/L = 0.1, ratio 1.6e3) are well conditioned: the suite must solve something.
  BOOST_TEST(converged > 0);
}
