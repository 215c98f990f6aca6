// Robot FK / IK by shooting: see shooting_robot_solver.hpp for the unknowns, residuals and strategy.
// The model's setup is in robot_shooting_model.cpp, the unknowns in unknown_layout.cpp, the residual
// rows in coupling_residuals.cpp, the shooting map in robot_shooting_system.cpp; here: the solves
// (the shared Newton loop), continuation and results.
#include "pcr/robots/shooting/shooting_robot_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/solve/newton_loop.hpp"
#include "robot_shooting_system.hpp"

namespace pcr {

using shooting_robot::RodSetup;
using shooting_robot::State;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Counts and time of an earlier attempt added to a solve's summary.
void add_attempt(SolveSummary& into, const SolveSummary& attempt) {
  into.iterations += attempt.iterations;
  into.jacobian_evaluations += attempt.jacobian_evaluations;
  into.wall_time_seconds += attempt.wall_time_seconds;
}

NewtonLoopOptions loop_options(const ShootingRobotOptions& o) {
  NewtonLoopOptions l;
  l.tolerance = o.tolerance;
  l.max_iterations = o.max_iterations;
  l.min_step = 1e-3;
  l.max_step = o.max_step;
  // Warm-started solves: chord steps with the previous solve's Jacobian (state-only integrations,
  // ~5x cheaper) while each halves the residual; Newton with a fresh Jacobian from the first that does
  // not. The Jacobian rides along with every trial integration of Newton and Levenberg-Marquardt.
  l.quasi_newton = QuasiNewtonKind::Chord;
  l.chord_decrease = 0.5;
  l.jacobian_with_trials = true;
  l.levenberg_marquardt = o.levenberg_marquardt;
  l.lm_initial_damping = 1e-4;
  l.lm_damping_increase = 10.0;
  l.lm_max_tries = 12;
  l.lm_cap_by_damping = false;
  l.lm_keep_damping = false;
  // Stalled (e.g. on the way to another equilibrium branch): less than 10 % progress over the window;
  // the caller then falls back to continuation.
  l.stall_window = o.stall_window;
  l.stall_ratio = 0.9;
  return l;
}

// Axial stretch v3 = d3 . p' at a state of the rod.
double axial_stretch(const RodOde& ode, double s, const RodStateVector& y) {
  RodStateVector dyds;
  ode.derivative(s, y, dyds);
  return rotation_matrix(y.segment<4>(RodStateIndex::q)).col(2).dot(dyds.segment<3>(RodStateIndex::p));
}

}  // namespace

struct ShootingRobotSolver::Impl {
  shooting_robot::RobotShootingModel shooting;
  ShootingRobotOptions options;
  shooting_robot::RobotShootingSystem system;
  NewtonLoop loop;
  bool has_warm = false;
  State warm;

  Impl(std::shared_ptr<const RobotModel> model, const ShootingRobotOptions& o)
      : shooting(std::move(model)), options(o), system(shooting, options), loop(loop_options(o)) {}

  /// Newton from s; warm_start allows chord steps with the last factorised Jacobian.
  RobotSolution solve(const State& s, bool warm_start = false);
  /// Solves at move(start, t) for t = 1/n, 2/n, ..., 1, each from the previous solution, with n = 4,
  /// 8, ..., 64 until every step converges; iterations and time of all attempts are summed.
  RobotSolution continuation(const State& start, const std::function<void(State&, double)>& move,
                             RobotSolution failed);
  RobotSolution result(const State& s) const;
};

RobotSolution ShootingRobotSolver::Impl::solve(const State& s, bool warm_start) {
  const auto t0 = std::chrono::steady_clock::now();
  system.start(s);
  const NewtonLoopResult run =
      loop.run(system, {options.max_iterations}, warm_start && options.reuse_jacobian);
  const bool evaluated = system.integrate_current();  // the rods' buffers after a rejected trial
  SolveSummary summary;
  summary.solver = std::string("shooting (") + to_string(options.integrator) + ")";
  summary.status = run.status;
  summary.message = run.message;
  summary.iterations = run.iterations;
  summary.jacobian_evaluations = run.jacobian_evaluations;
  const VecX& r = loop.residual();
  if (evaluated && std::isfinite(run.residual_max_abs) && r.allFinite()) {
    summary.residual_scaled_max_abs = r.lpNorm<Eigen::Infinity>();
    summary.residual_max_abs = r.cwiseProduct(system.row_scale()).lpNorm<Eigen::Infinity>();
  } else {  // never NaN: the largest finite value, and not converged
    summary.residual_scaled_max_abs = summary.residual_max_abs = std::numeric_limits<double>::max();
    summary.status = summary.converged() ? SolveStatus::Failed : summary.status;
  }
  summary.integration_steps = system.integration_steps();
  RobotSolution out = result(system.state());
  summary.wall_time_seconds = seconds_since(t0);
  out.summary = summary;
  if (summary.converged()) {
    warm = system.state();
    has_warm = true;
  }
  return out;
}

RobotSolution ShootingRobotSolver::Impl::continuation(const State& start,
                                                      const std::function<void(State&, double)>& move,
                                                      RobotSolution failed) {
  SolveSummary total = failed.summary;
  for (int n = 4; n <= 64; n *= 2) {
    State s = start;
    RobotSolution out;
    bool ok = true;
    for (int j = 1; j <= n && ok; ++j) {
      move(s, static_cast<double>(j) / n);
      out = solve(s, true);
      add_attempt(total, out.summary);
      ok = out.summary.converged();
      if (ok) s = warm;
    }
    if (ok) {
      out.summary.iterations = total.iterations;
      out.summary.jacobian_evaluations = total.jacobian_evaluations;
      out.summary.wall_time_seconds = total.wall_time_seconds;
      out.summary.load_steps = n;
      out.summary.message = "continuation in " + std::to_string(n) + " steps";
      return out;
    }
  }
  failed.summary.iterations = total.iterations;
  failed.summary.jacobian_evaluations = total.jacobian_evaluations;
  failed.summary.wall_time_seconds = total.wall_time_seconds;
  failed.summary.message += "; continuation failed";
  return failed;
}

// The solution read from the unknowns and the rods' last integration (of s).
RobotSolution ShootingRobotSolver::Impl::result(const State& s) const {
  RobotSolution out;
  out.inputs = s.inputs;
  out.platforms = s.poses;
  out.passive_joints = s.passive;
  for (int i = 0; i < shooting.num_rods(); ++i) {
    const RodSetup& r = shooting.rods[i];
    const RodStateVector tip = r.Y.col(0);
    const RodStateVector& base = r.y0;  // of the same integration
    RodResult rr;
    rr.name = shooting.model->rods()[r.rod].name;
    rr.length = r.model.length;
    rr.base_force = base.segment<3>(RodStateIndex::n);
    rr.base_moment = base.segment<3>(RodStateIndex::m);
    rr.tip_force = tip.segment<3>(RodStateIndex::n);
    rr.tip_moment = tip.segment<3>(RodStateIndex::m);
    rr.axial_force = rr.base_force.dot(rotation_matrix(Quat(base.segment<4>(RodStateIndex::q))).col(2));
    rr.centerline.reserve(r.trajectory.y.size() + 2);
    if (r.trajectory.y.empty()) rr.centerline.push_back(base.segment<3>(RodStateIndex::p));
    for (const RodStateVector& y : r.trajectory.y) rr.centerline.push_back(y.segment<3>(RodStateIndex::p));
    if (r.trajectory.y.empty()) rr.centerline.push_back(tip.segment<3>(RodStateIndex::p));
    // At the two ends (an ODE evaluation per point: the steps' points would cost a share of the solve).
    rr.min_axial_stretch =
        std::min(axial_stretch(*r.ode, 0.0, base), axial_stretch(*r.ode, r.model.length, tip));
    out.rods.push_back(std::move(rr));
  }
  return out;
}

ShootingRobotSolver::ShootingRobotSolver(std::shared_ptr<const RobotModel> model,
                                         const ShootingRobotOptions& options) {
  require(options.rk4_steps > 0, "ShootingRobotOptions.rk4_steps = ", options.rk4_steps, " must be > 0");
  require(options.integration_relative_tolerance > 0 && options.integration_absolute_tolerance > 0,
          "ShootingRobotOptions: integration_relative_tolerance = ", options.integration_relative_tolerance,
          ", integration_absolute_tolerance = ", options.integration_absolute_tolerance, " must be > 0");
  require(options.tolerance > 0, "ShootingRobotOptions.tolerance = ", options.tolerance, " must be > 0");
  require(options.max_iterations >= 0, "ShootingRobotOptions.max_iterations = ", options.max_iterations,
          " must be >= 0");
  require(options.max_step > 0, "ShootingRobotOptions.max_step = ", options.max_step, " must be > 0");
  require(options.stall_window >= 0, "ShootingRobotOptions.stall_window = ", options.stall_window,
          " must be >= 0");
  impl_ = std::make_unique<Impl>(std::move(model), options);
}

ShootingRobotSolver::~ShootingRobotSolver() = default;
ShootingRobotSolver::ShootingRobotSolver(ShootingRobotSolver&&) noexcept = default;
ShootingRobotSolver& ShootingRobotSolver::operator=(ShootingRobotSolver&&) noexcept = default;

const RobotModel& ShootingRobotSolver::model() const {
  return *impl_->shooting.model;
}
const ShootingRobotOptions& ShootingRobotSolver::options() const {
  return impl_->options;
}
void ShootingRobotSolver::reset() {
  impl_->has_warm = false;
}

RobotSolution ShootingRobotSolver::fk(const VecX& inputs) {
  const RobotModel& m = *impl_->shooting.model;
  require(inputs.size() == static_cast<int>(m.inputs().size()), "ShootingRobotSolver::fk: ", inputs.size(),
          " inputs given, the model has ", m.inputs().size());
  for (int j = 0; j < inputs.size(); ++j)
    require(std::isfinite(inputs[j]) && inputs[j] >= m.inputs()[j].lower && inputs[j] <= m.inputs()[j].upper,
            "ShootingRobotSolver::fk: input '", m.inputs()[j].name, "' = ", inputs[j], " outside [",
            m.inputs()[j].lower, ", ", m.inputs()[j].upper, "]");
  impl_->system.set_mode(false);
  SolveSummary first;  // a cold start goes through the default inputs (the URDF's initial pose fits them)
  const VecX u0 = m.default_input_values();
  if (!impl_->has_warm && inputs != u0) {
    first = impl_->solve(impl_->shooting.cold_state(u0, m.initial_platform_poses())).summary;
    if (!first.converged()) {
      RobotSolution failed = impl_->solve(impl_->shooting.cold_state(inputs, m.initial_platform_poses()));
      add_attempt(failed.summary, first);
      return failed;
    }
  }
  State s = impl_->has_warm ? impl_->warm : impl_->shooting.cold_state(inputs, m.initial_platform_poses());
  s.inputs = inputs;
  RobotSolution out = impl_->solve(s, impl_->has_warm);
  add_attempt(out.summary, first);
  if (out.summary.converged()) return out;
  // Continuation in the inputs from the last solution (or from a cold solve at the default inputs).
  if (!impl_->has_warm) {
    const RobotSolution at_default = impl_->solve(impl_->shooting.cold_state(u0, m.initial_platform_poses()));
    add_attempt(out.summary, at_default.summary);
    if (!at_default.summary.converged()) return out;
  }
  const State start = impl_->warm;
  return impl_->continuation(
      start, [&](State& st, double t) { st.inputs = start.inputs + t * (inputs - start.inputs); }, out);
}

RobotSolution ShootingRobotSolver::ik(const std::vector<Pose>& targets) {
  const RobotModel& m = *impl_->shooting.model;
  require(static_cast<int>(targets.size()) == impl_->shooting.num_platforms(),
          "ShootingRobotSolver::ik: ", targets.size(), " targets given, the model has ",
          impl_->shooting.num_platforms(), " platforms");
  require(m.inputs().size() == 6 * targets.size(), "ShootingRobotSolver::ik: model '", m.name(), "' has ",
          m.inputs().size(), " inputs; the shooting IK needs 6 per platform (a square system)");
  std::vector<Pose> poses = targets;
  for (Pose& p : poses) {
    require(p.position.allFinite() && p.orientation.allFinite() && p.orientation.norm() > 0,
            "ShootingRobotSolver::ik: target pose is not finite or has a zero quaternion");
    p.orientation.normalize();
  }
  impl_->system.set_mode(true);
  State s = impl_->has_warm ? impl_->warm : impl_->shooting.cold_state(m.default_input_values(), poses);
  s.poses = poses;
  RobotSolution out = impl_->solve(s, impl_->has_warm);
  if (!out.summary.converged()) {
    // Continuation in the targets from the last solution's poses (or the FK solution at the default
    // inputs): positions linear, rotations along the geodesic R(t) = exp(t log(R_1 R_0^T)) R_0.
    bool have_start = impl_->has_warm;
    if (!have_start) {
      const RobotSolution at_default = fk(m.default_input_values());
      add_attempt(out.summary, at_default.summary);
      have_start = at_default.summary.converged();
      impl_->system.set_mode(true);
    }
    if (have_start) {
      const State start = impl_->warm;
      out = impl_->continuation(
          start,
          [&](State& st, double t) {
            for (size_t k = 0; k < poses.size(); ++k) {
              const Pose& a = start.poses[k];
              st.poses[k].position = a.position + t * (poses[k].position - a.position);
              const Vec3 w = so3_log(poses[k].rotation() * a.rotation().transpose());
              st.poses[k].orientation =
                  quat_multiply(quat_from_rotation_vector(t * w), a.orientation).normalized();
            }
          },
          out);
    }
  }
  if (out.summary.converged())
    for (int j = 0; j < out.inputs.size(); ++j)
      if (out.inputs[j] < m.inputs()[j].lower || out.inputs[j] > m.inputs()[j].upper)
        out.summary.message +=
            "input '" + m.inputs()[j].name + "' = " + std::to_string(out.inputs[j]) + " outside its bounds; ";
  return out;
}

}  // namespace pcr
