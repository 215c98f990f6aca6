// Universal and revolute rod ends for the shooting solvers (see pcr/rods/shooting/joint_ends.hpp).
#include "pcr/rods/shooting/joint_ends.hpp"

#include <algorithm>
#include <cmath>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/rods/end_axes.hpp"

namespace pcr {
namespace joint_end {
namespace {

bool universal(const Axes& axes) {
  return axes.kind == RodEndKind::Universal;
}

// dq = 1/2 q (x) [0, omega] for a body rotation omega.
Quat rotated(const Quat& q, const Vec3& omega) {
  return 0.5 * quat_multiply(q, Quat(0.0, omega[0], omega[1], omega[2]));
}

// The moment the joint transmits (world) for the rod frame R and the unknowns mu = z[3..5] (universal:
// z[5] along t; revolute: z[4], z[5] along R_T c1, R_T c2).
Vec3 joint_moment(const Axes& axes, const Mat3& R_T, const Mat3& R, const Vec6& z) {
  if (universal(axes)) return z[5] * (R_T * axes.a).cross(R * axes.b);
  return R_T * (z[4] * axes.c1 + z[5] * axes.c2);
}

// Revolute tip orientation: v = R_T^T R a and the gain g = sqrt(2 / (1 + a . v)).
double revolute_gain(const Axes& axes, const Vec3& v) {
  return std::sqrt(2.0 / std::max(1.0 + axes.a.dot(v), 1e-12));
}

}  // namespace

bool is_joint(RodEndKind kind) {
  return kind == RodEndKind::Universal || kind == RodEndKind::Revolute;
}

Axes axes_of(RodEndKind kind, const Vec3& axis, const std::string& who) {
  require(is_joint(kind), who, ": a ", to_string(kind), " end has no joint axes");
  require(axis.allFinite() && axis.norm() > 1e-12, who, ": ", to_string(kind), " axis [", axis.transpose(),
          "] is not a finite non-zero vector");
  require(kind != RodEndKind::Universal || sine_to_tangent(axis) >= kMinJointAxisSine, who,
          ": universal axis [", axis.transpose(),
          "] is along the rod tangent (the end frame's z axis); the second axis e3 x a is undefined");
  // The same axes as the collocation end equations (end_axes.hpp): [a, c1, c2], b = c1.
  const Mat3 frame = joint_axes(axis);
  Axes axes;
  axes.kind = kind;
  axes.a = frame.col(0);
  axes.b = axes.c1 = frame.col(1);
  axes.c2 = frame.col(2);
  return axes;
}

Quat relative_rotation(const Axes& axes, double theta1, double theta2) {
  const Quat first = quat_from_rotation_vector(theta1 * axes.a);
  if (!universal(axes)) return first;
  return quat_multiply(first, quat_from_rotation_vector(theta2 * axes.b));
}

void joint_angles(const Axes& axes, const Mat3& R_rel, double& theta1, double& theta2) {
  const Vec3& a = axes.a;
  if (!universal(axes)) {
    // R_a(theta) c1 = cos(theta) c1 + sin(theta) c2.
    const Vec3 c = R_rel * axes.c1;
    theta1 = std::atan2(c.dot(axes.c2), c.dot(axes.c1));
    theta2 = 0.0;
    return;
  }
  // R_rel b = R_a(theta1) b = cos(theta1) b + sin(theta1) (a x b); then R_a(-theta1) R_rel = R_b(theta2)
  // with R_b(theta2) a = cos(theta2) a + sin(theta2) (b x a).
  const Vec3& b = axes.b;
  const Vec3 rb = R_rel * b;
  theta1 = std::atan2(rb.dot(a.cross(b)), rb.dot(b));
  const Vec3 ra = rotation_matrix(quat_from_rotation_vector(-theta1 * a)) * (R_rel * a);
  theta2 = std::atan2(ra.dot(b.cross(a)), ra.dot(a));
}

void base_state(const Axes& axes, const Vec3& p_T, const Quat& q_T, const Vec3& applied_moment, const Vec6& z,
                RodStateVector& y0, BaseTangents* dy_dz, FrameTangents* dy_dframe) {
  const Quat qT = q_T.normalized();
  const Quat q = quat_multiply(qT, relative_rotation(axes, z[3], z[4])).normalized();
  const Mat3 R_T = rotation_matrix(qT), R = rotation_matrix(q);
  const Vec3 m_joint = joint_moment(axes, R_T, R, z);
  y0 << p_T, q, z.head<3>(), -(applied_moment + m_joint);
  if (dy_dz) {
    BaseTangents& T = *dy_dz;
    T.setZero();
    T.block<3, 3>(RodStateIndex::n, 0).setIdentity();
    const Vec3 a_world = R_T * axes.a;
    // theta1: the world rotation about R_T a, omega_body = R^T R_T a.
    T.col(3).segment<4>(RodStateIndex::q) = rotated(q, R.transpose() * a_world);
    if (universal(axes)) {
      // theta2: the body rotation about b (t unchanged); theta1 turns R b about R_T a, dt = -R b.
      T.col(4).segment<4>(RodStateIndex::q) = rotated(q, axes.b);
      T.col(3).segment<3>(RodStateIndex::m) = z[5] * (R * axes.b);
      T.col(5).segment<3>(RodStateIndex::m) = -a_world.cross(R * axes.b);
    } else {
      T.col(4).segment<3>(RodStateIndex::m) = -(R_T * axes.c1);
      T.col(5).segment<3>(RodStateIndex::m) = -(R_T * axes.c2);
    }
  }
  if (dy_dframe) {
    // The frame turned by omega (world): R <- exp(hat(omega)) R, m_joint turns along.
    FrameTangents& F = *dy_dframe;
    F.setZero();
    for (int k = 0; k < 3; ++k) {
      F.col(k).segment<4>(RodStateIndex::q) = rotated(q, R.transpose().col(k));
      F.col(k).segment<3>(RodStateIndex::m) = -Vec3::Unit(k).cross(m_joint);
    }
  }
}

Vec6 base_unknowns(const Axes& axes, const Quat& q_T, const Vec3& applied_moment, const RodStateVector& y0) {
  const Quat qT = q_T.normalized();
  const Mat3 R_T = rotation_matrix(qT);
  double theta1 = 0.0, theta2 = 0.0;
  joint_angles(axes, R_T.transpose() * rotation_matrix(Quat(y0.segment<4>(RodStateIndex::q))), theta1,
               theta2);
  const Mat3 R = R_T * rotation_matrix(relative_rotation(axes, theta1, theta2));
  const Vec3 m_joint = -(y0.segment<3>(RodStateIndex::m) + applied_moment);
  Vec6 z;
  z.head<3>() = y0.segment<3>(RodStateIndex::n);
  if (universal(axes)) {
    z.tail<3>() << theta1, theta2, m_joint.dot((R_T * axes.a).cross(R * axes.b));
  } else {
    z.tail<3>() << theta1, m_joint.dot(R_T * axes.c1), m_joint.dot(R_T * axes.c2);
  }
  return z;
}

Vec3 unknown_scale(const Axes& axes, double moment_scale) {
  return universal(axes) ? Vec3(1.0, 1.0, moment_scale) : Vec3(1.0, moment_scale, moment_scale);
}

Vec3 tip_rows(const Axes& axes, const Mat3& R_T, const Mat3& R, const Vec3& m_joint) {
  const Vec3 a_world = R_T * axes.a;
  if (universal(axes)) {
    const Vec3 rb = R * axes.b;
    return Vec3(a_world.dot(rb), m_joint.dot(a_world), m_joint.dot(rb));
  }
  const Vec3 v = R_T.transpose() * (R * axes.a);
  const double g = revolute_gain(axes, v);
  return Vec3(-g * v.dot(axes.c2), g * v.dot(axes.c1), m_joint.dot(a_world));
}

Vec3 tip_rows_derivative(const Axes& axes, const Mat3& R_T, const Mat3& R, const Vec3& m_joint,
                         const Vec3& omega_body, const Vec3& dm) {
  const Vec3 a_world = R_T * axes.a;
  if (universal(axes)) {
    const Vec3 rb = R * axes.b, drb = R * omega_body.cross(axes.b);
    return Vec3(a_world.dot(drb), dm.dot(a_world), dm.dot(rb) + m_joint.dot(drb));
  }
  const Vec3 v = R_T.transpose() * (R * axes.a);
  const Vec3 dv = R_T.transpose() * (R * omega_body.cross(axes.a));
  const double g = revolute_gain(axes, v);
  const double dg = -0.5 * g / std::max(1.0 + axes.a.dot(v), 1e-12) * axes.a.dot(dv);
  return Vec3(-dg * v.dot(axes.c2) - g * dv.dot(axes.c2), dg * v.dot(axes.c1) + g * dv.dot(axes.c1),
              dm.dot(a_world));
}

Vec3 tip_row_scale(const Axes& axes, double moment_scale) {
  return universal(axes) ? Vec3(1.0, moment_scale, moment_scale) : Vec3(1.0, 1.0, moment_scale);
}

}  // namespace joint_end
}  // namespace pcr
