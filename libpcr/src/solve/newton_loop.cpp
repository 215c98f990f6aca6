// The shared Newton loop: checks, quasi-Newton, Newton with line search, Levenberg-Marquardt (see
// newton_loop.hpp).
#include "pcr/solve/newton_loop.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "pcr/core/error.hpp"

namespace pcr {

namespace {

// One pass over v: whether every entry is finite, the largest |entry| and the 2-norm.
struct VectorStats {
  bool finite;
  double max_abs, norm;
};
VectorStats stats_of(const VecX& v) {
  bool finite = true;
  double max_abs = 0.0, sum = 0.0;
  for (const double e : v) {
    const double a = std::abs(e);
    finite = finite && a <= std::numeric_limits<double>::max();  // false for inf and nan
    max_abs = std::max(max_abs, a);
    sum += a * a;
  }
  return {finite, max_abs, std::sqrt(sum)};
}

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0) {
  char buffer[240];
  std::snprintf(buffer, sizeof buffer, fmt, a, b, c);
  return buffer;
}

}  // namespace

NewtonLoop::NewtonLoop(const NewtonLoopOptions& options) : options_(options) {
  check(options);
}

void NewtonLoop::check(const NewtonLoopOptions& o) {
  require(o.tolerance > 0.0, "Newton options: tolerance = ", o.tolerance, " <= 0");
  require(o.max_iterations >= 0, "Newton options: max_iterations = ", o.max_iterations, " < 0");
  require(o.armijo > 0.0 && o.armijo < 1.0, "Newton options: armijo = ", o.armijo, " not in (0, 1)");
  require(o.backtrack > 0.0 && o.backtrack < 1.0, "Newton options: backtrack = ", o.backtrack,
          " not in (0, 1)");
  require(o.min_step > 0.0 && o.min_step <= 1.0, "Newton options: min_step = ", o.min_step, " not in (0, 1]");
  require(o.max_step > 0.0, "Newton options: max_step = ", o.max_step, " <= 0");
  require(o.stall_window >= 0, "Newton options: stall_window = ", o.stall_window, " < 0");
  require(o.stall_ratio > 0.0 && o.stall_ratio <= 1.0, "Newton options: stall_ratio = ", o.stall_ratio,
          " not in (0, 1]");
  require(o.lm_initial_damping > 0.0 && o.lm_damping_increase > 1.0 && o.lm_max_tries >= 1,
          "Newton options: Levenberg-Marquardt damping ", o.lm_initial_damping, ", increase ",
          o.lm_damping_increase, ", tries ", o.lm_max_tries, " (need > 0, > 1, >= 1)");
}

void NewtonLoop::resize(int n) {
  if (r_.size() == n) return;
  r_.resize(n);
  r_trial_.resize(n);
  dx_.resize(n);
  step_.resize(n);
  work_.resize(n);
  if (options_.quasi_newton == QuasiNewtonKind::Broyden) broyden_.resize(n);  // its storage only if used
}

NewtonLoopResult NewtonLoop::run(NonlinearSystem& system, const NewtonLoopLimits& limits, bool quasi_start) {
  require(limits.max_iterations >= 0, "Newton: max_iterations = ", limits.max_iterations, " < 0");
  require(limits.max_jacobian_evaluations >= 0,
          "Newton: max_jacobian_evaluations = ", limits.max_jacobian_evaluations, " < 0");
  Run run;
  run.system = &system;
  run.limits = limits;
  run.damping = options_.lm_initial_damping;
  resize(system.size());
  // Broyden updates kept from earlier solves serve only a path that goes on (continue_path) on their J0.
  if (!continue_path_ || !system.has_factorization()) broyden_.clear();
  continue_path_ = false;
  const bool quasi =
      options_.quasi_newton != QuasiNewtonKind::None && quasi_start && system.has_factorization();
  run.phase = quasi ? Phase::QuasiNewton : Phase::Newton;
  stall_history_.clear();
  if (options_.stall_window > 0) stall_history_.reserve(std::min(limits.max_iterations, 1000) + 1);
  if (!system.evaluate_start(options_.jacobian_with_trials && !quasi, r_)) {
    run.r_finite = false;
    finish(run, SolveStatus::Failed, "evaluation failed at the start point: " + system.evaluation_failure());
    return run.result;
  }
  measure_residual(run);
  for (;;) {
    Step next = check_point(run);
    if (next == Step::Done) break;
    if (run.phase == Phase::QuasiNewton) next = quasi_newton_step(run);
    if (next == Step::Done) break;
    if (next == Step::Newton && newton_step(run) == Step::Done) break;
  }
  return run.result;
}

void NewtonLoop::measure_residual(Run& run) {
  const VectorStats s = stats_of(r_);
  run.r_finite = s.finite;
  run.r_max = s.max_abs;
  run.r_norm = s.norm;
}

// Convergence and failure checks of the current point; Step::Newton: go on (the phase says which step).
NewtonLoop::Step NewtonLoop::check_point(Run& run) {
  switch (run.system->on_new_point(run.r_max, r_)) {
    case NonlinearSystem::PointUpdate::Unchanged: break;
    case NonlinearSystem::PointUpdate::Changed: measure_residual(run); break;
    case NonlinearSystem::PointUpdate::Failed:
      return finish(run, SolveStatus::Failed, "re-evaluation failed: " + run.system->evaluation_failure());
  }
  if (!run.r_finite) return finish(run, SolveStatus::Diverged, "non-finite residual");
  if (run.r_max <= options_.tolerance) return finish(run, SolveStatus::Converged, {});
  const int iterations = run.result.iterations;
  if (iterations >= run.limits.max_iterations)
    return stop_short(run, SolveStatus::MaxIterations,
                      format("no convergence in %.0f iterations (|r|max = %.3g)", iterations, run.r_max));
  // Stalled (e.g. at a local minimum of |r| with no root nearby, or on the way to another branch).
  const int window = options_.stall_window;
  if (window == 0) return Step::Newton;
  stall_history_.push_back(run.r_norm);
  const int seen = static_cast<int>(stall_history_.size());
  if (seen > window && run.r_norm > options_.stall_ratio * stall_history_[seen - 1 - window])
    return stop_short(run, SolveStatus::Failed,
                      format("stalled: |r| = %.3g fell by less than a factor %.3g in %.0f iterations",
                             run.r_norm, options_.stall_ratio, window));
  return Step::Newton;
}

NewtonLoop::Step NewtonLoop::quasi_newton_step(Run& run) {
  return options_.quasi_newton == QuasiNewtonKind::Broyden ? broyden_step(run) : chord_step(run);
}

// A Broyden step on J0; a fresh Jacobian (Step::Newton) when the steps stop contracting.
NewtonLoop::Step NewtonLoop::broyden_step(Run& run) {
  NonlinearSystem& system = *run.system;
  if (!run.broyden_step_ready) broyden_.start_sequence(system, r_);
  double norm = 0.0, max_abs = 0.0;
  const bool finite = try_point(run, broyden_.last_step(), false, &norm, &max_abs);
  // A step that lands within the tolerance is kept whatever the contraction test would say: near the
  // solution the corrections are dominated by round-off (|J0^-1| times the residual's noise), and a
  // fresh Jacobian there would be wasted.
  if (finite && max_abs <= options_.tolerance) {
    accept(run, norm, max_abs);
    run.broyden_step_ready = false;
    return Step::Next;
  }
  if (finite && broyden_.next_step(system, r_trial_, options_.broyden_contraction, work_)) {
    accept(run, norm, max_abs);
    run.broyden_step_ready = true;
    return Step::Next;
  }
  // Too slow or diverging: a fresh Jacobian, at the trial point if the step still reduced |r|.
  run.phase = Phase::Newton;
  run.broyden_step_ready = false;
  if (finite && norm < run.r_norm) {
    accept(run, norm, max_abs);
    return Step::Next;
  }
  return Step::Newton;
}

// A chord step -J0^-1 r; Newton from here on when it does not reduce |r| by chord_decrease.
NewtonLoop::Step NewtonLoop::chord_step(Run& run) {
  run.system->solve(r_, dx_);
  dx_ = -dx_;
  cap(*run.system, dx_);
  double norm = 0.0, max_abs = 0.0;
  if (dx_.allFinite() && try_point(run, dx_, false, &norm, &max_abs) &&
      norm < options_.chord_decrease * run.r_norm) {
    accept(run, norm, max_abs);
    return Step::Next;
  }
  run.phase = Phase::Newton;
  return Step::Newton;
}

// Fresh Jacobian, Newton direction, line search; Levenberg-Marquardt when that fails.
NewtonLoop::Step NewtonLoop::newton_step(Run& run) {
  NonlinearSystem& system = *run.system;
  NewtonLoopResult& result = run.result;
  if (result.jacobian_evaluations >= run.limits.max_jacobian_evaluations)
    return stop_short(run, SolveStatus::MaxIterations,
                      format("no convergence with %.0f Jacobian evaluations (|r|max = %.3g)",
                             run.limits.max_jacobian_evaluations, run.r_max));
  ++result.jacobian_evaluations;
  SystemStatus status = system.factorize(r_);
  if (system.jacobian_refreshes_residual()) measure_residual(run);
  if (options_.quasi_newton == QuasiNewtonKind::Broyden) broyden_.clear();  // they updated the old J0
  if (status.ok()) status = system.newton_direction(r_, dx_);
  if (status.ok()) {
    cap(system, dx_);
    double alpha = 1.0;
    if (line_search(run, &alpha)) {
      const VectorStats trial = stats_of(r_trial_);
      // Keep this factorisation for Broyden steps while they contract (the full Newton step is the
      // first step of the sequence: J0 s_0 = -r holds exactly).
      run.broyden_step_ready = false;
      if (options_.quasi_newton == QuasiNewtonKind::Broyden && alpha == 1.0) {
        broyden_.start_with_newton_step(dx_);
        run.broyden_step_ready = broyden_.next_step(system, r_trial_, options_.broyden_contraction, work_);
        if (run.broyden_step_ready) run.phase = Phase::QuasiNewton;
      }
      accept(run, trial.norm, trial.max_abs);
      return Step::Next;
    }
  }
  const bool lm = options_.levenberg_marquardt && (status.ok() || status.failure == SolveStatus::Singular) &&
                  system.dense_jacobian(jacobian_);
  if (lm && levenberg_marquardt_step(run)) return Step::Next;
  const std::string after_lm = lm ? "; no Levenberg-Marquardt step reduces |r| either" : "";
  if (!status.ok()) return finish(run, status.failure, status.message + after_lm);
  return stop_short(
      run, SolveStatus::Failed,
      format(options_.natural_monotonicity
                 ? "line search found no decrease of |r| nor of the Newton correction along the "
                   "Newton step (|r|max = %.3g): local minimum of |r| or inconsistent system"
                 : "line search found no decrease of |r| along the Newton step (|r|max = %.3g): "
                   "local minimum of |r| or inconsistent system",
             run.r_max) +
          after_lm);
}

bool NewtonLoop::line_search(Run& run, double* alpha_out) {
  NonlinearSystem& system = *run.system;
  const double dx_norm = options_.natural_monotonicity ? dx_.norm() : 0.0;
  for (double alpha = 1.0; alpha >= options_.min_step; alpha *= options_.backtrack) {
    if (alpha != 1.0) step_ = alpha * dx_;
    double norm = 0.0, max_abs = 0.0;
    *alpha_out = alpha;
    if (!try_point(run, alpha == 1.0 ? dx_ : step_, options_.jacobian_with_trials, &norm, &max_abs)) continue;
    if (norm <= (1.0 - options_.armijo * alpha) * run.r_norm) return true;
    if (!options_.natural_monotonicity) continue;
    // Simplified Newton correction with the same factorisation.
    system.solve(r_trial_, work_);
    if (work_.allFinite() && work_.norm() <= (1.0 - 0.5 * alpha) * dx_norm) return true;
  }
  return false;
}

bool NewtonLoop::levenberg_marquardt_step(Run& run) {
  NonlinearSystem& system = *run.system;
  const MatX& J = jacobian_;  // newton_step copied it
  normal_.noalias() = J.transpose() * J;
  gradient_.noalias() = J.transpose() * r_;
  marquardt_ = normal_.diagonal().cwiseMax(1e-12 * std::max(1.0, normal_.diagonal().maxCoeff()));
  auto direction = [&](double mu) {
    damped_ = normal_;
    damped_.diagonal() += mu * marquardt_;
    ldlt_.compute(damped_);
    dx_ = -ldlt_.solve(gradient_);
  };
  double mu = options_.lm_keep_damping ? run.damping : options_.lm_initial_damping;
  const bool capped = std::isfinite(options_.max_step);
  for (int k = 0; k < options_.lm_max_tries; ++k) {
    // Fit the step to the cap (raising the damping is cheap: no evaluation), then try it.
    direction(mu);
    if (capped && options_.lm_cap_by_damping) {
      while (system.step_size(dx_) > options_.max_step && mu < 1e12)
        direction(mu *= options_.lm_damping_increase);
    } else if (dx_.allFinite()) {
      cap(system, dx_);
    }
    double norm = 0.0, max_abs = 0.0;
    if (dx_.allFinite() && try_point(run, dx_, options_.jacobian_with_trials, &norm, &max_abs) &&
        norm < run.r_norm) {
      run.damping = std::max(mu / 3.0, 1e-12);
      accept(run, norm, max_abs);
      return true;
    }
    mu *= options_.lm_damping_increase;
  }
  run.damping = mu;
  return false;
}

bool NewtonLoop::try_point(Run& run, const VecX& step, bool with_jacobian, double* norm, double* max_abs) {
  if (!run.system->evaluate_trial(step, with_jacobian, r_trial_)) return false;
  const VectorStats s = stats_of(r_trial_);
  *norm = s.norm;
  *max_abs = s.max_abs;
  return s.finite;
}

// The trial point becomes the current one: the iteration's step is taken.
void NewtonLoop::accept(Run& run, double norm, double max_abs) {
  ++run.result.iterations;
  run.system->accept_trial();
  r_.swap(r_trial_);
  run.r_finite = true;
  run.r_norm = norm;
  run.r_max = max_abs;
}

void NewtonLoop::cap(const NonlinearSystem& system, VecX& dx) const {
  if (!std::isfinite(options_.max_step)) return;
  const double size = system.step_size(dx);
  if (size > options_.max_step) dx *= options_.max_step / size;
}

NewtonLoop::Step NewtonLoop::stop_short(Run& run, SolveStatus status, std::string message) {
  double bound = 0.0;
  if (!run.r_finite || !run.system->within_round_off(r_, options_.tolerance, bound))
    return finish(run, status, std::move(message));
  run.result.round_off_bound = bound;
  return finish(run, SolveStatus::Converged,
                format("converged to the round-off of the residuals: |r|max = %.3g above the tolerance %.3g, "
                       "within the round-off bound of each row (largest %.3g)",
                       run.r_max, options_.tolerance, bound));
}

NewtonLoop::Step NewtonLoop::finish(Run& run, SolveStatus status, std::string message) {
  run.result.status = status;
  run.result.message = std::move(message);
  run.result.residual_max_abs = run.r_finite ? run.r_max : std::numeric_limits<double>::infinity();
  return Step::Done;
}

}  // namespace pcr
