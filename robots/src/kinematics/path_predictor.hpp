#pragma once
// Start point for the next solve along a path of parameters z (FK: inputs; IK: target poses), from the
// last converged solutions (x_j, z_j), by polynomial extrapolation in the arc length s along the path:
//   dz = z_new - z_k, a = |z_k - z_{k-1}|, theta = (dz . (z_k - z_{k-1})) / a^2, s_new = theta a
//   (s_k = 0, s_{k-1} = -a, s_{k-2} = -(a + b), b = |z_{k-1} - z_{k-2}|);
//   two points: x_pred = x_k + theta (x_k - x_{k-1})  (error O(|dz|^2));
//   three points, when the step before also continues the path: the quadratic through them,
//   x_pred = L_k x_k + L_{k-1} x_{k-1} + L_{k-2} x_{k-2} with the Lagrange weights at s_new (error
//   O(|dz|^3)).
// Used only when the new step continues the old one (angle between dz and the last step below ~25 deg and
// 0 < theta <= 2); otherwise the start is x_k. Saves simplified-Newton iterations on smooth paths
// (teleoperation, trajectories): on the R5b path (p = 6, E = 8) the quadratic took 1.3 instead of 2.9
// iterations per warm IK solve at tolerance 1e-6, 3.9 instead of 4.9 at 1e-10 (README, Robots).
#include <cmath>

#include "pcr/core/types.hpp"

namespace pcr::kinematics {

class PathPredictor {
 public:
  /// Start point for parameters z_new (x_last if there is no usable history).
  VecX predict(const VecX& x_last, const VecX& z_new) const {
    if (count_ < 2 || z_new.size() != z_last_.size() || x_last.size() != x_prev_.size()) return x_last;
    const VecX dz = z_new - z_last_, dz_old = z_last_ - z_prev_;
    const double old2 = dz_old.squaredNorm(), new2 = dz.squaredNorm();
    if (!(old2 > 0.0) || !(new2 > 0.0)) return x_last;
    const double dot = dz.dot(dz_old);
    const double theta = dot / old2;
    if (!continues(dot, old2, new2) || !(theta > 0.0 && theta <= 2.0)) return x_last;
    if (count_ >= 3) {
      const VecX dz_older = z_prev_ - z_prev2_;
      const double older2 = dz_older.squaredNorm();
      if (older2 > 0.0 && continues(dz_old.dot(dz_older), old2, older2)) {
        const double a = std::sqrt(old2), b = std::sqrt(older2), s = theta * a;
        const double w_k = (s + a) * (s + a + b) / (a * (a + b));
        const double w_k1 = -s * (s + a + b) / (a * b);
        const double w_k2 = s * (s + a) / (b * (a + b));
        return w_k * x_last + w_k1 * x_prev_ + w_k2 * x_prev2_;
      }
    }
    return x_last + theta * (x_last - x_prev_);
  }
  /// Records a converged solution x for parameters z.
  void accept(const VecX& x, const VecX& z) {
    x_prev2_.swap(x_prev_);
    z_prev2_.swap(z_prev_);
    x_prev_.swap(x_last_);
    z_prev_.swap(z_last_);
    x_last_ = x;
    z_last_ = z;
    count_ = count_ < 3 ? count_ + 1 : 3;
  }
  void reset() { count_ = 0; }

 private:
  /// Two steps with dot product `dot` and squared lengths continue each other: angle below ~25 deg.
  static bool continues(double dot, double length2_a, double length2_b) {
    return dot >= 0.9 * std::sqrt(length2_a * length2_b);
  }
  VecX x_prev2_, z_prev2_, x_prev_, z_prev_, x_last_, z_last_;
  int count_ = 0;
};

}  // namespace pcr::kinematics
