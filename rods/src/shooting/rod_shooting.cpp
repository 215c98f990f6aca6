#include "pcr/rods/shooting/rod_shooting.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "pcr/core/error.hpp"
#include "shooting_ends.hpp"

namespace pcr {

using shooting::Mat6;
using shooting::Vec6;

IntegratorOptions ShootingOptions::integrator_options() const {
  IntegratorOptions o;
  o.method = integrator;
  o.rk4_steps = rk4_steps;
  o.rel_tol = rel_tol;
  o.abs_tol = abs_tol;
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
  return ShootingState::from_vector(rod_single_step(*ode_, s[i], h, states[i].to_vector(), method_));
}

std::vector<ShootingState> ShootingSolution::sample(const std::vector<double>& s_values) const {
  std::vector<ShootingState> out;
  out.reserve(s_values.size());
  for (double v : s_values) out.push_back(at(v));
  return out;
}

namespace {

void check_options(const ShootingOptions& o) {
  require(std::isfinite(o.residual_tolerance) && o.residual_tolerance > 0.0,
          "shooting: residual_tolerance must be positive, got ", o.residual_tolerance);
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

// One evaluation of the shooting map z -> r(z) at a base state.
struct Evaluation {
  bool ok = false;
  std::string message;
  Vec6 residual = Vec6::Zero();  ///< scaled
  Mat6 jacobian = Mat6::Zero();  ///< scaled
  bool has_jacobian = false;
  std::vector<double> mesh;  ///< accepted steps of an adaptive integration (empty otherwise)
  RodStateVector tip;
  int steps = 0;
};

class ShootingProblem {
 public:
  ShootingProblem(const RodModel& model, const IntegratorOptions& integrator)
      : model_(model),
        ode_(model),
        integrator_(integrator),
        scale_(shooting::residual_scale(model.tip, ode_)),
        unknown_scale_(shooting::unknown_scale(model.base, ode_)) {}

  const RodModel& model() const { return model_; }
  const RodOde& ode() const { return ode_; }
  const Vec6& scale() const { return scale_; }
  const Vec6& unknown_scale() const { return unknown_scale_; }

  // The residual at a base state, and its Jacobian (variational equations, ~6x the cost) if asked.
  // Dormand-Prince: on the given mesh if any (no error control), else adaptively, returning the
  // accepted steps in e.mesh.
  Evaluation evaluate(const RodStateVector& y0, bool with_jacobian, const std::vector<double>* mesh) const {
    Evaluation e;
    e.has_jacobian = with_jacobian;
    IntegrationReport report;
    const bool on_mesh = mesh && integrator_.method == IntegratorMethod::DormandPrince;
    RodTrajectory trajectory;
    RodTrajectory* record =
        (!on_mesh && integrator_.method == IntegratorMethod::DormandPrince) ? &trajectory : nullptr;
    if (with_jacobian) {
      RodStateWithTangents Y;
      shooting::base_tangents(model_.base, y0, Y);
      report = on_mesh ? integrate_rod_on_mesh(ode_, *mesh, Y, integrator_.method)
                       : integrate_rod(ode_, 0.0, model_.length, Y, integrator_, record);
      e.tip = Y.col(0);
      if (report.success && Y.allFinite())
        e.jacobian = scale_.cwiseInverse().asDiagonal() * shooting::tip_residual_jacobian(model_.tip, Y);
    } else {
      e.tip = y0;
      report = on_mesh ? integrate_rod_on_mesh(ode_, *mesh, e.tip, integrator_.method)
                       : integrate_rod(ode_, 0.0, model_.length, e.tip, integrator_, record);
    }
    e.mesh = std::move(trajectory.s);
    e.steps = report.steps;
    if (!report.success || !e.tip.allFinite()) {
      e.message = report.success ? "non-finite tip state" : report.message;
      return e;
    }
    e.residual = shooting::tip_residual(model_.tip, e.tip).cwiseQuotient(scale_);
    e.ok = e.residual.allFinite() && e.jacobian.allFinite();
    if (!e.ok) e.message = "non-finite residual";
    return e;
  }

 private:
  RodModel model_;
  RodOde ode_;
  IntegratorOptions integrator_;
  Vec6 scale_;
  Vec6 unknown_scale_;
};

struct NewtonOutcome {
  SolveStatus status = SolveStatus::Failed;
  int iterations = 0;
  std::string message;
  Evaluation last;           ///< at the returned base state
  std::vector<double> mesh;  ///< the frozen Dormand-Prince mesh (empty if none)
};

// Newton with backtracking line search on |r|^2; Levenberg-Marquardt (Marquardt's scaling
// diag(J^T J), Nocedal & Wright §10.3) when the Newton direction fails or J is singular.
NewtonOutcome solve_newton(const ShootingProblem& problem, RodStateVector& y0, const ShootingOptions& o) {
  NewtonOutcome out;
  const RodEnd& base = problem.model().base;
  // Dormand-Prince: once close to the root, the step sequence is frozen so that the shooting map is
  // smooth and Newton converges to round-off. The mesh was chosen adaptively for an iterate within
  // freeze_mesh_below of the root, so it suits the answer as well as a fresh adaptive one would
  // (a fresh one differs at the level of the integration tolerance, by discrete step events).
  const bool adaptive = o.integrator == IntegratorMethod::DormandPrince;
  std::vector<double>& mesh = out.mesh;
  bool frozen = false;
  auto mesh_in_use = [&]() { return frozen ? &mesh : nullptr; };
  Evaluation current = problem.evaluate(y0, false, nullptr);
  if (!current.ok) {
    out.status = SolveStatus::Failed;
    out.message = "integration failed at the initial guess: " + current.message;
    return out;
  }
  double mu = 1e-3;             // LM damping relative to diag(J^T J)
  std::vector<double> history;  // |r| per iteration, for stall detection
  while (true) {
    const double r_norm = current.residual.norm();
    const double r_max = current.residual.cwiseAbs().maxCoeff();
    history.push_back(r_norm);
    if (adaptive && !frozen && r_max <= o.freeze_mesh_below && !current.mesh.empty()) {
      mesh = current.mesh;  // current was integrated adaptively on exactly this mesh
      frozen = true;
    }
    if (r_max <= o.residual_tolerance) {
      out.status = SolveStatus::Converged;
      break;
    }
    if (out.iterations >= o.max_iterations) {
      out.status = SolveStatus::MaxIterations;
      out.message = "max_iterations reached";
      break;
    }
    // Stalled (e.g. at a local minimum of |r| with no root nearby): hand over to load stepping.
    const int window = o.stall_window;
    if (window > 0 && static_cast<int>(history.size()) > window &&
        r_norm > o.stall_ratio * history[history.size() - 1 - window]) {
      std::ostringstream msg;
      msg << "stalled: |r| = " << r_norm << " fell by less than a factor " << o.stall_ratio << " in "
          << window << " iterations";
      out.status = SolveStatus::Failed;
      out.message = msg.str();
      break;
    }
    ++out.iterations;
    if (!current.has_jacobian) {
      current = problem.evaluate(y0, true, mesh_in_use());
      if (!current.ok) {
        out.status = SolveStatus::Failed;
        out.message = "integration of the variational equations failed: " + current.message;
        break;
      }
    }
    bool accepted = false;
    // Trust-region-like cap: no unknown moves by more than max_step of its scale per step.
    auto capped = [&](Vec6 dz) {
      const double size = dz.cwiseQuotient(problem.unknown_scale()).cwiseAbs().maxCoeff();
      if (size > o.max_step) dz *= o.max_step / size;
      return dz;
    };
    auto try_step = [&](const Vec6& dz, double sufficient_decrease) {
      if (!dz.allFinite()) return false;
      RodStateVector y_trial = y0;
      shooting::retract_base(base, dz, y_trial);
      Evaluation trial = problem.evaluate(y_trial, false, mesh_in_use());  // the Jacobian once accepted
      if (!trial.ok || !(trial.residual.norm() < (1.0 - sufficient_decrease) * r_norm)) return false;
      y0 = y_trial;
      current = std::move(trial);
      return true;
    };
    const Eigen::PartialPivLU<Mat6> lu(current.jacobian);
    const double rcond = lu.rcond();
    if (rcond > 1e-14) {
      const Vec6 dz = capped(-lu.solve(current.residual));
      for (double alpha = 1.0; alpha >= 1.0 / 16 && !accepted; alpha *= 0.5)
        accepted = try_step(alpha * dz, 1e-4 * alpha);
    }
    if (!accepted && o.levenberg_marquardt) {
      const Mat6 JtJ = current.jacobian.transpose() * current.jacobian;
      const Vec6 g = current.jacobian.transpose() * current.residual;
      const Vec6 d = JtJ.diagonal().cwiseMax(1e-12 * std::max(1.0, JtJ.diagonal().maxCoeff()));
      auto lm_step = [&](double damping) {
        Mat6 A = JtJ;
        A.diagonal() += damping * d;
        return Vec6(-A.ldlt().solve(g));
      };
      auto step_size = [&](const Vec6& dz) {
        return dz.cwiseQuotient(problem.unknown_scale()).cwiseAbs().maxCoeff();
      };
      for (int k = 0; k < 30 && !accepted; ++k) {
        // Raise the damping until the step fits in the cap (cheap: no integration), then try it.
        Vec6 dz = lm_step(mu);
        while (step_size(dz) > o.max_step && mu < 1e12) dz = lm_step(mu *= 4.0);
        accepted = try_step(dz, 0.0);
        mu = accepted ? std::max(mu / 3.0, 1e-12) : mu * 4.0;
      }
    }
    if (!accepted) {
      std::ostringstream msg;
      msg << "no step reduces the residual (Jacobian rcond = " << rcond << ")";
      out.status = rcond <= 1e-14 ? SolveStatus::Singular : SolveStatus::Failed;
      out.message = msg.str();
      break;
    }
  }
  out.last = current;
  return out;
}

// Unloaded tip state of a clamped-base rod (n = m = 0 at the base, no distributed loads).
bool unloaded_tip(const RodModel& model, const IntegratorOptions& integrator, RodStateVector& tip) {
  const RodModel unloaded = shooting::model_at_load(model, 0.0, nullptr);
  const RodOde ode(unloaded);
  ShootingState base;
  base.p = model.base.position;
  base.q = model.base.orientation.normalized();
  tip = base.to_vector();
  return integrate_rod(ode, 0.0, model.length, tip, integrator).success && tip.allFinite();
}

}  // namespace

ShootingSolution solve_rod_shooting(const RodModel& model, const ShootingOptions& options,
                                    const ShootingSolution* warm_start) {
  const auto t_start = std::chrono::steady_clock::now();
  model.validate();
  check_options(options);
  const IntegratorOptions integrator = options.integrator_options();
  check_integrator_options(integrator);  // validates the integrator options (throws InputError)

  ShootingSolution solution;
  ShootingSummary& summary = solution.summary;
  summary.solver = std::string("shooting-") + to_string(options.integrator);

  // Full load first, from the warm start or the unloaded-rod guess.
  const ShootingProblem full(model, integrator);
  RodStateVector y0 = warm_start ? warm_start->base.to_vector() : shooting::initial_base_guess(model);
  if (!y0.allFinite() || y0.segment<4>(RodStateIndex::q).norm() < 1e-12)
    y0 = shooting::initial_base_guess(model);
  shooting::enforce_base(model.base, y0);
  NewtonOutcome outcome = solve_newton(full, y0, options);
  summary.iterations = outcome.iterations;
  summary.load_steps = 1;

  if (outcome.status != SolveStatus::Converged && options.load_stepping) {
    // Continuation in the load factor: lambda from 0 to 1, increments doubled after a success and
    // halved after a failure, each solve warm-started from the last converged one.
    RodStateVector tip_free;
    const bool interpolate_tip = model.base.kind == RodEndKind::Clamped &&
                                 model.tip.kind != RodEndKind::Free &&
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
      const NewtonOutcome step = solve_newton(ShootingProblem(loaded, integrator), y, options);
      summary.iterations += step.iterations;
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
  }
  summary.status = outcome.status;
  summary.message = outcome.message;

  // Final integration at full load from the returned base state, with the trajectory.
  solution.ode_ = std::make_shared<RodOde>(model);
  solution.method_ = options.integrator;
  RodStateVector y = y0;
  RodTrajectory trajectory;
  RodTrajectory* record = options.store_trajectory ? &trajectory : nullptr;
  // On the mesh Newton converged on (if frozen), so that the reported residual is the converged one.
  const bool on_mesh = outcome.status == SolveStatus::Converged && !outcome.mesh.empty();
  const IntegrationReport report =
      on_mesh ? integrate_rod_on_mesh(*solution.ode_, outcome.mesh, y, options.integrator, record)
              : integrate_rod(*solution.ode_, 0.0, model.length, y, integrator, record);
  solution.base = ShootingState::from_vector(y0);
  if (report.success && y.allFinite()) {
    solution.tip = ShootingState::from_vector(y);
    const Vec6 r = shooting::tip_residual(model.tip, y);
    summary.residual_max_abs = r.cwiseAbs().maxCoeff();
    summary.residual_scaled_max_abs = r.cwiseQuotient(full.scale()).cwiseAbs().maxCoeff();
    summary.integration_steps = report.steps;
    solution.s = trajectory.s;
    solution.states.reserve(trajectory.y.size());
    for (const RodStateVector& state : trajectory.y) solution.states.push_back(ShootingState::from_vector(state));
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
