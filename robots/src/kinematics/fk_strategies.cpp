// ForwardKinematics::solve's attempts, tried in order until one converges (kStrategies):
//  1. Newton from the path predictor's start (the last solution when there is no path);
//  2. Newton from the last solution (when the extrapolated start failed);
//  3. continuation in the inputs from the last solution (input_continuation.hpp);
//  4. continuation from the model's default inputs, solved from the straight initial guess, along the line;
//  5. continuation from the default inputs one input at a time;
//  6. pseudo-arclength continuation from the default inputs along the line, through folds, following the
//     equilibrium the robot snaps to at a fold (fold_continuation.hpp). Last, so that it costs nothing
//     where an earlier strategy converges (where it fails it can take longer than all of them together).
// The warm path starts in a deformed state that may be far from the new inputs and fails more often than
// the cold one (random input sweeps), hence the attempts from the default inputs after it. The direct
// attempts, which have a continuation to fall back on, and each continuation step get a limited number
// of fresh Jacobians (random sweeps, docs/benchmarks.md "Random FK sweeps": limited fresh Jacobians per step
// took 5x less time per Stewart-Gough solve than full-budget steps, and more converged).
#include <string>

#include "fk_data.hpp"
#include "fold_continuation.hpp"
#include "input_continuation.hpp"

namespace pcr::kinematics {

namespace {

/// Fresh-Jacobian budgets of a direct attempt and of one continuation step.
constexpr int kDirectJacobianEvaluations = 10;
/// The budget of a direct attempt from a start off a path (a jump in the inputs; the default equilibrium
/// for a cold solve): Newton converges there in a few Jacobians or not at all.
constexpr int kJumpJacobianEvaluations = 4;
constexpr int kContinuationStepJacobianEvaluations = 3;
/// Steps along a line of inputs: a first step of 0.1 of the line, cut to 0.3 when it fails. Random
/// Stewart-Gough inputs: Newton converges from the default equilibrium only within about 0.02-0.05 m of
/// rod length (the residual after the tangent predictor grows like 2500 t^2 there: the stiff axial and
/// shear rows), while a random line is 0.3-0.6 m long; a first step of 0.5 halved on failure, with 8
/// fresh Jacobians per step, spent about 30 Jacobians on failed steps before the first converged one
/// (docs/benchmarks.md "Random FK sweeps").
constexpr LineSteps kLineSteps{0.1, 0.3};
/// Orders tried by the one-input-at-a-time continuation (the last fallback; bounds its cost on inputs
/// without a reachable equilibrium: at most this many orders of one leg per input).
constexpr int kOneInputOrders = 3;
/// Step budget of the fold-aware continuation from the default inputs (snaps included).
constexpr int kArclengthSteps = 200;

/// One FK solve in progress.
struct FkAttempt {
  FkAttempt(FkData& d, const VecX& u, VecX& x_out) : data(d), inputs(u), x(x_out) {}
  FkData& data;
  const VecX& inputs;
  VecX& x;               // the result (the last iterate of a failed attempt)
  SolveSummary summary;  // of the converged attempt, else of the last direct one with notes appended
  int iterations = 0, jacobians = 0;  // of all attempts
  enum class Default { NotTried, Converged, Failed } default_state = Default::NotTried;
  VecX x_default;  // the equilibrium at the default inputs (strategies 4 and 5)
  bool on_path = false;
  bool continued_from_last = false;  // the continuation from the last solution was tried  // the predicted
                                     // start was extrapolated along a path (not the last solution)

  void count(int more_iterations, int more_jacobians) {
    iterations += more_iterations;
    jacobians += more_jacobians;
  }
  SolveAtInputs solve_at() {
    return [this](const VecX& u, VecX& xs, int max_jacobians, bool intermediate) {
      return data.solve_at(u, xs, max_jacobians, intermediate);
    };
  }
};

/// A direct Newton attempt from `start` with at most `jacobians` fresh Jacobians.
bool direct_attempt(FkAttempt& a, const VecX& start, int jacobians) {
  a.x = start;
  a.summary = a.data.solve_at(a.inputs, a.x, jacobians);
  a.count(a.summary.iterations, a.summary.jacobian_evaluations);
  return a.summary.converged();
}

/// Newton from the path predictor's start (the last solution off a path), or from the default
/// equilibrium when there is no solution yet. A start off a path (a jump in the inputs) gets the short
/// budget: Newton converges there only from close by, and a continuation is cheaper than a long attempt.
bool from_prediction(FkAttempt& a, const char*) {
  if (!a.data.has_solution) {
    const VecX* x0 = a.data.model->default_equilibrium();
    return direct_attempt(a, x0 ? *x0 : a.data.x, kJumpJacobianEvaluations);
  }
  const VecX start = a.data.predictor.predict(a.data.x, a.inputs, &a.on_path);
  if (a.on_path && a.data.newton) a.data.newton->continue_path();
  return direct_attempt(a, start, a.on_path ? kDirectJacobianEvaluations : kJumpJacobianEvaluations);
}

/// Newton from the last solution when the predicted start was another point (extrapolated along a path).
bool from_last_solution(FkAttempt& a, const char*) {
  return a.data.has_solution && a.on_path && direct_attempt(a, a.data.x, kDirectJacobianEvaluations);
}

/// Takes a continuation's result: on success its state and summary, else a note on where it stopped.
bool finish_continuation(FkAttempt& a, const ContinuationResult& r, const VecX& xr, const std::string& how) {
  a.count(r.iterations, r.jacobian_evaluations);
  if (!r.converged) {
    a.summary.message += "; " + how + " stopped at " + r.stopped_at;
    return false;
  }
  a.x = xr;
  a.summary = r.last;
  a.summary.message = "converged by " + how + " (" + std::to_string(r.steps) + " steps)";
  return true;
}

bool continuation_from_last_solution(FkAttempt& a, const char* how) {
  if (!a.data.has_solution || a.continued_from_last) return false;
  a.continued_from_last = true;
  VecX xs = a.data.x;
  const VecX u_last = a.data.model->assembly->inputs(a.data.x);
  return finish_continuation(a,
                             continue_along_line(a.solve_at(), u_last, a.inputs,
                                                 kContinuationStepJacobianEvaluations, xs, kLineSteps),
                             xs, how);
}

/// The equilibrium at the default inputs from the straight initial guess, solved once per attempt.
bool solve_default_inputs(FkAttempt& a) {
  if (a.default_state == FkAttempt::Default::NotTried) {
    const VecX* x0 = a.data.model->default_equilibrium();
    if (x0) a.x_default = *x0;
    a.default_state = x0 ? FkAttempt::Default::Converged : FkAttempt::Default::Failed;
    if (!x0) a.summary.message += "; the default inputs did not converge from the straight initial guess";
  }
  return a.default_state == FkAttempt::Default::Converged;
}

bool continuation_from_default_inputs(FkAttempt& a, const char* how) {
  if (!solve_default_inputs(a)) return false;
  VecX xs = a.x_default;
  const VecX u_default = a.data.model->assembly->model().default_input_values();
  return finish_continuation(a,
                             continue_along_line(a.solve_at(), u_default, a.inputs,
                                                 kContinuationStepJacobianEvaluations, xs, kLineSteps),
                             xs, how);
}

/// Whether the inputs are nearer (Euclidean distance in input space) to the default inputs than to the
/// last solution's: then the continuation from the default equilibrium goes first (a shorter path from a
/// state without bent rods; random sweeps, docs/benchmarks.md "Random FK sweeps").
bool default_inputs_nearer(FkAttempt& a) {
  if (!a.data.has_solution || !solve_default_inputs(a)) return false;
  const RobotAssembly& assembly = *a.data.model->assembly;
  return (a.inputs - assembly.model().default_input_values()).norm() <
         (a.inputs - assembly.inputs(a.data.x)).norm();
}

bool continuation_from_last_solution_if_nearer(FkAttempt& a, const char* how) {
  return !default_inputs_nearer(a) && continuation_from_last_solution(a, how);
}

/// Pseudo-arclength continuation from the default inputs along the straight line, through folds: at a
/// fold it follows the stable equilibrium the robot snaps to (fold_continuation.hpp). Unstable modes are
/// counted only at folds and snap landings (a verdict costs about a cold solve).
bool arclength_from_default_inputs(FkAttempt& a, const char* how) {
  if (!solve_default_inputs(a)) return false;
  const FkModel& m = *a.data.model;
  if (m.options.solver != SolverKind::Newton) return false;
  PathThroughFoldsOptions o;
  o.at_fold = FoldPolicy::Snap;
  o.count_unstable_modes = false;
  o.max_steps = kArclengthSteps;
  const SegmentOutcome seg =
      continue_segment(*m.assembly, a.x_default, -1, m.assembly->model().default_input_values(), a.inputs, 0,
                       m.options.tolerance, o);
  a.count(seg.iterations, seg.jacobian_evaluations);
  if (!seg.reached) {
    a.summary.message += "; " + std::string(how) + " stopped: " + seg.stopped;
    return false;
  }
  int snaps = 0;
  for (const PathEvent& e : seg.events) snaps += e.kind == PathEventKind::Snap ? 1 : 0;
  a.x = seg.x;
  VecX c;
  m.assembly->problem().evaluate_residuals(a.x, c);
  a.summary = SolveSummary{};
  a.summary.status = SolveStatus::Converged;
  a.summary.solver = "newton-arclength";
  a.summary.residual_max_abs = c.size() ? (c - m.assembly->problem().row_lower()).cwiseAbs().maxCoeff() : 0.0;
  a.summary.message = "converged by " + std::string(how) + " (" + std::to_string(seg.steps) + " steps, " +
                      std::to_string(snaps) + " snaps)";
  return true;
}

bool one_input_at_a_time(FkAttempt& a, const char* how) {
  if (!solve_default_inputs(a)) return false;
  VecX xs = a.x_default;
  const VecX u_default = a.data.model->assembly->model().default_input_values();
  const ContinuationResult r =
      continue_one_input_at_a_time(a.solve_at(), u_default, a.inputs, kDirectJacobianEvaluations,
                                   kContinuationStepJacobianEvaluations, kOneInputOrders, xs, kLineSteps);
  return finish_continuation(a, r, xs, how);
}

/// A strategy returns whether it converged; the name is what the summary's message calls it.
struct FkStrategy {
  const char* name;
  bool (*attempt)(FkAttempt& a, const char* name);
};

constexpr FkStrategy kStrategies[] = {
    {"the predicted start", from_prediction},
    {"the last solution", from_last_solution},
    {"continuation in the inputs from the last solution", continuation_from_last_solution_if_nearer},
    {"continuation in the inputs from the default inputs", continuation_from_default_inputs},
    {"continuation in the inputs from the last solution", continuation_from_last_solution},
    {"continuation from the default inputs one input at a time", one_input_at_a_time},
    {"fold-aware arclength continuation from the default inputs", arclength_from_default_inputs},
};

}  // namespace

SolveSummary solve_with_fallbacks(FkData& data, const VecX& inputs, VecX& x) {
  FkAttempt a(data, inputs, x);
  for (const FkStrategy& s : kStrategies)
    if (s.attempt(a, s.name)) break;
  a.summary.iterations = a.iterations;
  a.summary.jacobian_evaluations = a.jacobians;
  return a.summary;
}

}  // namespace pcr::kinematics
