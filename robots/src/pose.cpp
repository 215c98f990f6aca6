#include "pcr/robots/pose.hpp"

#include <algorithm>
#include <cmath>

#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"

namespace pcr {

Pose Pose::from_xyz_rpy(const Vec3& xyz, const Vec3& rpy) {
  return Pose{xyz, quat_from_rotation(rotation_from_rpy(rpy[0], rpy[1], rpy[2]))};
}

Mat3 Pose::rotation() const {
  return rotation_matrix(orientation);
}

Vec3 Pose::rpy() const {
  // R = Rz(y) Ry(p) Rx(r): R20 = -sin p, R21 = cos p sin r, R22 = cos p cos r, R10 = sin y cos p,
  // R00 = cos y cos p.
  const Mat3 R = rotation();
  const double sin_pitch = std::clamp(-R(2, 0), -1.0, 1.0);
  const double pitch = std::asin(sin_pitch);
  if (std::abs(sin_pitch) > 1.0 - 1e-12) {
    // Gimbal lock: only yaw -/+ roll is defined; take roll = 0, then R01 = -sin y, R11 = cos y.
    return Vec3(0.0, pitch, std::atan2(-R(0, 1), R(1, 1)));
  }
  return Vec3(std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0)));
}

Pose Pose::operator*(const Pose& other) const {
  const Quat q = quat_multiply(orientation, other.orientation);
  return Pose{transform_point(other.position), q / q.norm()};
}

Pose Pose::inverse() const {
  const Quat q = quat_conjugate(orientation) / orientation.norm();
  return Pose{-(rotation().transpose() * position), q};
}

Vec3 Pose::transform_point(const Vec3& point) const {
  return position + rotation() * point;
}

}  // namespace pcr
