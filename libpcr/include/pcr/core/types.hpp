#pragma once
// Fixed-size types used across pcr. SI units throughout.
#include <Eigen/Dense>

namespace pcr {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
/// Quaternion stored scalar first: q = [w, x, y, z].
using Quat = Eigen::Vector4d;
using VecX = Eigen::VectorXd;
using MatX = Eigen::MatrixXd;
using RowMajorMatX = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

}  // namespace pcr
