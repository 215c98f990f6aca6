#pragma once
// Start point for the next solve along a path of parameters z (FK: inputs; IK: target poses), from the
// last converged solutions (x_j, z_j), by polynomial interpolation or extrapolation in the arc length
// along the line of the last step:
//   d = (z_k - z_{k-1}) / a, a = |z_k - z_{k-1}|, node s_j = (z_j - z_k) . d of each stored solution,
//   s_new = (z_new - z_k) . d,  x_pred = sum_j L_j(s_new) x_j, L_j the Lagrange weights over the nodes.
// The polynomial through m points has error O(|dz|^m): two points give the line x_k + theta (x_k -
// x_{k-1}), three a quadratic, four (kMaxPoints) a cubic. A stored point is used only if the stored
// steps from it to z_k all run along the line (each within ~25 deg of the next, either direction) and
// its node is not within a / 10 of one already used (a path that turns back revisits its points: the
// newest solution there is kept). The new point must lie on
// the line too, in either direction, at most 2 a from z_k; otherwise (a turn, a jump, a first step)
// the start is x_k. Going back along the path interpolates between stored solutions (exact where the
// target was solved before). Saves simplified-Newton iterations on smooth paths (teleoperation,
// trajectories): on the R5b path (p = 6, E = 8, tolerance 1e-6) the cubic starts within a residual of
// about 1e-6 (the quadratic about 2e-5, the last solution about 1e-3; docs/benchmarks.md, "Robots").
// The higher orders amplify the convergence errors of the stored solutions (the cubic's weights on an
// even path are 4, -6, 4, -1), which is why the order stops at four points.
#include <array>
#include <cmath>

#include "pcr/core/types.hpp"

namespace pcr::kinematics {

class PathPredictor {
 public:
  static constexpr int kMaxPoints = 4;

  /// Start point for parameters z_new (x_last if there is no usable history); on_path (if given) says
  /// whether it came from the stored solutions.
  VecX predict(const VecX& x_last, const VecX& z_new, bool* on_path = nullptr) const {
    if (on_path) *on_path = false;
    if (count_ < 2 || z_new.size() != z(0).size() || x_last.size() != x(1).size()) return x_last;
    const VecX step = z(0) - z(1), dz = z_new - z(0);
    const double a = step.norm();
    if (!(a > 0.0) || !(dz.squaredNorm() > 0.0)) return x_last;
    const VecX d = step / a;
    const double s_new = dz.dot(d);
    if (!on_line(s_new, dz) || !(std::abs(s_new) <= 2.0 * a)) return x_last;
    std::array<double, kMaxPoints> nodes{};
    std::array<int, kMaxPoints> points{};  // which stored solution each node is
    nodes[1] = -a;
    points[1] = 1;
    int used = 2;
    for (int j = 2; j < count_; ++j) {
      // The path back to z_j must run along the same line: each stored step parallel or antiparallel
      // to the one after it (a turn ends the segment), and z_j itself near the line.
      const VecX older = z(j - 1) - z(j), later = z(j - 2) - z(j - 1);
      const double older2 = older.squaredNorm(), later2 = later.squaredNorm();
      if (older2 > 0.0 && later2 > 0.0 && !(std::abs(older.dot(later)) >= 0.9 * std::sqrt(older2 * later2)))
        break;
      const VecX e = z(j) - z(0);
      const double s = e.dot(d);
      if (!on_line(s, e)) break;
      bool distinct = true;
      for (int i = 0; i < used; ++i) distinct = distinct && std::abs(s - nodes[i]) >= 0.1 * a;
      if (!distinct) continue;  // a revisited point: the newer solution is already a node
      nodes[used] = s;
      points[used] = j;
      ++used;
    }
    if (on_path) *on_path = true;
    VecX out = lagrange_weight(nodes, used, 0, s_new) * x_last;
    for (int i = 1; i < used; ++i) out += lagrange_weight(nodes, used, i, s_new) * x(points[i]);
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
  /// The vector e from z_k lies on the line of the last step (angle below ~25 deg, either direction),
  /// s = e . d its coordinate along it.
  static bool on_line(double s, const VecX& e) { return std::abs(s) >= 0.9 * e.norm(); }
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
