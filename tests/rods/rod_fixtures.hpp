#pragma once
// Analytic reference solutions and rod set-ups shared by the rod tests.
#include <cmath>

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

}  // namespace pcr::test
