#include "pcr/math/quaternion.hpp"

#include <cmath>

#include "pcr/core/error.hpp"

namespace pcr {
namespace {

// dR_unit/dq_k is linear in q: fill it for the given q (also gives d^2 R_unit/(dq_k dq_l) with q = e_l).
Mat3 unit_form_derivative(const Quat& q, int k) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  Mat3 D;
  switch (k) {
    case 0: D << w, -z, y, z, w, -x, -y, x, w; break;
    case 1: D << x, y, z, y, -x, -w, z, w, -x; break;
    case 2: D << -y, x, w, x, y, z, -w, z, -y; break;
    default: D << -z, -w, x, w, -z, y, x, y, z; break;
  }
  return 2.0 * D;
}

double checked_squared_norm(const Quat& q) {
  const double s = q.squaredNorm();
  require(s > 0.0 && std::isfinite(s), "rotation_matrix: quaternion must be finite and non-zero, got |q|^2 = ", s);
  return s;
}

}  // namespace

Quat quat_multiply(const Quat& a, const Quat& b) {
  const Vec3 av = a.tail<3>(), bv = b.tail<3>();
  Quat r;
  r[0] = a[0] * b[0] - av.dot(bv);
  r.tail<3>() = a[0] * bv + b[0] * av + av.cross(bv);
  return r;
}

Quat quat_conjugate(const Quat& q) { return Quat(q[0], -q[1], -q[2], -q[3]); }

Quat quat_identity() { return Quat(1.0, 0.0, 0.0, 0.0); }

Quat quat_from_rotation_vector(const Vec3& theta) {
  const double angle = theta.norm();
  const double half = 0.5 * angle;
  // sin(half)/angle -> 1/2 - angle^2/48 for small angles.
  const double s = angle < 1e-8 ? 0.5 - angle * angle / 48.0 : std::sin(half) / angle;
  return Quat(std::cos(half), s * theta[0], s * theta[1], s * theta[2]);
}

Quat quat_from_rotation(const Mat3& R) {
  // Shepperd: pick the largest of 4w^2, 4x^2, 4y^2, 4z^2 to divide by.
  const double t = R.trace();
  Quat q;
  if (t >= R(0, 0) && t >= R(1, 1) && t >= R(2, 2)) {
    const double r = std::sqrt(1.0 + t);
    q << 0.5 * r, (R(2, 1) - R(1, 2)) / (2 * r), (R(0, 2) - R(2, 0)) / (2 * r), (R(1, 0) - R(0, 1)) / (2 * r);
  } else if (R(0, 0) >= R(1, 1) && R(0, 0) >= R(2, 2)) {
    const double r = std::sqrt(1.0 + R(0, 0) - R(1, 1) - R(2, 2));
    q << (R(2, 1) - R(1, 2)) / (2 * r), 0.5 * r, (R(0, 1) + R(1, 0)) / (2 * r), (R(0, 2) + R(2, 0)) / (2 * r);
  } else if (R(1, 1) >= R(2, 2)) {
    const double r = std::sqrt(1.0 - R(0, 0) + R(1, 1) - R(2, 2));
    q << (R(0, 2) - R(2, 0)) / (2 * r), (R(0, 1) + R(1, 0)) / (2 * r), 0.5 * r, (R(1, 2) + R(2, 1)) / (2 * r);
  } else {
    const double r = std::sqrt(1.0 - R(0, 0) - R(1, 1) + R(2, 2));
    q << (R(1, 0) - R(0, 1)) / (2 * r), (R(0, 2) + R(2, 0)) / (2 * r), (R(1, 2) + R(2, 1)) / (2 * r), 0.5 * r;
  }
  if (q[0] < 0) q = -q;
  return q.normalized();
}

Mat3 rotation_unit_form(const Quat& q) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  Mat3 A;
  A << w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y),  //
      2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x),    //
      2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z;
  return A;
}

Mat3 rotation_matrix(const Quat& q) { return rotation_unit_form(q) / checked_squared_norm(q); }

void rotation_matrix_derivatives(const Quat& q, Mat3& R, QuatRotationJacobian& dR) {
  // R = A / S with S = |q|^2:  dR/dq_k = A_k / S - 2 q_k A / S^2.
  const double S = checked_squared_norm(q);
  const Mat3 A = rotation_unit_form(q);
  R = A / S;
  for (int k = 0; k < 4; ++k) dR[k] = (unit_form_derivative(q, k) - 2.0 * q[k] * R) / S;
}

void rotation_matrix_second_derivatives(const Quat& q, Mat3& R, QuatRotationJacobian& dR,
                                        QuatRotationHessian& d2R) {
  // d2R/dq_k dq_l = A_kl / S - 2 (q_l A_k + q_k A_l) / S^2 - A (2 delta_kl / S^2 - 8 q_k q_l / S^3).
  const double S = checked_squared_norm(q);
  const Mat3 A = rotation_unit_form(q);
  std::array<Mat3, 4> Ak;
  for (int k = 0; k < 4; ++k) Ak[k] = unit_form_derivative(q, k);
  R = A / S;
  for (int k = 0; k < 4; ++k) dR[k] = (Ak[k] - 2.0 * q[k] * R) / S;
  for (int k = 0; k < 4; ++k) {
    for (int l = k; l < 4; ++l) {
      const Mat3 Akl = unit_form_derivative(Quat::Unit(l), k);
      const double delta = k == l ? 1.0 : 0.0;
      d2R[k][l] = Akl / S - 2.0 * (q[l] * Ak[k] + q[k] * Ak[l]) / (S * S) -
                  A * (2.0 * delta / (S * S) - 8.0 * q[k] * q[l] / (S * S * S));
      d2R[l][k] = d2R[k][l];
    }
  }
}

}  // namespace pcr
