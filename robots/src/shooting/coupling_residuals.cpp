// Coupling and balance residuals of the shooting robot solver (see coupling_residuals.hpp).
#include "coupling_residuals.hpp"

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"

namespace pcr {
namespace shooting_robot {

namespace {

Quat tip_quaternion(const RodStateVector& y) {
  return y.segment<4>(RodStateIndex::q).normalized();
}

Vec3 position_rows(const RodStateVector& y, const Pose& T, const RobotShootingModel& m) {
  return (y.segment<3>(RodStateIndex::p) - T.position) / m.Ls;
}

// Clamped: position and 2 vec(q_e), q_e = conj(q_T) (x) q with w >= 0 (= sin(theta/2) axis, zero only
// at R = R_T).
Vec6 clamped(const RodStateVector& y, const Pose& T, const RobotShootingModel& m) {
  Quat qe = quat_multiply(quat_conjugate(T.orientation.normalized()), tip_quaternion(y));
  if (qe[0] < 0) qe = -qe;
  Vec6 r;
  r << position_rows(y, T, m), 2.0 * qe.tail<3>();
  return r;
}
Vec6 clamped_scale(const RobotShootingModel& m) {
  return (Vec6() << Vec3::Constant(m.Ls), Vec3::Ones()).finished();
}

// Collar: position, d3 along the collar axis (the components of R_T^T d3 normal to it), free torsion:
// m(L) . d3 = 0.
Vec6 collar(const RodStateVector& y, const Pose& T, const RobotShootingModel& m) {
  const Vec3 d3 = rotation_matrix(tip_quaternion(y)).col(2);
  const Vec3 b = T.rotation().transpose() * d3;
  Vec6 r;
  r << position_rows(y, T, m), b[0], b[1], y.segment<3>(RodStateIndex::m).dot(d3) / m.Ms;
  return r;
}
Vec6 collar_scale(const RobotShootingModel& m) {
  return (Vec6() << Vec3::Constant(m.Ls), 1.0, 1.0, m.Ms).finished();
}

// Spherical: position, no moment transmitted (m(L) = 0).
Vec6 spherical(const RodStateVector& y, const Pose& T, const RobotShootingModel& m) {
  Vec6 r;
  r << position_rows(y, T, m), y.segment<3>(RodStateIndex::m) / m.Ms;
  return r;
}
Vec6 spherical_scale(const RobotShootingModel& m) {
  return (Vec6() << Vec3::Constant(m.Ls), Vec3::Constant(m.Ms)).finished();
}

}  // namespace

const Coupling& coupling_of(RodEndKind kind) {
  static const Coupling kClamped{clamped, clamped_scale}, kCollar{collar, collar_scale},
      kSpherical{spherical, spherical_scale};
  switch (kind) {
    case RodEndKind::Clamped: return kClamped;
    case RodEndKind::Collar: return kCollar;
    case RodEndKind::Spherical: return kSpherical;
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

}  // namespace shooting_robot
}  // namespace pcr
