#include "pcr/rods/shooting/rod_shooting.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "pcr/core/error.hpp"
#include "pcr/rods/shooting/joint_ends.hpp"
#include "rod_shooting_system.hpp"
#include "shooting_ends.hpp"

namespace pcr {

using shooting::Mat6;
using shooting::Vec6;

IntegratorOptions ShootingOptions::integrator_options() const {
  IntegratorOptions o;
  o.method = integrator;
  o.rk4_steps = rk4_steps;
  o.relative_tolerance = integration_relative_tolerance;
  o.absolute_tolerance = integration_absolute_tolerance;
  o.min_step_fraction = min_step_fraction;
  o.max_steps = max_integration_steps;
  return o;
}

ShootingState ShootingSolution::at(double s_query) const {
  require(ode_ && !s.empty(),
          "ShootingSolution::at: no stored trajectory (store_trajectory was off or the solve ",
          "did not produce one)");
  s_query = checked_arc_length(s_query, ode_->length(), "ShootingSolution::at");
  // Last stored step at or before s_query, then one step of the solve's method.
  const auto it = std::upper_bound(s.begin(), s.end(), s_query);
  const size_t i = it == s.begin() ? 0 : static_cast<size_t>(it - s.begin()) - 1;
  const double h = s_query - s[i];
  if (h <= 0.0) return states[i];
  // The states hold the section's n, m; the ODE a drawn rod's N, M (rod_ode.hpp).
  RodStateVector y = states[i].to_vector();
  ode_->to_effective(y);
  y = rod_single_step(*ode_, s[i], h, y, method_);
  ode_->to_section(y);
  return ShootingState::from_vector(y);
}

std::vector<ShootingState> ShootingSolution::sample(const std::vector<double>& s_values) const {
  std::vector<ShootingState> out;
  out.reserve(s_values.size());
  for (double v : s_values) out.push_back(at(v));
  return out;
}

namespace {

void check_options(const ShootingOptions& o) {
  require(std::isfinite(o.tolerance) && o.tolerance > 0.0, "shooting: tolerance must be positive, got ",
          o.tolerance);
  require(std::isfinite(o.max_step) && o.max_step > 0.0, "shooting: max_step must be positive, got ",
          o.max_step);
  require(o.stall_window >= 0, "shooting: stall_window must be >= 0, got ", o.stall_window);
  require(o.stall_ratio > 0.0 && o.stall_ratio <= 1.0, "shooting: stall_ratio must lie in (0, 1], got ",
          o.stall_ratio);
  require(o.max_iterations >= 1, "shooting: max_iterations must be >= 1, got ", o.max_iterations);
  require(o.initial_load_increment > 0.0 && o.initial_load_increment <= 1.0,
          "shooting: initial_load_increment must lie in (0, 1], got ", o.initial_load_increment);
  require(o.max_load_increment >= o.initial_load_increment && o.max_load_increment <= 1.0,
          "shooting: max_load_increment must lie in [initial_load_increment, 1], got ", o.max_load_increment);
  require(o.min_load_increment > 0.0 && o.min_load_increment <= o.initial_load_increment,
          "shooting: min_load_increment must lie in (0, initial_load_increment], got ", o.min_load_increment);
  require(o.max_load_steps >= 1, "shooting: max_load_steps must be >= 1, got ", o.max_load_steps);
}

// Unloaded tip state of a clamped-base rod (n = m = 0 at the base, no distributed loads).
bool unloaded_tip(const RodModel& model, const IntegratorOptions& integrator, RodStateVector& tip) {
  const RodModel unloaded = shooting::model_at_load(model, 0.0, nullptr);
  const RodOde ode(unloaded);
  ShootingState base;
  base.p = model.base.position;
  base.q = model.base.orientation.normalized();
  tip = base.to_vector();
  ode.to_effective(tip);
  const bool ok = integrate_rod(ode, 0.0, model.length, tip, integrator).success && tip.allFinite();
  ode.to_section(tip);
  return ok;
}

// Continuation in the load factor after a failed full-load solve: lambda from 0 to 1, increments
// doubled after a success and halved after a failure, each solve warm-started from the last converged
// one. y0: the returned base state (the last converged partial load if lambda = 1 is not reached).
shooting::NewtonOutcome load_continuation(const RodModel& model, const IntegratorOptions& integrator,
                                          const ShootingOptions& options, SolveSummary& summary,
                                          RodStateVector& y0, shooting::NewtonOutcome outcome) {
  RodStateVector tip_free;
  const bool interpolate_tip = model.base.kind == RodEndKind::Clamped && model.tip.kind != RodEndKind::Free &&
                               unloaded_tip(model, integrator, tip_free);
  const RodStateVector* tip_ptr = interpolate_tip ? &tip_free : nullptr;
  double lambda_done = 0.0, increment = options.initial_load_increment;
  RodStateVector y_done = shooting::initial_base_guess(shooting::model_at_load(model, 0.0, tip_ptr));
  // No secant predictor: it overshoots on concave load paths (Bisshopp-Drucker m(0) ~ sqrt(alpha))
  // and lands on another equilibrium branch (measured at alpha = 100).
  bool first = true;
  while (lambda_done < 1.0 && summary.load_steps < options.max_load_steps) {
    const double lambda = std::min(1.0, lambda_done + increment);
    const RodModel loaded = shooting::model_at_load(model, lambda, tip_ptr);
    RodStateVector y = first ? shooting::initial_base_guess(loaded) : y_done;
    shooting::enforce_base(loaded.base, y);
    const shooting::NewtonOutcome step = shooting::solve_newton(loaded, integrator, y, options);
    summary.iterations += step.iterations;
    summary.jacobian_evaluations += step.jacobian_evaluations;
    ++summary.load_steps;
    if (step.status == SolveStatus::Converged) {
      lambda_done = lambda;
      y_done = y;
      first = false;
      increment = std::min(2.0 * increment, options.max_load_increment);
      if (lambda == 1.0) outcome = step;
    } else {
      increment *= 0.5;
      if (increment < options.min_load_increment) {
        outcome = step;
        break;
      }
    }
  }
  if (lambda_done == 1.0) {
    y0 = y_done;
  } else if (!first) {
    y0 = y_done;  // the last converged partial load: finite and meaningful
    if (outcome.status == SolveStatus::Converged) outcome.status = SolveStatus::MaxIterations;
  }
  if (lambda_done < 1.0) {
    std::ostringstream msg;
    msg << "load stepping stopped at lambda = " << lambda_done << " after " << summary.load_steps
        << " solves";
    if (!outcome.message.empty()) msg << "; last: " << outcome.message;
    outcome.message = msg.str();
    if (outcome.status == SolveStatus::Converged) outcome.status = SolveStatus::MaxIterations;
  }
  return outcome;
}

}  // namespace

ShootingSolution solve_rod_shooting(const RodModel& model, const ShootingOptions& options,
                                    const ShootingSolution* warm_start) {
  const auto t_start = std::chrono::steady_clock::now();
  model.validate();
  for (const auto& [end, which] : {std::make_pair(&model.base, "base"), std::make_pair(&model.tip, "tip")})
    if (joint_end::is_joint(end->kind))
      joint_end::axes_of(end->kind, end->axis, "shooting: rod '" + model.name + "' " + which);
  check_options(options);
  const IntegratorOptions integrator = options.integrator_options();
  check_integrator_options(integrator);  // validates the integrator options (throws InputError)

  ShootingSolution solution;
  SolveSummary& summary = solution.summary;
  summary.solver = std::string("shooting-") + to_string(options.integrator);

  // Full load first, from the warm start or the unloaded-rod guess.
  RodStateVector y0 = warm_start ? warm_start->base.to_vector() : shooting::initial_base_guess(model);
  if (!y0.allFinite() || y0.segment<4>(RodStateIndex::q).norm() < 1e-12)
    y0 = shooting::initial_base_guess(model);
  shooting::enforce_base(model.base, y0);
  shooting::NewtonOutcome outcome = shooting::solve_newton(model, integrator, y0, options);
  summary.iterations = outcome.iterations;
  summary.jacobian_evaluations = outcome.jacobian_evaluations;
  summary.load_steps = 1;

  if (outcome.status != SolveStatus::Converged && options.load_stepping)
    outcome = load_continuation(model, integrator, options, summary, y0, std::move(outcome));
  summary.status = outcome.status;
  summary.message = outcome.message;

  // Final integration at full load from the returned base state, with the trajectory.
  solution.ode_ = std::make_shared<RodOde>(model);
  solution.method_ = options.integrator;
  RodStateVector y = y0;
  solution.ode_->to_effective(y);  // the ODE's state (rod_ode.hpp: N, M of a drawn rod)
  RodTrajectory trajectory;
  RodTrajectory* record = options.store_trajectory ? &trajectory : nullptr;
  // On the mesh Newton converged on (if frozen), so that the reported residual is the converged one.
  const bool on_mesh = outcome.status == SolveStatus::Converged && !outcome.mesh.empty();
  const IntegrationReport report =
      on_mesh ? integrate_rod_on_mesh(*solution.ode_, outcome.mesh, y, options.integrator, record)
              : integrate_rod(*solution.ode_, 0.0, model.length, y, integrator, record);
  solution.base = ShootingState::from_vector(y0);
  solution.ode_->to_section(y);
  if (report.success && y.allFinite()) {
    solution.tip = ShootingState::from_vector(y);
    const Vec6 r = shooting::tip_residual(model.tip, y);
    summary.residual_max_abs = r.cwiseAbs().maxCoeff();
    summary.residual_scaled_max_abs =
        r.cwiseQuotient(shooting::residual_scale(model.tip, *solution.ode_)).cwiseAbs().maxCoeff();
    summary.integration_steps = report.steps;
    solution.s = trajectory.s;
    solution.states.reserve(trajectory.y.size());
    for (RodStateVector state : trajectory.y) {
      solution.ode_->to_section(state);
      solution.states.push_back(ShootingState::from_vector(state));
    }
  } else {
    // Never report NaN: keep the base state, no tip, and say why.
    solution.tip = solution.base;
    summary.residual_max_abs = summary.residual_scaled_max_abs = std::numeric_limits<double>::max();
    if (summary.status == SolveStatus::Converged) summary.status = SolveStatus::Failed;
    summary.message +=
        (summary.message.empty() ? "" : "; ") + std::string("final integration failed: ") + report.message;
  }
  summary.wall_time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return solution;
}

}  // namespace pcr
