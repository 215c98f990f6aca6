// The obstacles' gap rows of the energy (energy_terms.hpp ObstacleGapRows).
#include <algorithm>
#include <limits>
#include <utility>

#include "energy_terms.hpp"

namespace pcr::kinematics {

ObstacleGapRows::ObstacleGapRows(std::vector<Obstacle> obstacles, double radius, VecX basis,
                                 std::vector<VariableId> points, double length_scale)
    : ResidualBlock("energy.obstacle_gap", "", static_cast<int>(obstacles.size()), std::move(points)),
      obstacles_(std::move(obstacles)),
      radius_(radius),
      basis_(std::move(basis)),
      length_scale_(length_scale) {
  set_row_bounds(VecX::Zero(num_rows()), VecX::Constant(num_rows(), std::numeric_limits<double>::infinity()));
}

Vec3 ObstacleGapRows::centerline(const double* const* values) const {
  Vec3 p = Vec3::Zero();
  for (int a = 0; a < basis_.size(); ++a) p += basis_[a] * Eigen::Map<const Vec3>(values[a]);
  return p;
}

void ObstacleGapRows::evaluate(const double* const* values, double* residual,
                               double* const* jacobians) const {
  const Vec3 p = centerline(values);
  for (int k = 0; k < num_rows(); ++k) {
    const ObstacleGap g = obstacle_gap(obstacles_[k], p, radius_);
    residual[k] = g.gap / length_scale_;
    if (!jacobians) continue;
    for (int a = 0; a < basis_.size(); ++a) {
      if (!jacobians[a]) continue;
      double* row = jacobians[a] + k * 7;
      for (int c = 0; c < 3; ++c) row[c] = basis_[a] * g.normal[c] / length_scale_;  // dg/dp = nu
      std::fill(row + 3, row + 7, 0.0);
    }
  }
}

void ObstacleGapRows::evaluate_hessian(const double* const* values, const double* weights,
                                       double* hessian) const {
  const int n = 7 * static_cast<int>(basis_.size());
  std::fill(hessian, hessian + n * n, 0.0);
  const Vec3 p = centerline(values);
  Mat3 curvature = Mat3::Zero();  // sum_k w_k d nu_k / d p
  for (int k = 0; k < num_rows(); ++k)
    curvature += weights[k] * obstacle_gap(obstacles_[k], p, radius_).normal_derivative;
  curvature /= length_scale_;
  for (int a = 0; a < basis_.size(); ++a)
    for (int b = 0; b < basis_.size(); ++b)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          hessian[(7 * a + i) * n + 7 * b + j] = basis_[a] * basis_[b] * curvature(i, j);
}

}  // namespace pcr::kinematics
