#pragma once
// The joint axes of universal and revolute rod ends (docs/design.md §1), shared by the end equations,
// the rod's well-posedness check and the robot's rank check. All vectors in the end's attachment frame
// (the rod frame at that end when the joint is at zero), whose z axis is the rod tangent.
#include <cmath>

#include "pcr/core/types.hpp"
#include "pcr/rods/rod_model.hpp"

namespace pcr {

/// A universal axis must make at least this sine with the attachment z axis (the rod tangent): the
/// second axis b = e3 x a / |e3 x a| is undefined along it, and ill-conditioned near it.
constexpr double kMinJointAxisSine = 1e-6;

/// sin of the angle between a (any non-zero length) and the attachment z axis.
inline double sine_to_tangent(const Vec3& a) {
  return Vec3::UnitZ().cross(a).norm() / a.norm();
}

/// Orthonormal joint axes [a, c1, c2] (columns, right-handed) from the joint axis a (normalised here):
/// c1 = e3 x a / |e3 x a| (with e1 x a when a is along z), re-orthogonalised against a, c2 = a x c1.
/// Universal: the second axis b = c1 (fixed in the rod's body frame); revolute: c1, c2 span the
/// rotations the pin blocks.
inline Mat3 joint_axes(const Vec3& axis) {
  const Vec3 a = axis.normalized();
  Vec3 c1 = (sine_to_tangent(a) >= kMinJointAxisSine ? Vec3::UnitZ() : Vec3::UnitX()).cross(a);
  c1 = (c1 - c1.dot(a) * a).normalized();
  Mat3 axes;
  axes << a, c1, a.cross(c1);
  return axes;
}

/// Rows (one per blocked direction) on the relative angular velocity w_rod - w_link (world) that a
/// coupling forbids when the rod frame at the end equals the attachment frame R (world): clamped I (3),
/// collar the rows d1^T, d2^T of R (2), revolute (R c1)^T, (R c2)^T (2), universal the normal of the
/// two joint axes (R (a x b))^T (1), spherical and free none. With the 3 position rows of an attached
/// end these are the kinematic_constraint_count constraints (6, 5, 5, 4, 3, 0).
inline MatX blocked_rotations(RodEndKind kind, const Mat3& R, const Vec3& axis) {
  switch (kind) {
    case RodEndKind::Clamped: return Mat3::Identity();
    case RodEndKind::Collar: return R.leftCols<2>().transpose();
    case RodEndKind::Revolute: return (R * joint_axes(axis).rightCols<2>()).transpose();
    case RodEndKind::Universal: return (R * joint_axes(axis).col(2)).transpose();
    case RodEndKind::Spherical:
    case RodEndKind::Free: return MatX::Zero(0, 3);
  }
  return MatX::Zero(0, 3);
}

/// Whether the coupling holds the rod's twist about its own tangent: clamped, universal, and revolute
/// with the pin axis not along the tangent (a pin along it is a swivel).
inline bool holds_twist(RodEndKind kind, const Vec3& axis) {
  switch (kind) {
    case RodEndKind::Clamped:
    case RodEndKind::Universal: return true;
    case RodEndKind::Revolute: return sine_to_tangent(axis) >= kMinJointAxisSine;
    default: return false;
  }
}

}  // namespace pcr
