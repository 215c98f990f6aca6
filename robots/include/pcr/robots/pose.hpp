#pragma once
// A rigid transform (position + unit quaternion), as used for URDF origins, link poses and rod
// attachment frames. A pose "of frame B in frame A" maps B coordinates to A coordinates:
// x_A = position + R(orientation) x_B.
#include "pcr/core/types.hpp"

namespace pcr {

struct Pose {
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat(1.0, 0.0, 0.0, 0.0);  ///< unit quaternion [w, x, y, z]

  static Pose identity() { return Pose{}; }
  /// URDF origin: translation xyz, rotation R = Rz(yaw) Ry(pitch) Rx(roll) with rpy = (roll, pitch, yaw).
  static Pose from_xyz_rpy(const Vec3& xyz, const Vec3& rpy);
  /// R(orientation) (normalised, so a non-unit quaternion still gives a rotation).
  Mat3 rotation() const;
  /// URDF roll, pitch, yaw of the rotation (pitch in [-pi/2, pi/2]; roll = 0 at gimbal lock).
  Vec3 rpy() const;
  /// Composition: (A_from_B * B_from_C) = A_from_C.
  Pose operator*(const Pose& other) const;
  /// B_from_A for this = A_from_B.
  Pose inverse() const;
  /// A point given in the child frame, expressed in the parent frame: position + R x.
  Vec3 transform_point(const Vec3& point) const;
};

}  // namespace pcr
