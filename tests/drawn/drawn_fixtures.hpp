#pragma once
// Rods shared by the drawn-rod tests: the steel wire of the drawn-rod references (E = 200 GPa,
// nu = 0.3, rho = 7850 kg/m^3, solid circle, k = 1).
#include "pcr/math/quaternion.hpp"
#include "pcr/rods/rod_model.hpp"

namespace pcr::test {

inline RodModel steel_wire(double radius, double length) {
  RodModel m;
  m.name = "wire";
  m.length = length;
  m.set_material_and_section(Material::from_poisson_ratio(200e9, 0.3, 7850.0), CrossSection::circle(radius));
  m.base.kind = RodEndKind::Clamped;
  m.tip.kind = RodEndKind::Free;
  return m;
}

/// A 3D cantilever of the steel wire (r = 1 mm, L = 0.4 m): turned base frame, constant intrinsic
/// strains, gravity, a dead tip force and moment. The tip force is about 1 N: rho A c^2 = 0.22 N at
/// c = 3 m/s, some 20 % of it.
inline RodModel bent_cantilever(double drawing_speed) {
  RodModel m = steel_wire(1e-3, 0.4);
  m.name = "bent";
  m.base.position = Vec3(0.05, -0.02, 0.1);
  m.base.orientation = Quat(0.9, 0.1, 0.3, -0.2).normalized();
  m.intrinsic.curvature = Vec3(1.5, -0.5, 0.8);
  m.intrinsic.shear_extension = Vec3(0.0, 0.0, 1e-4);
  m.loads.gravity = Vec3(0.0, 0.0, -9.81);
  m.tip.force = Vec3(0.4, -0.3, -0.8);
  m.tip.moment = Vec3(0.02, 0.01, -0.015);
  m.drawing_speed = drawing_speed;
  return m;
}

}  // namespace pcr::test
