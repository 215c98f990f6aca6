#include "shooting_ends.hpp"

#include <cmath>

#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/rods/shooting/joint_ends.hpp"

namespace pcr {
namespace shooting {
namespace {

// The axes of a universal or revolute end (checked with the rod's name by solve_rod_shooting).
joint_end::Axes axes_of(const RodEnd& end) {
  return joint_end::axes_of(end.kind, end.axis, "shooting rod end");
}

Quat times_pure(const Quat& a, const Vec3& u) {
  return quat_multiply(a, Quat(0.0, u[0], u[1], u[2]));
}

bool prescribes_pose(RodEndKind kind) {
  return kind != RodEndKind::Free;
}

}  // namespace

Quat quat_between(const Vec3& a, const Vec3& b) {
  const double c = a.dot(b);
  if (c < -1.0 + 1e-12) {
    // Half turn about any axis perpendicular to a.
    Vec3 axis = a.cross(Vec3::UnitX());
    if (axis.norm() < 1e-6) axis = a.cross(Vec3::UnitY());
    axis.normalize();
    return Quat(0.0, axis[0], axis[1], axis[2]);
  }
  const Vec3 v = a.cross(b);
  return Quat(1.0 + c, v[0], v[1], v[2]).normalized();
}

RodModel model_at_load(const RodModel& model, double lambda, const RodStateVector* unloaded_tip) {
  RodModel m = model;
  m.loads.gravity *= lambda;
  m.loads.force_per_length *= lambda;
  m.loads.moment_per_length *= lambda;
  for (RodEnd* end : {&m.base, &m.tip}) {
    end->force *= lambda;
    end->moment *= lambda;
  }
  if (unloaded_tip && prescribes_pose(m.tip.kind)) {
    const Vec3 p_free = unloaded_tip->segment<3>(RodStateIndex::p);
    const Mat3 R_free = rotation_matrix(unloaded_tip->segment<4>(RodStateIndex::q));
    const Mat3 R_bar = rotation_matrix(model.tip.orientation);
    m.tip.position = p_free + lambda * (model.tip.position - p_free);
    if (m.tip.kind == RodEndKind::Collar) {
      // Only the axis matters: turn d3 along the great circle.
      const Vec3 d3_free = R_free.col(2), d3_bar = R_bar.col(2);
      const Mat3 turn = so3_exp(lambda * so3_log(rotation_matrix(quat_between(d3_free, d3_bar))));
      m.tip.orientation = quat_from_rotation(turn * R_free);
    } else {
      m.tip.orientation = quat_from_rotation(R_free * so3_exp(lambda * so3_log(R_free.transpose() * R_bar)));
    }
  }
  return m;
}

void enforce_base(const RodEnd& base, RodStateVector& y0) {
  auto p = y0.segment<3>(RodStateIndex::p);
  auto q = y0.segment<4>(RodStateIndex::q);
  auto n = y0.segment<3>(RodStateIndex::n);
  auto m = y0.segment<3>(RodStateIndex::m);
  q.normalize();
  switch (base.kind) {
    case RodEndKind::Clamped:
      p = base.position;
      q = base.orientation.normalized();
      break;
    case RodEndKind::Collar: {
      p = base.position;
      const Vec3 d3_bar = rotation_matrix(base.orientation).col(2);
      const Vec3 d3 = rotation_matrix(Quat(q)).col(2);
      q = quat_multiply(quat_between(d3, d3_bar), Quat(q)).normalized();
      // m(0) . d3 = -moment . d3 (the collar transmits no torsion but the applied one).
      m += (-base.moment.dot(d3_bar) - m.dot(d3_bar)) * d3_bar;
      break;
    }
    case RodEndKind::Spherical:
      p = base.position;
      m = -base.moment;
      break;
    case RodEndKind::Universal:
    case RodEndKind::Revolute: {
      // Onto the joint's motions and transmitted moments: y0 from its own projected unknowns.
      const joint_end::Axes axes = axes_of(base);
      const RodStateVector y = y0;
      joint_end::base_state(axes, base.position, base.orientation, base.moment,
                            joint_end::base_unknowns(axes, base.orientation, base.moment, y), y0);
      break;
    }
    case RodEndKind::Free:
      n = -base.force;
      m = -base.moment;
      break;
  }
}

RodStateVector initial_base_guess(const RodModel& model) {
  const RodEnd& base = model.base;
  const RodEnd& tip = model.tip;
  const Vec3 f = model.distributed_force();
  const double L = model.length;
  ShootingState x;
  x.p = base.position;
  x.q = base.orientation.normalized();
  if (base.kind == RodEndKind::Clamped) {
    // The unloaded rod (n = m = 0): the first Newton step is then the small-deflection solution, and
    // the step cap (ShootingOptions::max_step) scales all unknowns alike, which acts like a built-in
    // load ramp. Measured on the Bisshopp-Drucker cantilever: converges directly up to alpha = 30,
    // whereas the straight-rod statics guess m(0) = M + L d3 x F + ... stalls from alpha = 5 on.
    x.n.setZero();
    x.m.setZero();
  } else {
    // The base carries about half the distributed load.
    x.n = 0.5 * L * f;
    if (joint_end::is_joint(base.kind)) {
      // The tip is held in position (RodModel::validate): turned towards it (then projected onto the joint's
      // motions by enforce_base).
      const Vec3 chord = tip.position - base.position;
      if (chord.norm() > 1e-12 * L)
        x.q = quat_multiply(quat_between(rotation_matrix(x.q).col(2), chord.normalized()), x.q);
    } else if (base.kind == RodEndKind::Free || base.kind == RodEndKind::Spherical) {
      // The tip is clamped (RodModel::validate): guess a straight rod ending at the tip pose.
      const Quat q_tip = tip.orientation.normalized();
      const Vec3 d3_tip = rotation_matrix(q_tip).col(2);
      if (base.kind == RodEndKind::Free) {
        x.q = q_tip;
        x.p = tip.position - L * d3_tip;
      } else {
        const Vec3 chord = tip.position - base.position;
        x.q =
            chord.norm() > 1e-12 * L ? quat_multiply(quat_between(d3_tip, chord.normalized()), q_tip) : q_tip;
      }
    }
  }
  RodStateVector y = x.to_vector();
  enforce_base(base, y);
  return y;
}

void base_tangents(const RodEnd& base, const RodStateVector& y0, RodStateWithTangents& Y) {
  Y.setZero();
  Y.col(0) = y0;
  if (joint_end::is_joint(base.kind)) {
    const joint_end::Axes axes = axes_of(base);
    RodStateVector y;
    joint_end::BaseTangents tangents;
    joint_end::base_state(axes, base.position, base.orientation, base.moment,
                          joint_end::base_unknowns(axes, base.orientation, base.moment, y0), y, &tangents);
    Y.rightCols<kRodTangentCount>() = tangents;
    return;
  }
  const Quat q = y0.segment<4>(RodStateIndex::q);
  // Body rotation by theta: dq = 1/2 q (x) [0, theta].
  auto rotation_column = [&](int col, const Vec3& axis) {
    Y.col(col).segment<4>(RodStateIndex::q) = 0.5 * times_pure(q, axis);
  };
  for (int j = 0; j < 3; ++j) {
    const Vec3 e = Vec3::Unit(j);
    switch (base.kind) {
      case RodEndKind::Clamped:
        Y.col(1 + j).segment<3>(RodStateIndex::n) = e;
        Y.col(4 + j).segment<3>(RodStateIndex::m) = e;
        break;
      case RodEndKind::Collar: Y.col(1 + j).segment<3>(RodStateIndex::n) = e; break;
      case RodEndKind::Spherical:
        Y.col(1 + j).segment<3>(RodStateIndex::n) = e;
        rotation_column(4 + j, e);
        break;
      case RodEndKind::Universal:
      case RodEndKind::Revolute: break;  // above
      case RodEndKind::Free:
        Y.col(1 + j).segment<3>(RodStateIndex::p) = e;
        rotation_column(4 + j, e);
        break;
    }
  }
  if (base.kind == RodEndKind::Collar) {
    const Mat3 R_bar = rotation_matrix(base.orientation);
    Y.col(4).segment<3>(RodStateIndex::m) = R_bar.col(0);
    Y.col(5).segment<3>(RodStateIndex::m) = R_bar.col(1);
    rotation_column(6, Vec3::UnitZ());
  }
}

void retract_base(const RodEnd& base, const Vec6& dz, RodStateVector& y0) {
  auto q = y0.segment<4>(RodStateIndex::q);
  const Vec3 a = dz.head<3>(), b = dz.tail<3>();
  switch (base.kind) {
    case RodEndKind::Clamped:
      y0.segment<3>(RodStateIndex::n) += a;
      y0.segment<3>(RodStateIndex::m) += b;
      break;
    case RodEndKind::Collar: {
      const Mat3 R_bar = rotation_matrix(base.orientation);
      y0.segment<3>(RodStateIndex::n) += a;
      y0.segment<3>(RodStateIndex::m) += b[0] * R_bar.col(0) + b[1] * R_bar.col(1);
      q = quat_multiply(Quat(q), quat_from_rotation_vector(Vec3(0.0, 0.0, b[2]))).normalized();
      break;
    }
    case RodEndKind::Spherical:
      y0.segment<3>(RodStateIndex::n) += a;
      q = quat_multiply(Quat(q), quat_from_rotation_vector(b)).normalized();
      break;
    case RodEndKind::Universal:
    case RodEndKind::Revolute: {
      // The joint angles and transmitted moments move additively (a global parameterisation).
      const joint_end::Axes axes = axes_of(base);
      const Vec6 z = joint_end::base_unknowns(axes, base.orientation, base.moment, y0) + dz;
      joint_end::base_state(axes, base.position, base.orientation, base.moment, z, y0);
      break;
    }
    case RodEndKind::Free:
      y0.segment<3>(RodStateIndex::p) += a;
      q = quat_multiply(Quat(q), quat_from_rotation_vector(b)).normalized();
      break;
  }
}

namespace {

// q_e = conj(q_bar) (x) q (unit, sign chosen with w >= 0): the rotation R_bar^T R. Its vector part is
// sin(theta/2) times the axis, zero only at R = R_bar (unlike vee(R_bar^T R - R^T R_bar), which also
// vanishes at half turns and would let Newton stop at a tip flipped by pi).
Quat orientation_error(const Quat& q_bar, const Quat& q) {
  Quat e = quat_multiply(quat_conjugate(q_bar.normalized()), q.normalized());
  if (e[0] < 0.0) e = -e;
  return e;
}

// Collar axis error for b = R_bar^T d3 (d3 in the prescribed frame): the first two components of
// 2 vec(quaternion taking e3 to b) = g (e3 x b), g = 2 / sqrt(2 (1 + b_z)); zero only at b = e3
// (the first two components of b alone also vanish at b = -e3).
double axis_error_gain(const Vec3& b) {
  return std::sqrt(2.0 / std::max(1.0 + b[2], 1e-12));
}
Eigen::Vector2d axis_error(const Vec3& b) {
  return axis_error_gain(b) * Eigen::Vector2d(-b[1], b[0]);
}

}  // namespace

Vec6 tip_residual(const RodEnd& tip, const RodStateVector& y) {
  const Vec3 p = y.segment<3>(RodStateIndex::p), n = y.segment<3>(RodStateIndex::n),
             m = y.segment<3>(RodStateIndex::m);
  const Mat3 R = rotation_matrix(y.segment<4>(RodStateIndex::q));
  Vec6 r = Vec6::Zero();
  switch (tip.kind) {
    case RodEndKind::Clamped:
      r << p - tip.position,
          2.0 * orientation_error(tip.orientation, y.segment<4>(RodStateIndex::q)).tail<3>();
      break;
    case RodEndKind::Collar: {
      const Vec3 b = rotation_matrix(tip.orientation).transpose() * R.col(2);
      r << p - tip.position, axis_error(b), (m - tip.moment).dot(R.col(2));
      break;
    }
    case RodEndKind::Spherical: r << p - tip.position, m - tip.moment; break;
    case RodEndKind::Universal:
    case RodEndKind::Revolute:
      r << p - tip.position,
          joint_end::tip_rows(axes_of(tip), rotation_matrix(tip.orientation), R, m - tip.moment);
      break;
    case RodEndKind::Free: r << n - tip.force, m - tip.moment; break;
  }
  return r;
}

Mat6 tip_residual_jacobian(const RodEnd& tip, const RodStateWithTangents& Y) {
  const Quat q = Y.col(0).segment<4>(RodStateIndex::q);
  const Vec3 m = Y.col(0).segment<3>(RodStateIndex::m);
  const Mat3 R = rotation_matrix(q);
  const Mat3 R_bar = rotation_matrix(tip.orientation);
  const Quat q_error = orientation_error(tip.orientation, q);
  const Vec3 b = R_bar.transpose() * R.col(2);
  const double g = axis_error_gain(b);
  const Quat q_conj(q[0], -q[1], -q[2], -q[3]);
  const joint_end::Axes axes = joint_end::is_joint(tip.kind) ? axes_of(tip) : joint_end::Axes();
  Mat6 J;
  for (int j = 0; j < 6; ++j) {
    const auto col = Y.col(1 + j);
    const Vec3 dp = col.segment<3>(RodStateIndex::p), dn = col.segment<3>(RodStateIndex::n),
               dm = col.segment<3>(RodStateIndex::m);
    const Vec3 omega =
        2.0 * quat_multiply(q_conj, Quat(col.segment<4>(RodStateIndex::q))).tail<3>() / q.squaredNorm();
    Vec6 dr = Vec6::Zero();
    switch (tip.kind) {
      case RodEndKind::Clamped:
        // d(2 vec(q_e)) with dq_e = q_e (x) [0, omega / 2].
        dr << dp, q_error[0] * omega + q_error.tail<3>().cross(omega);
        break;
      case RodEndKind::Collar: {
        const Vec3 dd3 = R * omega.cross(Vec3::UnitZ());
        const Vec3 db = R_bar.transpose() * dd3;
        const double dg = -0.5 * g / std::max(1.0 + b[2], 1e-12) * db[2];
        dr << dp, g * Eigen::Vector2d(-db[1], db[0]) + dg * Eigen::Vector2d(-b[1], b[0]),
            dm.dot(R.col(2)) + (m - tip.moment).dot(dd3);
        break;
      }
      case RodEndKind::Spherical: dr << dp, dm; break;
      case RodEndKind::Universal:
      case RodEndKind::Revolute:
        dr << dp, joint_end::tip_rows_derivative(axes, R_bar, R, m - tip.moment, omega, dm);
        break;
      case RodEndKind::Free: dr << dn, dm; break;
    }
    J.col(j) = dr;
  }
  return J;
}

Vec6 residual_scale(const RodEnd& tip, const RodOde& ode) {
  const double L = ode.length_scale(), F = ode.force_scale(), M = ode.moment_scale();
  Vec6 scale = Vec6::Ones();
  switch (tip.kind) {
    case RodEndKind::Clamped: scale << L, L, L, 1, 1, 1; break;
    case RodEndKind::Collar: scale << L, L, L, 1, 1, M; break;
    case RodEndKind::Spherical: scale << L, L, L, M, M, M; break;
    case RodEndKind::Universal:
    case RodEndKind::Revolute: scale << L, L, L, joint_end::tip_row_scale(axes_of(tip), M); break;
    case RodEndKind::Free: scale << F, F, F, M, M, M; break;
  }
  return scale;
}

Vec6 unknown_scale(const RodEnd& base, const RodOde& ode) {
  const double L = ode.length_scale(), F = ode.bending_force_scale(), M = F * L;
  Vec6 scale = Vec6::Ones();
  switch (base.kind) {
    case RodEndKind::Clamped: scale << F, F, F, M, M, M; break;
    case RodEndKind::Collar: scale << F, F, F, M, M, 1; break;
    case RodEndKind::Spherical: scale << F, F, F, 1, 1, 1; break;
    case RodEndKind::Universal:
    case RodEndKind::Revolute: scale << F, F, F, joint_end::unknown_scale(axes_of(base), M); break;
    case RodEndKind::Free: scale << L, L, L, 1, 1, 1; break;
  }
  return scale;
}

}  // namespace shooting
}  // namespace pcr
