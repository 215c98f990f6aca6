#include "pcr/math/so3.hpp"

#include <algorithm>
#include <cmath>

namespace pcr {

Mat3 hat(const Vec3& v) {
  Mat3 S;
  S << 0, -v[2], v[1], v[2], 0, -v[0], -v[1], v[0], 0;
  return S;
}

Vec3 vee(const Mat3& S) {
  return 0.5 * Vec3(S(2, 1) - S(1, 2), S(0, 2) - S(2, 0), S(1, 0) - S(0, 1));
}

Mat3 so3_exp(const Vec3& theta) {
  const double a2 = theta.squaredNorm();
  const double a = std::sqrt(a2);
  // exp(hat t) = I + A hat(t) + B hat(t)^2, A = sin a / a, B = (1 - cos a) / a^2.
  double A, B;
  if (a < 1e-4) {
    A = 1.0 - a2 / 6.0 + a2 * a2 / 120.0;
    B = 0.5 - a2 / 24.0 + a2 * a2 / 720.0;
  } else {
    A = std::sin(a) / a;
    B = (1.0 - std::cos(a)) / a2;
  }
  const Mat3 K = hat(theta);
  return Mat3::Identity() + A * K + B * K * K;
}

Vec3 so3_log(const Mat3& R) {
  // 2 sin(a) axis = vee(R - R^T) * 2 / 2 ... with s = |w| = sin a, c = cos a = (tr R - 1) / 2.
  const Vec3 w = vee(R);  // = sin(a) * axis
  const double s = w.norm();
  const double c = std::clamp(0.5 * (R.trace() - 1.0), -1.0, 1.0);
  const double a = std::atan2(s, c);
  if (a < 1e-4) {
    // a / sin a = 1 + a^2 / 6 + ...
    return (1.0 + a * a / 6.0) * w;
  }
  if (a < M_PI - 1e-3) return (a / s) * w;
  // Near pi the skew part vanishes: take the axis from the symmetric part
  // (R + R^T) / 2 - c I = (1 - c) axis axis^T, with its sign from w.
  const Mat3 B = 0.5 * (R + R.transpose()) - c * Mat3::Identity();
  int i = 0;
  B.diagonal().maxCoeff(&i);
  Vec3 axis = B.col(i) / std::sqrt(std::max(B(i, i), 1e-300));
  axis.normalize();
  if (axis.dot(w) < 0) axis = -axis;
  return a * axis;
}

double rotation_angle_between(const Mat3& Ra, const Mat3& Rb) { return so3_log(Ra.transpose() * Rb).norm(); }

Mat3 rotation_x(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Mat3 R;
  R << 1, 0, 0, 0, c, -s, 0, s, c;
  return R;
}

Mat3 rotation_y(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Mat3 R;
  R << c, 0, s, 0, 1, 0, -s, 0, c;
  return R;
}

Mat3 rotation_z(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Mat3 R;
  R << c, -s, 0, s, c, 0, 0, 0, 1;
  return R;
}

Mat3 rotation_from_rpy(double roll, double pitch, double yaw) {
  return rotation_z(yaw) * rotation_y(pitch) * rotation_x(roll);
}

}  // namespace pcr
