#pragma once
// Start point for the next solve along a path of parameters z (FK: inputs; IK: target poses), from the
// last converged solutions (x_j, z_j), by polynomial extrapolation in the arc length s along the path:
//   dz = z_new - z_k, a = |z_k - z_{k-1}|, theta = (dz . (z_k - z_{k-1})) / a^2, s_new = theta a,
//   nodes s_k = 0, s_{k-1} = -a, s_{k-j-1} = s_{k-j} - |z_{k-j} - z_{k-j-1}|;
//   x_pred = sum_j L_j(s_new) x_{k-j}, L_j the Lagrange weights over the nodes used.
// The polynomial through m points has error O(|dz|^m): two points give the line x_k + theta (x_k -
// x_{k-1}), three a quadratic, four (kMaxPoints) a cubic. Used only when the new step continues the old
// one (angle between dz and the last step below ~25 deg and 0 < theta <= 2); otherwise the start is x_k.
// Older points join only while each step continues the one after it, so after a turn the order grows
// again one point at a time. Saves simplified-Newton iterations on smooth paths (teleoperation,
// trajectories): on the R5b path (p = 6, E = 8, tolerance 1e-6) the cubic starts within a residual of
// about 1e-6 (the quadratic about 2e-5, the last solution about 1e-3; README, Robots).
// The higher orders amplify the convergence errors of the stored solutions (the cubic's weights on an
// even path are 4, -6, 4, -1), which is why the order stops at four points.
#include <array>
#include <cmath>

#include "pcr/core/types.hpp"

namespace pcr::kinematics {

class PathPredictor {
 public:
  static constexpr int kMaxPoints = 4;

  /// Start point for parameters z_new (x_last if there is no usable history).
  VecX predict(const VecX& x_last, const VecX& z_new) const {
    if (count_ < 2 || z_new.size() != z(0).size() || x_last.size() != x(1).size()) return x_last;
    const VecX dz = z_new - z(0), dz_old = z(0) - z(1);
    const double old2 = dz_old.squaredNorm(), new2 = dz.squaredNorm();
    if (!(old2 > 0.0) || !(new2 > 0.0)) return x_last;
    const double dot = dz.dot(dz_old);
    const double theta = dot / old2;
    if (!continues(dot, old2, new2) || !(theta > 0.0 && theta <= 2.0)) return x_last;
    std::array<double, kMaxPoints> nodes{};
    nodes[1] = -std::sqrt(old2);
    int used = 2;
    while (used < count_) {  // z(used - 1) - z(used) must continue z(used - 2) - z(used - 1)
      const VecX step = z(used - 1) - z(used), later = z(used - 2) - z(used - 1);
      const double step2 = step.squaredNorm();
      if (!(step2 > 0.0) || !continues(step.dot(later), step2, later.squaredNorm())) break;
      nodes[used] = nodes[used - 1] - std::sqrt(step2);
      ++used;
    }
    const double s = theta * std::sqrt(old2);
    VecX out = lagrange_weight(nodes, used, 0, s) * x_last;
    for (int j = 1; j < used; ++j) out += lagrange_weight(nodes, used, j, s) * x(j);
    return out;
  }
  /// Records a converged solution x for parameters z.
  void accept(const VecX& x_new, const VecX& z_new) {
    newest_ = (newest_ + kMaxPoints - 1) % kMaxPoints;
    xs_[newest_] = x_new;
    zs_[newest_] = z_new;
    count_ = count_ < kMaxPoints ? count_ + 1 : kMaxPoints;
  }
  void reset() { count_ = 0; }

 private:
  /// Two steps with dot product `dot` and squared lengths continue each other: angle below ~25 deg.
  static bool continues(double dot, double length2_a, double length2_b) {
    return dot >= 0.9 * std::sqrt(length2_a * length2_b);
  }
  /// L_j(s) = prod_{i != j} (s - s_i) / (s_j - s_i) over the first `used` nodes.
  static double lagrange_weight(const std::array<double, kMaxPoints>& nodes, int used, int j, double s) {
    double w = 1.0;
    for (int i = 0; i < used; ++i)
      if (i != j) w *= (s - nodes[i]) / (nodes[j] - nodes[i]);
    return w;
  }
  /// The j-th newest stored solution and parameters (j = 0: the last accepted).
  const VecX& x(int j) const { return xs_[(newest_ + j) % kMaxPoints]; }
  const VecX& z(int j) const { return zs_[(newest_ + j) % kMaxPoints]; }

  std::array<VecX, kMaxPoints> xs_, zs_;  // ring buffer, newest at index newest_
  int newest_ = 0;
  int count_ = 0;
};

}  // namespace pcr::kinematics
