#pragma once
// Analytic reference solutions and rod set-ups shared by the rod tests.
#include <cmath>

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>

#include "pcr/math/quaternion.hpp"
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
  return e3 * std::sin(ws) / w + a.cross(e3) * (1.0 - std::cos(ws)) / w +
         a * a.dot(e3) * (s - std::sin(ws) / w);
}

inline Mat3 constant_curvature_rotation(const Vec3& kappa, double s) {
  return so3_exp(s * kappa);
}

/// The helical spring of Weeger et al. 2017 §7: a stress-free helix of radius R = 0.01 and pitch
/// angle alpha (3 coils, EI = 2e-3, GJ = 1.5e-3) as intrinsic curvature kappa0 = (k, 0, tau) with
/// k = cos^2(alpha)/R, tau = sin(alpha) cos(alpha)/R, the point of its axis nearest the reference tip
/// (the axis passes through (a x e3) / |kappa0|), and the classical compliance along the axis
/// delta / F = R^2 L (cos^2 alpha / GJ + sin^2 alpha / EI) (inextensible, unshearable).
struct HelicalSpring {
  double radius = 0.01, length = 0.0, EI = 2e-3, GJ = 1.5e-3, compliance = 0.0;
  Vec3 kappa0, axis, tip_ref, on_axis;
  /// Clamped at the origin, free tip, stress-free in the helix; axial/shear stiffness
  /// stiffness_ratio * EI / R^2. The dead tip load F along the axis acts through the axis point.
  RodModel model(double stiffness_ratio, double F) const {
    RodModel m =
        cantilever(length, Vec3::Constant(stiffness_ratio * EI / (radius * radius)), Vec3(EI, EI, GJ));
    m.intrinsic.curvature = kappa0;
    m.tip.force = F * axis;
    m.tip.moment = (on_axis - tip_ref).cross(F * axis);
    return m;
  }
};

inline HelicalSpring helical_spring(double alpha_deg) {
  HelicalSpring h;
  const double alpha = alpha_deg * M_PI / 180.0, R = h.radius, coils = 3;
  h.length = coils * 2 * M_PI * R / std::cos(alpha);
  h.kappa0 = Vec3(std::cos(alpha) * std::cos(alpha) / R, 0.0, std::sin(alpha) * std::cos(alpha) / R);
  h.axis = h.kappa0.normalized();
  h.tip_ref = constant_curvature_position(h.kappa0, h.length);
  const Vec3 c0 = h.axis.cross(Vec3::UnitZ()) / h.kappa0.norm();
  h.on_axis = c0 + h.axis * h.axis.dot(h.tip_ref - c0);
  h.compliance = R * R * h.length *
                 (std::cos(alpha) * std::cos(alpha) / h.GJ + std::sin(alpha) * std::sin(alpha) / h.EI);
  return h;
}

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
  return {1 - std::sqrt(2 * std::sin(t0) / alpha),
          1 - 2 * (ellint_2(k) - ellint_2(k, phi1)) / std::sqrt(alpha), t0};
}

/// Post-buckled inextensible elastica of the clamped-free column under P = lambda P_cr:
/// sqrt(lambda) = 2 K(k) / pi with k = sin(theta0 / 2); tip lateral deflection delta / L = 2 k / K(k)
/// (Timoshenko & Gere §2.7). Solved for k by bisection (K increases with k).
inline double clamped_free_elastica_deflection(double lambda) {
  double a = 0.0, b = 1.0 - 1e-15;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (a + b);
    (2.0 * boost::math::ellint_1(mid) / M_PI < std::sqrt(lambda) ? a : b) = mid;
  }
  const double k = 0.5 * (a + b);
  return 2.0 * k / boost::math::ellint_1(k);
}

/// A cantilever with every end and distributed load, an intrinsic curvature and shear-extension, and
/// the given end kinds (the prescribed tip frame is used by clamped, collar and spherical tips).
inline RodModel loaded_rod(RodEndKind base, RodEndKind tip) {
  RodModel m = cantilever(0.7, Vec3(3e3, 2e3, 5e3), Vec3(2.0, 1.5, 1.2));
  m.base.kind = base;
  m.tip.kind = tip;
  m.base.orientation = quat_from_rotation_vector(Vec3(0.1, -0.2, 0.05));
  m.tip.position = Vec3(0.1, 0.05, 0.6);
  m.tip.orientation = quat_from_rotation_vector(Vec3(0.3, 0.1, -0.2));
  m.tip.force = Vec3(0.3, -0.2, 0.1);
  m.tip.moment = Vec3(0.05, 0.1, -0.02);
  m.base.force = Vec3(-0.1, 0.2, 0.0);
  m.base.moment = Vec3(0.02, 0.0, 0.03);
  m.mass_per_length = 0.2;
  m.loads.gravity = Vec3(0, -9.81, 0);
  m.loads.moment_per_length = Vec3(0.01, 0.02, -0.01);
  m.intrinsic.curvature = Vec3(0.3, -0.1, 0.2);
  m.intrinsic.shear_extension = Vec3(0.001, 0.0, 0.002);
  return m;
}

/// loaded_rod without distributed loads (gravity, moment per length): what the condensed form takes.
inline RodModel end_loaded_rod(RodEndKind base, RodEndKind tip) {
  RodModel m = loaded_rod(base, tip);
  m.loads.gravity.setZero();
  m.loads.moment_per_length.setZero();
  return m;
}

}  // namespace pcr::test
