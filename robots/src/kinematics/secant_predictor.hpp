#pragma once
// Start point for the next solve along a path of parameters z (FK: inputs; IK: target poses), from the
// last two converged solutions (x_{k-1}, z_{k-1}) and (x_k, z_k):
//   x_pred = x_k + theta (x_k - x_{k-1}),   theta = (dz . dz_old) / |dz_old|^2,
//   dz = z_new - z_k, dz_old = z_k - z_{k-1}   (first-order extrapolation along the path).
// Used only when the new step continues the old one (angle between dz and dz_old below ~25 deg and
// 0 < theta <= 2); otherwise the start is x_k. The error of the start drops from O(|dz|) to O(|dz|^2),
// which saves simplified-Newton iterations on smooth paths (teleoperation, trajectories).
#include <cmath>

#include "pcr/core/types.hpp"

namespace pcr::kinematics {

class SecantPredictor {
 public:
  /// Start point for parameters z_new (x_last if there is no usable history).
  VecX predict(const VecX& x_last, const VecX& z_new) const {
    if (count_ < 2 || z_new.size() != z_last_.size() || x_last.size() != x_prev_.size()) return x_last;
    const VecX dz = z_new - z_last_, dz_old = z_last_ - z_prev_;
    const double old2 = dz_old.squaredNorm(), new2 = dz.squaredNorm();
    if (!(old2 > 0.0) || !(new2 > 0.0)) return x_last;
    const double dot = dz.dot(dz_old);
    const double theta = dot / old2;
    if (dot < 0.9 * std::sqrt(old2 * new2) || !(theta > 0.0 && theta <= 2.0)) return x_last;
    return x_last + theta * (x_last - x_prev_);
  }
  /// Records a converged solution x for parameters z.
  void accept(const VecX& x, const VecX& z) {
    x_prev_ = x_last_;
    z_prev_ = z_last_;
    x_last_ = x;
    z_last_ = z;
    count_ = count_ < 2 ? count_ + 1 : 2;
  }
  void reset() { count_ = 0; }

 private:
  VecX x_prev_, z_prev_, x_last_, z_last_;
  int count_ = 0;
};

}  // namespace pcr::kinematics
