#pragma once
// Quaternions q = [w, x, y, z] (scalar first, Hamilton product) and the rotation they define.
//
// R(q) = R_unit(q) / |q|^2 is a rotation for every q != 0 (docs/design.md §1); R_unit is the usual
// quadratic form, equal to R(q) when |q| = 1. Its first and second derivatives with respect to the
// four components of q are what the collocation Jacobians need.
#include <array>

#include "pcr/core/types.hpp"

namespace pcr {

/// Hamilton product a (x) b, so that R(a (x) b) = R(a) R(b).
Quat quat_multiply(const Quat& a, const Quat& b);
/// Conjugate [w, -x, -y, -z] (the inverse for unit quaternions).
Quat quat_conjugate(const Quat& q);
/// Identity rotation [1, 0, 0, 0].
Quat quat_identity();
/// Unit quaternion of a rotation by |theta| about theta / |theta| (rotation vector).
Quat quat_from_rotation_vector(const Vec3& theta);
/// Unit quaternion with w >= 0 of a rotation matrix (Shepperd's method; R must be a rotation).
Quat quat_from_rotation(const Mat3& R);

/// The quadratic form R_unit(q) (not normalised).
Mat3 rotation_unit_form(const Quat& q);
/// R(q) = R_unit(q) / |q|^2. Throws InputError for q = 0.
Mat3 rotation_matrix(const Quat& q);

/// dR/dq_k for k = 0..3 (w, x, y, z).
using QuatRotationJacobian = std::array<Mat3, 4>;
/// d^2 R / (dq_k dq_l), symmetric in (k, l).
using QuatRotationHessian = std::array<std::array<Mat3, 4>, 4>;

/// R(q) and dR/dq_k.
void rotation_matrix_derivatives(const Quat& q, Mat3& R, QuatRotationJacobian& dR);
/// R(q), dR/dq_k and d^2R/(dq_k dq_l).
void rotation_matrix_second_derivatives(const Quat& q, Mat3& R, QuatRotationJacobian& dR,
                                        QuatRotationHessian& d2R);

}  // namespace pcr
