#pragma once
// Set-ups shared by the single-rod shooting tests (the test_shooting module): tight reference settings,
// the R2 cantilever of the Bisshopp-Drucker table, small checks. Rods: pcr::test::cantilever
// (rods/rod_fixtures.hpp).
#include <boost/test/unit_test.hpp>

#include "pcr/rods/shooting/rod_shooting.hpp"
#include "rods/rod_fixtures.hpp"

namespace pcr::shooting_test {

/// Tight settings for reference solutions: local error 1e-12 per step, residual 1e-12 (scaled).
inline ShootingOptions tight_options() {
  ShootingOptions o;
  o.integration_relative_tolerance = 1e-12;
  o.integration_absolute_tolerance = 1e-14;
  o.tolerance = 1e-12;
  return o;
}

inline double max_abs(const Vec3& v) {
  return v.cwiseAbs().maxCoeff();
}

inline bool all_finite(const ShootingState& x) {
  return x.p.allFinite() && x.q.allFinite() && x.n.allFinite() && x.m.allFinite();
}

/// The global error of Dormand-Prince at integration_relative_tolerance = 1e-12 over the few hundred
/// steps of these rods is bounded by (steps) x 1e-12 < 1e-9 relative to the rod length (measured: ~1e-13).
constexpr double kTightIntegration = 1e-9;

/// R2 cantilever: axis e3 (the table's x), force P along e1 (the table's y), EI = 1, L = 1, and
/// EA = GA = 1e8 EI / L^2: the inextensible, unshearable limit up to strains P / EA <= 1.5e-7.
constexpr double kR2AxialStiffness = 1e8;
inline RodModel bisshopp_drucker(double alpha) {
  RodModel rod = test::cantilever(1.0, Vec3::Constant(kR2AxialStiffness), Vec3(1, 1, 1));
  rod.tip.force = Vec3(alpha, 0, 0);
  return rod;
}

}  // namespace pcr::shooting_test
