// Coupling and balance residuals of the shooting robot solver (see coupling_residuals.hpp).
#include "coupling_residuals.hpp"

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"

namespace pcr {
namespace shooting_robot {

namespace {

using joint_end::Axes;

Quat tip_quaternion(const RodStateVector& y) {
  return y.segment<4>(RodStateIndex::q).normalized();
}

Vec3 position_rows(const RodStateVector& y, const Pose& T, const RobotShootingModel& m) {
  return (y.segment<3>(RodStateIndex::p) - T.position) / m.Ls;
}

// Clamped: position and 2 vec(q_e), q_e = conj(q_T) (x) q with w >= 0 (= sin(theta/2) axis, zero only
// at R = R_T).
Vec6 clamped(const RodStateVector& y, const Pose& T, const Axes&, const RobotShootingModel& m) {
  Quat qe = quat_multiply(quat_conjugate(T.orientation.normalized()), tip_quaternion(y));
  if (qe[0] < 0) qe = -qe;
  Vec6 r;
  r << position_rows(y, T, m), 2.0 * qe.tail<3>();
  return r;
}
Vec6 clamped_scale(const Axes&, const RobotShootingModel& m) {
  return (Vec6() << Vec3::Constant(m.Ls), Vec3::Ones()).finished();
}

// Collar: position, d3 along the collar axis (the components of R_T^T d3 normal to it), free torsion:
// m(L) . d3 = 0.
Vec6 collar(const RodStateVector& y, const Pose& T, const Axes&, const RobotShootingModel& m) {
  const Vec3 d3 = rotation_matrix(tip_quaternion(y)).col(2);
  const Vec3 b = T.rotation().transpose() * d3;
  Vec6 r;
  r << position_rows(y, T, m), b[0], b[1], y.segment<3>(RodStateIndex::m).dot(d3) / m.Ms;
  return r;
}
Vec6 collar_scale(const Axes&, const RobotShootingModel& m) {
  return (Vec6() << Vec3::Constant(m.Ls), 1.0, 1.0, m.Ms).finished();
}

// Spherical: position, no moment transmitted (m(L) = 0).
Vec6 spherical(const RodStateVector& y, const Pose& T, const Axes&, const RobotShootingModel& m) {
  Vec6 r;
  r << position_rows(y, T, m), y.segment<3>(RodStateIndex::m) / m.Ms;
  return r;
}
Vec6 spherical_scale(const Axes&, const RobotShootingModel& m) {
  return (Vec6() << Vec3::Constant(m.Ls), Vec3::Constant(m.Ms)).finished();
}

// Universal and revolute: position and the joint's rows (joint_ends.hpp; no applied moment).
Vec6 joint(const RodStateVector& y, const Pose& T, const Axes& axes, const RobotShootingModel& m) {
  const Vec3 rows = joint_end::tip_rows(axes, T.rotation(), rotation_matrix(tip_quaternion(y)),
                                        y.segment<3>(RodStateIndex::m));
  Vec6 r;
  r << position_rows(y, T, m), rows.cwiseQuotient(joint_end::tip_row_scale(axes, m.Ms));
  return r;
}
Vec6 joint_scale(const Axes& axes, const RobotShootingModel& m) {
  return (Vec6() << Vec3::Constant(m.Ls), joint_end::tip_row_scale(axes, m.Ms)).finished();
}

}  // namespace

const Coupling& coupling_of(RodEndKind kind) {
  static const Coupling kClamped{clamped, clamped_scale}, kCollar{collar, collar_scale},
      kSpherical{spherical, spherical_scale}, kJoint{joint, joint_scale};
  switch (kind) {
    case RodEndKind::Clamped: return kClamped;
    case RodEndKind::Collar: return kCollar;
    case RodEndKind::Spherical: return kSpherical;
    case RodEndKind::Universal:
    case RodEndKind::Revolute: return kJoint;
    default: break;
  }
  throw_input_error("ShootingRobotSolver: a rod end of kind ", to_string(kind),
                    " cannot be coupled to a platform by the shooting solver");
}

Vec6 platform_balance(const RobotShootingModel& m, int k, const Pose& pose) {
  // F_ext + m g - sum n(L) = 0 and the moments about the platform origin x (shooting_robot_solver.hpp).
  const RobotModel& robot = *m.model;
  const Platform& p = robot.platforms()[k];
  const Mat3 R = pose.rotation();
  const Vec3 weight = p.mass * robot.gravity();
  Vec3 F = weight, M = (R * p.center_of_mass).cross(weight);
  for (const LoadSetup& l : m.loads)
    if (l.platform == k) {
      F += l.force;
      M += l.torque + (R * l.point).cross(l.force);
    }
  for (int i : m.rods_of_platform[k]) {
    const RodStateVector& y = m.rods[i].Y.col(0);
    const Vec3 n = y.segment<3>(RodStateIndex::n);
    F -= n;
    M -= y.segment<3>(RodStateIndex::m) + (y.segment<3>(RodStateIndex::p) - pose.position).cross(n);
  }
  Vec6 b;
  b << F / m.Fs, M / m.Ms;
  return b;
}

void joint_axis(const RobotShootingModel& m, int joint, const VecX& q, const State& s, Vec3& w, Vec3& o) {
  const Joint& j = m.model->joints()[joint];
  const Pose frame = m.model->link_pose(j.parent_link, q, s.poses) * j.origin;
  w = frame.rotation() * j.axis;
  o = frame.position;
}

double passive_balance(const RobotShootingModel& m, int p, const VecX& q, const State& s,
                       const std::vector<RodStateVector>& y0) {
  const RobotModel& robot = *m.model;
  const PassiveSetup& setup = m.passive[p];
  const Joint& joint = robot.joints()[setup.joint];
  Vec3 w, o;
  joint_axis(m, setup.joint, q, s, w, o);
  Vec3 force = Vec3::Zero(), moment = Vec3::Zero();  // on what lies beyond the joint, moment about o
  for (int i : setup.rods) {
    const Vec3 n = y0[i].segment<3>(RodStateIndex::n);
    force += n;
    moment += y0[i].segment<3>(RodStateIndex::m) + (y0[i].segment<3>(RodStateIndex::p) - o).cross(n);
  }
  for (int l : setup.links) {
    const Link& link = robot.links()[l];
    const Vec3 weight = link.mass * robot.gravity();
    force += weight;
    moment += (robot.link_pose(l, q, s.poses).transform_point(link.center_of_mass) - o).cross(weight);
  }
  const double Q = w.dot(setup.prismatic ? force : moment);
  return (Q - joint.stiffness * (q[joint.value_index] - joint.rest)) / setup.row_scale;
}

Eigen::Matrix<double, 1, kRodStateSize> passive_force_gradient(const PassiveSetup& p, const Vec3& w,
                                                               const Vec3& o, const RodStateVector& y0) {
  // Q = w . n(0) (prismatic) or w . (m(0) + (p(0) - o) x n(0)).
  Eigen::Matrix<double, 1, kRodStateSize> g = Eigen::Matrix<double, 1, kRodStateSize>::Zero();
  if (p.prismatic) {
    g.segment<3>(RodStateIndex::n) = w.transpose();
    return g;
  }
  const Vec3 n = y0.segment<3>(RodStateIndex::n), arm = y0.segment<3>(RodStateIndex::p) - o;
  g.segment<3>(RodStateIndex::p) = n.cross(w).transpose();    // w . (dp x n) = dp . (n x w)
  g.segment<3>(RodStateIndex::n) = w.cross(arm).transpose();  // w . (arm x dn) = dn . (w x arm)
  g.segment<3>(RodStateIndex::m) = w.transpose();
  return g;
}

}  // namespace shooting_robot
}  // namespace pcr
