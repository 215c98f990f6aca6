// PathPredictor (path_predictor.hpp): polynomial extrapolation of the stored solutions along a line or
// along the polygon of the stored parameters, the order following the last solves.
#include "path_predictor.hpp"

#include <algorithm>
#include <cmath>

namespace pcr::kinematics {

namespace {

/// The vector e from z_k lies on the line of the last step (angle below ~25 deg, either direction),
/// s = e . d its coordinate along it.
bool on_line(double s, const VecX& e) {
  return std::abs(s) >= 0.9 * e.norm();
}

/// u . v >= cos(~25 deg) |u| |v|: v goes on in the direction of u (false if either is zero).
bool goes_on(const VecX& u, const VecX& v) {
  const double uu = u.squaredNorm(), vv = v.squaredNorm();
  return uu > 0.0 && vv > 0.0 && u.dot(v) >= 0.9 * std::sqrt(uu * vv);
}

}  // namespace

void PathPredictor::Weights::set_weights(double s_new) {
  // L_j(s) = prod_{i != j} (s - s_i) / (s_j - s_i).
  for (int j = 0; j < used; ++j) {
    double l = 1.0;
    for (int i = 0; i < used; ++i)
      if (i != j) l *= (s_new - nodes[i]) / (nodes[j] - nodes[i]);
    weights[j] = l;
  }
}

bool PathPredictor::line_weights(const VecX& z_new, int max_points, Weights& w) const {
  const VecX step = z(0) - z(1), dz = z_new - z(0);
  const double a = step.norm();
  if (!(a > 0.0) || !(dz.squaredNorm() > 0.0)) return false;
  const VecX d = step / a;
  const double s_new = dz.dot(d);
  if (!on_line(s_new, dz) || !(std::abs(s_new) <= 2.0 * a)) return false;
  w.nodes[0] = 0.0;
  w.points[0] = 0;
  w.nodes[1] = -a;
  w.points[1] = 1;
  w.used = 2;
  for (int j = 2; j < count_ && w.used < max_points; ++j) {
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
    for (int i = 0; i < w.used; ++i) distinct = distinct && std::abs(s - w.nodes[i]) >= 0.1 * a;
    if (!distinct) continue;  // a revisited point: the newer solution is already a node
    w.nodes[w.used] = s;
    w.points[w.used] = j;
    ++w.used;
  }
  w.set_weights(s_new);
  return true;
}

bool PathPredictor::curve_weights(const VecX& z_new, int max_points, Weights& w) const {
  const VecX dz = z_new - z(0);
  const double a = (z(0) - z(1)).norm(), s_new = dz.norm();
  if (!goes_on(z(0) - z(1), dz) || !(s_new <= 2.0 * a)) return false;
  w.nodes[0] = 0.0;
  w.points[0] = 0;
  w.used = 1;
  for (int j = 1; j < count_ && w.used < max_points; ++j) {
    // Step j (from z_j to z_{j-1}) goes on into the one after it (into dz for the last step).
    const VecX step = z(j - 1) - z(j);
    if (!goes_on(step, j == 1 ? dz : VecX(z(j - 2) - z(j - 1)))) break;
    w.nodes[w.used] = w.nodes[w.used - 1] - step.norm();
    w.points[w.used] = j;
    ++w.used;
  }
  w.set_weights(s_new);
  return w.used >= 2;
}

double PathPredictor::miss(const Weights& w, const VecX& z_new) const {
  VecX z_pred = -z_new;
  for (int i = 0; i < w.used; ++i) z_pred += w.weights[i] * z(w.points[i]);
  return z_pred.norm();
}

bool PathPredictor::weights_for(const VecX& z_new, int max_points, Weights& w) const {
  if (count_ < 2 || z_new.size() != z(0).size()) return false;
  Weights line, curve;
  const bool by_line = line_weights(z_new, max_points, line),
             by_curve = curve_weights(z_new, max_points, curve);
  if (!by_line && !by_curve) return false;
  // The curve only where it reproduces z_new clearly better (on a straight path both are exact).
  w = by_curve && (!by_line || miss(curve, z_new) < 0.5 * miss(line, z_new)) ? curve : line;
  return true;
}

VecX PathPredictor::combine(const Weights& w, const VecX& x_last) const {
  VecX out = w.weights[0] * x_last;
  for (int i = 1; i < w.used; ++i) out += w.weights[i] * x(w.points[i]);
  return out;
}

VecX PathPredictor::predict(const VecX& x_last, const VecX& z_new, bool* on_path) const {
  if (on_path) *on_path = false;
  Weights w;
  if (count_ < 2 || x_last.size() != x(1).size() || !weights_for(z_new, order_, w)) return x_last;
  if (on_path) *on_path = true;
  return combine(w, x_last);
}

void PathPredictor::accept(const VecX& x_new, const VecX& z_new) {
  // The order: of the current one and its neighbours, the one whose prediction would have come closest
  // to x_new (max-abs; the smaller order on a tie), among those that had the points they ask for; kept
  // while the current order lacks them (the start of a path, after a turn).
  Weights current;
  if (count_ >= 2 && x_new.size() == x(0).size() && weights_for(z_new, order_, current) &&
      current.used == order_) {
    int best = order_;
    double best_error = INFINITY;
    for (int m = std::max(2, order_ - 1); m <= std::min(kMaxPoints, order_ + 1); ++m) {
      Weights w;
      if (!weights_for(z_new, m, w) || w.used < m) continue;
      const double error = (combine(w, x(0)) - x_new).lpNorm<Eigen::Infinity>();
      if (error < best_error) {
        best_error = error;
        best = m;
      }
    }
    order_ = best;
  }
  newest_ = (newest_ + kMaxPoints - 1) % kMaxPoints;
  xs_[newest_] = x_new;
  zs_[newest_] = z_new;
  count_ = count_ < kMaxPoints ? count_ + 1 : kMaxPoints;
}

}  // namespace pcr::kinematics
