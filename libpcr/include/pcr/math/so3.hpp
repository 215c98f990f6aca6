#pragma once
// The rotation group SO(3): hat/vee, exponential and logarithm, rotation error measures.
#include "pcr/core/types.hpp"

namespace pcr {

/// hat(v) w = v x w.
Mat3 hat(const Vec3& v);
/// Inverse of hat on the skew-symmetric part: vee(S) = [S(2,1), S(0,2), S(1,0)] of (S - S^T) / 2.
Vec3 vee(const Mat3& S);

/// exp(hat(theta)) by Rodrigues' formula (Taylor series for |theta| < 1e-4).
Mat3 so3_exp(const Vec3& theta);
/// Rotation vector theta with |theta| in [0, pi] and exp(hat(theta)) = R; accurate near 0 and near pi.
Vec3 so3_log(const Mat3& R);

/// Angle in [0, pi] of the relative rotation Ra^T Rb (geodesic distance on SO(3)).
double rotation_angle_between(const Mat3& Ra, const Mat3& Rb);
/// Rotation about the x, y or z axis by angle (rad).
Mat3 rotation_x(double angle);
Mat3 rotation_y(double angle);
Mat3 rotation_z(double angle);
/// URDF convention: R = Rz(yaw) Ry(pitch) Rx(roll).
Mat3 rotation_from_rpy(double roll, double pitch, double yaw);

}  // namespace pcr
