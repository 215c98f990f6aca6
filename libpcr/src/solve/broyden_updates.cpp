// Broyden (QNERR) updates of a factorised Jacobian's inverse (see broyden_updates.hpp).
#include "pcr/solve/broyden_updates.hpp"

#include <cmath>
#include <limits>

namespace pcr {

void BroydenUpdates::resize(int n) {
  num_steps_ = 0;
  if (!steps_.empty() && steps_[0].size() == n) return;
  steps_.assign(kMaxSteps, VecX::Zero(n));
  starts_.assign(kMaxSteps, 1);
  step_norms2_.assign(kMaxSteps, 0.0);
}

// H = prod_j (I + s_{j+1} s_j^T / |s_j|^2) J0^-1: one factor per pair of consecutive steps of a sequence.
void BroydenUpdates::solve(NonlinearSystem& system, const VecX& b, VecX& x) const {
  system.solve(b, x);
  for (int j = 0; j + 1 < num_steps_; ++j)
    if (!starts_[j + 1]) x += steps_[j + 1] * (steps_[j].dot(x) / step_norms2_[j]);
}

void BroydenUpdates::drop_old_steps() {
  int first = num_steps_;
  for (int j = 0; j < num_steps_; ++j) {
    if (starts_[j] && num_steps_ - j <= kCarriedSteps) {
      first = j;
      break;
    }
  }
  for (int j = first; j < num_steps_; ++j) {
    steps_[j - first].swap(steps_[j]);
    step_norms2_[j - first] = step_norms2_[j];
    starts_[j - first] = starts_[j];
  }
  num_steps_ -= first;
}

const VecX& BroydenUpdates::start_sequence(NonlinearSystem& system, const VecX& r) {
  drop_old_steps();
  VecX& s0 = steps_[num_steps_];
  solve(system, r, s0);
  s0 = -s0;
  step_norms2_[num_steps_] = s0.squaredNorm();
  starts_[num_steps_++] = 1;
  return s0;
}

void BroydenUpdates::start_with_newton_step(const VecX& s) {
  steps_[0] = s;
  step_norms2_[0] = s.squaredNorm();
  starts_[0] = 1;
  num_steps_ = 1;
}

bool BroydenUpdates::next_step(NonlinearSystem& system, const VecX& r_new, double contraction, VecX& work) {
  if (num_steps_ >= kMaxSteps) return false;
  solve(system, r_new, work);
  work = -work;
  const VecX& s_k = steps_[num_steps_ - 1];
  const double s2 = step_norms2_[num_steps_ - 1];
  // One pass for finiteness and |w|.
  double w2 = 0.0;
  bool finite = true;
  for (const double e : work) {
    finite = finite && std::abs(e) <= std::numeric_limits<double>::max();
    w2 += e * e;
  }
  if (!finite || !(s2 > 0.0) || !(std::sqrt(w2) <= contraction * std::sqrt(s2))) return false;
  const double alpha = s_k.dot(work) / s2;
  starts_[num_steps_] = 0;
  steps_[num_steps_] = work / (1.0 - alpha);
  step_norms2_[num_steps_] = steps_[num_steps_].squaredNorm();
  ++num_steps_;
  return true;
}

}  // namespace pcr
