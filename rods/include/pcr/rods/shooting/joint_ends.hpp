#pragma once
// Rod ends held by a universal (Hooke) or revolute (pin) joint (RodEndKind, rod_model.hpp) as the
// shooting solvers see them; shared by the single-rod solver (rod_shooting.hpp) and the robot solver.
//
// End frame T (world rotation R_T, origin p_T), axis a (unit, in T); for universal the second axis
// b = unit(e3 x a), fixed in the rod's body frame (the axes of end_axes.hpp, shared with collocation). The
// rod frame R at the end and the moment the joint transmits to the rod (m_joint, world):
//   universal: R = R_T R_a(theta1) R_b(theta2),  m_joint = mu t,  t = (R_T a) x (R b)
//              (unit: R b = R_T R_a(theta1) b stays normal to R_T a, so the angles never lock);
//   revolute:  R = R_T R_a(theta),  m_joint = mu1 R_T c1 + mu2 R_T c2, (a, c1, c2) right-handed
//              orthonormal in T (joint_axes: c1 = unit(e3 x a), or unit(e1 x a) when a is along e3).
// With the applied moment M on the rod at that end: m(L) = M + m_joint at a tip, m(0) = -(M + m_joint)
// at a base (n, m: the force and moment of the part s+ on the part s-).
//
// Base unknowns (six, the rod's shooting unknowns at s = 0):
//   universal: z = (n(0), theta1, theta2, mu),   revolute: z = (n(0), theta, mu1, mu2).
// Tip rows (three, after the three position rows p(L) - p_T), zero exactly on the joint's motions:
//   universal: (R_T a) . (R b),  m_joint . (R_T a),  m_joint . (R b)          with m_joint = m(L) - M;
//   revolute:  g (-v . c2, v . c1), g = sqrt(2 / (1 + a . v)), v = R_T^T R a (the first two components
//              of 2 vec of the smallest rotation taking a to v: zero only at v = a), m_joint . (R_T a).
#include <string>

#include "pcr/core/types.hpp"
#include "pcr/rods/rod_model.hpp"
#include "pcr/rods/shooting/rod_ode.hpp"

namespace pcr {
namespace joint_end {

using Vec6 = Eigen::Matrix<double, 6, 1>;
/// d y(0) / d z for the six base unknowns (rotations as dq = 1/2 q (x) [0, omega_body]).
using BaseTangents = Eigen::Matrix<double, kRodStateSize, 6>;
/// d y(0) / d omega for a rotation omega (world) of the end frame about its origin.
using FrameTangents = Eigen::Matrix<double, kRodStateSize, 3>;

/// Universal or revolute.
bool is_joint(RodEndKind kind);

struct Axes {
  RodEndKind kind = RodEndKind::Universal;
  Vec3 a = Vec3::UnitX();   ///< first axis (universal) or pin axis (revolute), unit, end frame
  Vec3 b = Vec3::UnitY();   ///< universal: second axis, unit, rod body frame
  Vec3 c1 = Vec3::UnitY();  ///< revolute: unit, normal to a (end frame)
  Vec3 c2 = Vec3::UnitZ();  ///< revolute: a x c1
};
/// The axes of a joint end; InputError naming `who` for a non-finite or zero axis, or a universal axis
/// within 1e-6 rad of the rod tangent e3 (no second axis then).
Axes axes_of(RodEndKind kind, const Vec3& axis, const std::string& who);

/// R_rel = R_T^T R: R_a(theta1) R_b(theta2) (universal) or R_a(theta1) (revolute; theta2 unused).
Quat relative_rotation(const Axes& axes, double theta1, double theta2);
/// The joint angles of R_rel (exact on the joint's motions; for any other rotation, those of a nearby
/// motion: theta1 from the direction of R_rel b (universal) or R_rel c1 (revolute) about a).
void joint_angles(const Axes& axes, const Mat3& R_rel, double& theta1, double& theta2);

/// y(0) of a rod whose base is held by the joint, from its six unknowns z, the end frame (p_T, q_T) and
/// the moment M applied to the rod there; optionally d y(0)/dz and d y(0)/d(end frame rotation).
void base_state(const Axes& axes, const Vec3& p_T, const Quat& q_T, const Vec3& applied_moment, const Vec6& z,
                RodStateVector& y0, BaseTangents* dy_dz = nullptr, FrameTangents* dy_dframe = nullptr);
/// The six unknowns of a base state (the rotation projected onto the joint's motions, the moment onto
/// the transmitted directions); base_state(base_unknowns(y0)) = y0 when y0 satisfies the joint.
Vec6 base_unknowns(const Axes& axes, const Quat& q_T, const Vec3& applied_moment, const RodStateVector& y0);
/// Sizes of the unknowns z[3..5] for a moment scale M: universal (1, 1, M), revolute (1, M, M).
Vec3 unknown_scale(const Axes& axes, double moment_scale);

/// The three tip rows (see above) at the rod frame R and m_joint = m(L) - M, against R_T.
Vec3 tip_rows(const Axes& axes, const Mat3& R_T, const Mat3& R, const Vec3& m_joint);
/// Their derivative along a change dR = R hat(omega_body), dm of the tip state.
Vec3 tip_rows_derivative(const Axes& axes, const Mat3& R_T, const Mat3& R, const Vec3& m_joint,
                         const Vec3& omega_body, const Vec3& dm);
/// Sizes of the tip rows for a moment scale M: universal (1, M, M), revolute (1, 1, M).
Vec3 tip_row_scale(const Axes& axes, double moment_scale);

}  // namespace joint_end
}  // namespace pcr
