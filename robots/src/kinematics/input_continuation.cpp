// Continuation in the actuation inputs (see input_continuation.hpp).
#include "input_continuation.hpp"

#include <algorithm>
#include <cmath>

namespace pcr::kinematics {

namespace {

/// The step after a converged one: `step` as it was asked for, `taken` as it was taken (shorter at the end
/// of the line) (LineSteps). after_failure: the attempt before this one failed; then the error rule does
/// not grow the step (near a fold the predictor's error stays small up to the step that fails, and
/// growing again at once costs a failed step, 4 fresh Jacobians, every other step).
double next_step(const LineSteps& steps, double step, double taken, const SolveSummary& s,
                 const VecX& weights, const VecX& predicted, const VecX& converged, bool secant,
                 bool after_failure) {
  if (!(steps.predictor_error > 0.0) || weights.size() != converged.size())
    return step * (s.iterations <= 4 ? 2.0 : 1.25);
  const double error = (converged - predicted).cwiseProduct(weights).cwiseAbs().maxCoeff();
  const double ratio = error > 0.0 ? steps.predictor_error / error : 16.0;
  return taken * std::clamp(secant ? std::sqrt(ratio) : ratio, 0.5, after_failure ? 1.0 : 4.0);
}

}  // namespace

ContinuationResult continue_along_line(const SolveAtInputs& solve_at, const VecX& u0, const VecX& u1,
                                       int step_jacobians, VecX& x, const LineSteps& steps,
                                       const ContinuationWeights& weights) {
  ContinuationResult r;
  double t = 0.0, step = steps.first, t_prev = -1.0;
  VecX xc = x, x_prev, predicted;
  bool failed = false;  // the last attempt failed
  while (t < 1.0 && step > 1e-4 && r.steps < 200) {
    const double target = std::min(1.0, t + step);
    VecX trial = xc;
    const bool secant = t_prev >= 0.0;
    if (secant) trial += ((target - t) / (t - t_prev)) * (xc - x_prev);  // secant in t
    predicted = trial;
    r.last = solve_at(u0 + target * (u1 - u0), trial, step_jacobians, target < 1.0);
    r.iterations += r.last.iterations;
    r.jacobian_evaluations += r.last.jacobian_evaluations;
    ++r.steps;
    if (r.last.converged()) {
      step = next_step(steps, step, target - t, r.last, weights, predicted, trial, secant, failed);
      failed = false;
      x_prev.swap(xc);
      xc.swap(trial);
      t_prev = t;
      t = target;
    } else {
      failed = true;
      step *= steps.cut;
    }
  }
  r.converged = t >= 1.0 && r.last.converged();
  if (r.converged)
    x = xc;
  else
    r.stopped_at = "t = " + std::to_string(t);
  return r;
}

ContinuationResult continue_one_input_at_a_time(const SolveAtInputs& solve_at, const VecX& u0, const VecX& u1,
                                                int direct_jacobians, int step_jacobians, int max_orders,
                                                VecX& x, const LineSteps& steps) {
  if (u0 == u1) return continue_along_line(solve_at, u0, u1, step_jacobians, x, steps);  // no leg to take
  ContinuationResult total;
  const int n = static_cast<int>(u0.size());
  for (int first = 0; first < std::min(n, max_orders); ++first) {
    VecX xc = x, u = u0;
    bool ok = true;
    for (int k = 0; k < n && ok; ++k) {
      const int i = (first + k) % n;
      if (u[i] == u1[i]) continue;
      VecX next = u;
      next[i] = u1[i];
      // A direct solve first: it is cheap when the leg is short, and from the end of the last leg it may
      // land past a fold where small steps cannot go.
      VecX direct = xc;
      total.last = solve_at(next, direct, direct_jacobians, false);
      total.iterations += total.last.iterations;
      total.jacobian_evaluations += total.last.jacobian_evaluations;
      ++total.steps;
      if (total.last.converged()) {
        xc.swap(direct);
        u = next;
        continue;
      }
      const ContinuationResult leg = continue_along_line(solve_at, u, next, step_jacobians, xc, steps);
      total.steps += leg.steps;
      total.iterations += leg.iterations;
      total.jacobian_evaluations += leg.jacobian_evaluations;
      total.last = leg.last;
      ok = leg.converged;
      if (ok)
        u = next;
      else
        total.stopped_at = "input " + std::to_string(i) + " at " + leg.stopped_at;
    }
    if (ok) {
      total.converged = true;
      total.stopped_at.clear();
      x = xc;
      return total;
    }
  }
  return total;
}

}  // namespace pcr::kinematics
