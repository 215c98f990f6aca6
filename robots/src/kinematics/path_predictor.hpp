#pragma once
// Start point for the next solve along a path of parameters z (FK: inputs; IK: target poses), from the
// last converged solutions (x_j, z_j), by polynomial interpolation or extrapolation in a scalar
// coordinate s along the path: x_pred = sum_j L_j(s_new) x_j, L_j the Lagrange weights over the nodes
// s_j of the stored solutions. The polynomial through m points has error O(|dz|^m): two points give the
// line x_k + theta (x_k - x_{k-1}), three a quadratic, four a cubic, up to kMaxPoints. Two coordinates:
//  - line: s = (z - z_k) . d along the last step d = (z_k - z_{k-1}) / a, a = |z_k - z_{k-1}|. A stored
//    point is used only if the stored steps from it to z_k all run along the line (each within ~25 deg
//    of the next, either direction) and its node is not within a / 10 of one already used (a path that
//    turns back revisits its points: the newest solution there is kept). The new point must lie on the
//    line too, in either direction, at most 2 a from z_k. Going back along the path interpolates
//    between stored solutions (exact where the target was solved before).
//  - curve: s = the arc length along the polygon of the stored parameters (s_k = 0, s_{k-1} = -a, ...;
//    s_new = |z_new - z_k|), for a path that bends smoothly: every step forward within ~25 deg of the
//    one before, the new one too, at most 2 a long. On a circle of radius r with equal steps of angle
//    theta the polynomial through m points misses the new point by r (2 sin(theta / 2))^m, the line's
//    projection by about r theta^2 (it drops the part of the step across the line).
// Of the two, the one whose weights reproduce z_new better (|sum_j L_j(s_new) z_j - z_new|) gives the
// start (the curve only if it misses by less than half the line's). Otherwise (a turn, a jump, a first
// step) the start is x_k.
//
// The order: higher orders cut the truncation error but amplify the convergence errors of the stored
// solutions (the weights of m points on an even path sum to 2^m - 1 in magnitude: 4, -6, 4, -1 for the
// cubic). Which wins depends on the path and the solver's tolerance, so the number of points follows
// the last solves: each accepted solution is compared with what the current order and one neighbour
// (the lower and the higher in turn) would have predicted for it, and the closer of them is used next
// (a path's smoothness changes slowly along it). On the R5b teleoperation path (straight, p = 6, E = 8,
// tolerance 1e-7) the cubic starts within a residual of about 5e-7, the stored solutions' noise; on the
// R5b helix the cubic leaves ~4e-5 (its truncation error), six points about 1e-6 (docs/benchmarks.md,
// "Time split of a warm R5b solve").
#include <array>

#include "pcr/core/types.hpp"

namespace pcr::kinematics {

class PathPredictor {
 public:
  static constexpr int kMaxPoints = 6;

  /// Start point for parameters z_new (x_last if there is no usable history); on_path (if given) says
  /// whether it came from the stored solutions.
  VecX predict(const VecX& x_last, const VecX& z_new, bool* on_path = nullptr) const;
  /// Records a converged solution x for parameters z (and adapts the order to it).
  void accept(const VecX& x_new, const VecX& z_new);
  void reset() {
    count_ = 0;
    last_prediction_valid_ = false;
  }
  /// The most points the next prediction uses (2 .. kMaxPoints).
  int order() const { return order_; }

 private:
  /// Lagrange weights at s_new over the nodes of some stored solutions (`points`: which, 0 = newest).
  struct Weights {
    std::array<double, kMaxPoints> nodes{}, weights{};
    std::array<int, kMaxPoints> points{};
    int used = 0;
    double s_new = 0.0;
    void set_weights(double s);
  };
  /// The nodes (up to kMaxPoints) of both coordinates for z_new and whether each is usable.
  struct Candidates {
    Weights line, curve;
    bool by_line = false, by_curve = false;
  };
  bool line_nodes(const VecX& z_new, Weights& w) const;
  bool curve_nodes(const VecX& z_new, Weights& w) const;
  /// Both coordinates' nodes for z_new; false: no usable history.
  bool candidates(const VecX& z_new, Candidates& c) const;
  /// The weights of the start for z_new over at most max_points nodes, line or curve (file comment).
  Weights pick(const Candidates& c, int max_points, const VecX& z_new) const;
  /// |sum_j w_j z_j - z_new|: how far the weights' own parameters are from the new ones.
  double miss(const Weights& w, const VecX& z_new) const;
  /// sum_j w_j x_j, the newest node being x_last.
  VecX combine(const Weights& w, const VecX& x_last) const;
  /// |sum_j w_j x_j - x_new|max over the stored x_j (before x_new is stored).
  double prediction_error(const Weights& w, const VecX& x_new) const;

  /// The j-th newest stored solution and parameters (j = 0: the last accepted).
  const VecX& x(int j) const { return xs_[(newest_ + j) % kMaxPoints]; }
  const VecX& z(int j) const { return zs_[(newest_ + j) % kMaxPoints]; }

  std::array<VecX, kMaxPoints> xs_, zs_;  // ring buffer, newest at index newest_
  int newest_ = 0;
  int count_ = 0;
  int order_ = 4;           // points of the next prediction, adapted in accept
  bool try_higher_ = true;  // which neighbour of order_ the next accept compares with
  // The last prediction at order_ (for accept), and scratch of prediction_error: predict writes them,
  // so one predictor serves one solver at a time (as the kinematics object that owns it).
  mutable VecX last_prediction_, last_z_, scratch_;
  mutable bool last_prediction_valid_ = false;
};

}  // namespace pcr::kinematics
