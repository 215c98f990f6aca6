#pragma once
// Analytic reference solutions and rod set-ups shared by the rod tests.
#include <cmath>

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>

#include "pcr/math/so3.hpp"
#include "pcr/rods/rod_model.hpp"

namespace pcr::test {

/// Straight rod along +z from the origin, clamped at the base (R = I), free tip; diagonal stiffnesses.
inline RodModel cantilever(double length, const Vec3& k_se, const Vec3& k_bt) {
  RodModel m;
  m.name = "cantilever";
  m.length = length;
  m.shear_extension_stiffness = k_se;
  m.bending_torsion_stiffness = k_bt;
  m.base.kind = RodEndKind::Clamped;
  m.tip.kind = RodEndKind::Free;
  return m;
}

/// Centerline of the rod with constant body curvature kappa (and no extension/shear) from the origin
/// with R(0) = I: p(s) = integral_0^s exp(t hat(kappa)) e3 dt, in closed form (Rodrigues):
/// with w = |kappa|, a = kappa / w:  p = e3 sin(ws)/w + (a x e3)(1 - cos(ws))/w + a (a.e3)(s - sin(ws)/w).
inline Vec3 constant_curvature_position(const Vec3& kappa, double s) {
  const double w = kappa.norm();
  if (w < 1e-300) return s * Vec3::UnitZ();
  const Vec3 a = kappa / w, e3 = Vec3::UnitZ();
  const double ws = w * s;
  return e3 * std::sin(ws) / w + a.cross(e3) * (1.0 - std::cos(ws)) / w + a * a.dot(e3) * (s - std::sin(ws) / w);
}

inline Mat3 constant_curvature_rotation(const Vec3& kappa, double s) { return so3_exp(s * kappa); }

/// Tip of the inextensible elastica cantilever under a perpendicular dead tip force (Bisshopp &
/// Drucker 1945) for alpha = P L^2 / EI, from its elliptic-integral solution: with the tip angle t0,
/// k^2 = (1 + sin t0) / 2 and sin(phi1) = 1 / (sqrt(2) k), t0 solves sqrt(alpha) = K(k) - F(k, phi1);
/// then x/L = sqrt(2 sin(t0) / alpha) and y/L = 1 - 2 (E(k) - E(k, phi1)) / sqrt(alpha).
struct Elastica {
  double axial, lateral, angle;  ///< (L - x)/L, y/L, tip angle
};

inline Elastica bisshopp_drucker(double alpha) {
  using boost::math::ellint_1;
  using boost::math::ellint_2;
  auto parts = [](double t0, double& k, double& phi1) {
    k = std::sqrt((1 + std::sin(t0)) / 2);
    phi1 = std::asin(1 / (std::sqrt(2.0) * k));
  };
  auto g = [&](double t0) {
    double k, phi1;
    parts(t0, k, phi1);
    return ellint_1(k) - ellint_1(k, phi1) - std::sqrt(alpha);
  };
  double a = 1e-12, b = M_PI / 2 - 1e-12;  // g(a) < 0 < g(b) for alpha > 0: bisection to round-off
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (a + b);
    (g(a) * g(mid) <= 0 ? b : a) = mid;
  }
  const double t0 = 0.5 * (a + b);
  double k, phi1;
  parts(t0, k, phi1);
  return {1 - std::sqrt(2 * std::sin(t0) / alpha), 1 - 2 * (ellint_2(k) - ellint_2(k, phi1)) / std::sqrt(alpha), t0};
}

}  // namespace pcr::test
