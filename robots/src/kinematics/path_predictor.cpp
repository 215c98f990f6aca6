// PathPredictor (path_predictor.hpp): polynomial extrapolation of the stored solutions along a line or
// along the polygon of the stored parameters, the order following the last solves.
#include "path_predictor.hpp"

#include <algorithm>
#include <cmath>

namespace pcr::kinematics {

namespace {

/// |e . d| >= cos(~25 deg) |e| (d a unit vector, s = e . d): e lies along the line of d, either
/// direction.
bool on_line(double s, double e_norm) {
  return std::abs(s) >= 0.9 * e_norm;
}

/// u . v >= cos(~25 deg) |u| |v|: v goes on in the direction of u (false if either is zero).
template <typename U, typename V>
bool goes_on(const U& u, const V& v) {
  const double uu = u.squaredNorm(), vv = v.squaredNorm();
  return uu > 0.0 && vv > 0.0 && u.dot(v) >= 0.9 * std::sqrt(uu * vv);
}

}  // namespace

void PathPredictor::Weights::set_weights(double s) {
  // L_j(s) = prod_{i != j} (s - s_i) / (s_j - s_i).
  for (int j = 0; j < used; ++j) {
    double l = 1.0;
    for (int i = 0; i < used; ++i)
      if (i != j) l *= (s - nodes[i]) / (nodes[j] - nodes[i]);
    weights[j] = l;
  }
}

bool PathPredictor::line_nodes(const VecX& z_new, Weights& w) const {
  // Eigen expressions, no temporaries: the parameter vectors are short, this runs every solve.
  const auto step = z(0) - z(1);
  const auto dz = z_new - z(0);
  const double a = step.norm(), dz_norm = dz.norm();
  if (!(a > 0.0) || !(dz_norm > 0.0)) return false;
  const double s_new = dz.dot(step) / a;  // along d = step / a
  if (!on_line(s_new, dz_norm) || !(std::abs(s_new) <= 2.0 * a)) return false;
  w.nodes[0] = 0.0;
  w.points[0] = 0;
  w.nodes[1] = -a;
  w.points[1] = 1;
  w.used = 2;
  for (int j = 2; j < count_ && w.used < kMaxPoints; ++j) {
    // The path back to z_j must run along the same line: each stored step parallel or antiparallel
    // to the one after it (a turn ends the segment), and z_j itself near the line.
    const auto older = z(j - 1) - z(j);
    const auto later = z(j - 2) - z(j - 1);
    const double older2 = older.squaredNorm(), later2 = later.squaredNorm();
    if (older2 > 0.0 && later2 > 0.0 && !(std::abs(older.dot(later)) >= 0.9 * std::sqrt(older2 * later2)))
      break;
    const auto e = z(j) - z(0);
    const double s = e.dot(step) / a;
    if (!on_line(s, e.norm())) break;
    bool distinct = true;
    for (int i = 0; i < w.used; ++i) distinct = distinct && std::abs(s - w.nodes[i]) >= 0.1 * a;
    if (!distinct) continue;  // a revisited point: the newer solution is already a node
    w.nodes[w.used] = s;
    w.points[w.used] = j;
    ++w.used;
  }
  w.s_new = s_new;
  return true;
}

bool PathPredictor::curve_nodes(const VecX& z_new, Weights& w) const {
  const auto dz = z_new - z(0);
  const double a = (z(0) - z(1)).norm(), s_new = dz.norm();
  if (!goes_on(z(0) - z(1), dz) || !(s_new <= 2.0 * a)) return false;
  w.nodes[0] = 0.0;
  w.points[0] = 0;
  w.used = 1;
  for (int j = 1; j < count_ && w.used < kMaxPoints; ++j) {
    // Step j (from z_j to z_{j-1}) goes on into the one after it (into dz for the last step).
    const auto step = z(j - 1) - z(j);
    if (!(j == 1 ? goes_on(step, dz) : goes_on(step, z(j - 2) - z(j - 1)))) break;
    w.nodes[w.used] = w.nodes[w.used - 1] - step.norm();
    w.points[w.used] = j;
    ++w.used;
  }
  w.s_new = s_new;
  return w.used >= 2;
}

double PathPredictor::miss(const Weights& w, const VecX& z_new) const {
  double sum = 0.0;
  for (int k = 0; k < z_new.size(); ++k) {
    double e = -z_new[k];
    for (int i = 0; i < w.used; ++i) e += w.weights[i] * z(w.points[i])[k];
    sum += e * e;
  }
  return std::sqrt(sum);
}

bool PathPredictor::candidates(const VecX& z_new, Candidates& c) const {
  if (count_ < 2 || z_new.size() != z(0).size()) return false;
  c.by_line = line_nodes(z_new, c.line);
  c.by_curve = curve_nodes(z_new, c.curve);
  return c.by_line || c.by_curve;
}

PathPredictor::Weights PathPredictor::pick(const Candidates& c, int max_points, const VecX& z_new) const {
  Weights line = c.line, curve = c.curve;  // the first max_points nodes of each
  line.used = std::min(line.used, max_points);
  curve.used = std::min(curve.used, max_points);
  if (c.by_line) line.set_weights(line.s_new);
  if (c.by_curve) curve.set_weights(curve.s_new);
  // The curve only where it reproduces z_new clearly better (on a straight path both are exact).
  return c.by_curve && (!c.by_line || miss(curve, z_new) < 0.5 * miss(line, z_new)) ? curve : line;
}

VecX PathPredictor::combine(const Weights& w, const VecX& x_last) const {
  VecX out = w.weights[0] * x_last;
  for (int i = 1; i < w.used; ++i) out += w.weights[i] * x(w.points[i]);
  return out;
}

VecX PathPredictor::predict(const VecX& x_last, const VecX& z_new, bool* on_path) const {
  if (on_path) *on_path = false;
  last_prediction_valid_ = false;
  Candidates c;
  if (count_ < 2 || x_last.size() != x(1).size() || !candidates(z_new, c)) return x_last;
  if (on_path) *on_path = true;
  const Weights w = pick(c, order_, z_new);
  VecX out = combine(w, x_last);
  // Kept for accept (the order's error on this step, without combining again).
  last_prediction_ = out;
  last_z_ = z_new;
  last_prediction_valid_ = w.used == order_;  // x_last is x(0), the last accepted solution
  return out;
}

double PathPredictor::prediction_error(const Weights& w, const VecX& x_new) const {
  scratch_ = -x_new;
  for (int i = 0; i < w.used; ++i) scratch_ += w.weights[i] * x(w.points[i]);
  return scratch_.lpNorm<Eigen::Infinity>();
}

void PathPredictor::accept(const VecX& x_new, const VecX& z_new) {
  // The order: the current one or a neighbour (the lower and the higher in turn), whichever would have
  // come closer to x_new (max-abs; the current one on a tie), if both had the points they ask for; kept
  // while the current order lacks them (the start of a path, after a turn).
  Candidates c;
  if (count_ >= 2 && x_new.size() == x(0).size() && candidates(z_new, c)) {
    const int other = std::clamp(order_ + (try_higher_ ? 1 : -1), 2, kMaxPoints);
    try_higher_ = !try_higher_;
    const Weights current = pick(c, order_, z_new), neighbour = pick(c, other, z_new);
    if (other != order_ && current.used == order_ && neighbour.used == other) {
      const bool cached = last_prediction_valid_ && last_z_.size() == z_new.size() && last_z_ == z_new;
      const double error =
          cached ? (last_prediction_ - x_new).lpNorm<Eigen::Infinity>() : prediction_error(current, x_new);
      if (prediction_error(neighbour, x_new) < error) order_ = other;
    }
  }
  last_prediction_valid_ = false;
  newest_ = (newest_ + kMaxPoints - 1) % kMaxPoints;
  xs_[newest_] = x_new;
  zs_[newest_] = z_new;
  count_ = count_ < kMaxPoints ? count_ + 1 : kMaxPoints;
}

}  // namespace pcr::kinematics
