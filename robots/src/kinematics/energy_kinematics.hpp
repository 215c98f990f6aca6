#pragma once
// Rotations of non-unit quaternions and strains for any scalar (double or pcr::Dual), shared by the
// energy terms (energy_terms.hpp; internal header of pcr::robots).
#include <Eigen/Core>

#include "pcr/math/dual.hpp"

namespace pcr::kinematics {

template <class T>
using V3 = Eigen::Matrix<T, 3, 1>;
template <class T>
using V4 = Eigen::Matrix<T, 4, 1>;
template <class T>
using M3 = Eigen::Matrix<T, 3, 3>;

/// R(q) = R_unit(q) / |q|^2 for q = [w, x, y, z] (quaternion.hpp): a rotation for every q != 0.
template <class T>
M3<T> rotation_of(const V4<T>& q) {
  const T w = q[0], x = q[1], y = q[2], z = q[3];
  const T s = T(1.0) / (w * w + x * x + y * y + z * z);
  M3<T> R;
  R << w * w + x * x - y * y - z * z, 2.0 * (x * y - w * z), 2.0 * (x * z + w * y),  //
      2.0 * (x * y + w * z), w * w - x * x + y * y - z * z, 2.0 * (y * z - w * x),   //
      2.0 * (x * z - w * y), 2.0 * (y * z + w * x), w * w - x * x - y * y + z * z;
  return R * s;
}

/// Body curvature u = 2 vec(conj(q) (x) q_s) / |q|^2 (R_s = R hat(u); independent of |q|).
template <class T>
V3<T> curvature_of(const V4<T>& q, const V4<T>& qs) {
  const V3<T> v = q.template tail<3>(), vs = qs.template tail<3>();
  const T s = T(1.0) / q.squaredNorm();
  return (vs * q[0] - v * qs[0] - v.cross(vs)) * (2.0 * s);
}

}  // namespace pcr::kinematics
