// The last resorts of ForwardKinematics::solve (fk_strategies.cpp kStrategies 6-9): continuations via
// waypoints and one input at a time, the fold-aware arclength continuation, the energy minimisation.
#include <string>
#include <vector>

#include "coarse_continuation.hpp"
#include "energy_fallback.hpp"
#include "fk_attempt.hpp"
#include "fold_continuation.hpp"
#include "pcr/robots/robot_stability.hpp"

namespace pcr::kinematics::strategies {

namespace {

/// Element k >= 1 of the van der Corput sequence in `base` (the radical inverse of k), in (0, 1).
double radical_inverse(int k, int base) {
  double value = 0.0, scale = 1.0 / base;
  for (; k > 0; k /= base, scale /= base) value += (k % base) * scale;
  return value;
}

/// Waypoint k of strategy 6: point k + 1 of the Halton sequence (bases 2, 3, 5, ...: spread over the box
/// with no random generator, the same for every solve) scaled to the input bounds.
VecX waypoint(const RobotModel& model, int k) {
  static constexpr int kPrimes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37};
  constexpr int kCount = sizeof kPrimes / sizeof kPrimes[0];
  const std::vector<ActuationInput>& inputs = model.inputs();
  VecX w(static_cast<int>(inputs.size()));
  for (int i = 0; i < w.size(); ++i) {
    const double h = radical_inverse(k + 1 + i / kCount, kPrimes[i % kCount]);
    w[i] = inputs[i].lower + h * (inputs[i].upper - inputs[i].lower);
  }
  return w;
}

}  // namespace

bool via_waypoints(FkAttempt& a, const char* how) {
  if (!a.x_default) return false;
  const RobotModel& model = a.data.model->assembly->model();
  std::string stopped;
  for (int k = 0; k < kWaypoints; ++k) {
    const VecX w = waypoint(model, k);
    VecX xw = *a.x_default;
    const ContinuationResult to_w = continue_along_line(a.solve_at(true), a.default_inputs(), w,
                                                        kFast.step_jacobians, xw, kFast.steps, a.weights());
    a.count(to_w.iterations, to_w.jacobian_evaluations);
    if (!to_w.converged) continue;
    VecX xs = xw;
    const ContinuationResult r = continue_along_line(a.solve_at(true), w, a.inputs, kFast.step_jacobians, xs,
                                                     kFast.steps, a.weights());
    a.count(r.iterations, r.jacobian_evaluations);
    if (!r.converged) continue;
    a.x = xs;
    a.summary = r.last;
    a.summary.message = "converged by " + std::string(how) + " (waypoint " + std::to_string(k + 1) + ", " +
                        std::to_string(to_w.steps + r.steps) + " steps)";
    return true;
  }
  a.summary.message +=
      "; " + std::string(how) + ": none of " + std::to_string(kWaypoints) + " waypoints led there";
  return false;
}

/// Strategy 6 on the coarse mesh: both legs there, then Newton on the requested mesh (the fine waypoints
/// follow where no waypoint leads there this way).
bool coarse_via_waypoints(FkAttempt& a, const char* how) {
  if (!a.x_default || !has_coarse_mesh(a.data)) return false;
  const RobotModel& model = a.data.model->assembly->model();
  const VecX& u1 = a.inputs;
  for (int k = 0; k < kWaypoints; ++k) {
    const VecX w = waypoint(model, k);
    const CoarseContinuation legs = [&w, &u1](FkData& coarse, const ContinuationWeights& weights,
                                              const VecX& from, VecX& xc) {
      const SolveAtInputs loose = [&coarse](const VecX& u, VecX& xs, int max_jacobians, bool) {
        return coarse.solve_at(u, xs, max_jacobians, true);
      };
      const ContinuationResult to_w =
          continue_along_line(loose, from, w, kFast.step_jacobians, xc, kFast.steps, weights);
      if (!to_w.converged) return to_w;
      ContinuationResult r =
          continue_along_line(loose, w, u1, kFast.step_jacobians, xc, kFast.steps, weights);
      r.steps += to_w.steps;
      r.iterations += to_w.iterations;
      r.jacobian_evaluations += to_w.jacobian_evaluations;
      return r;
    };
    VecX xs;
    const CoarseOutcome r = coarse_then_fine(a.data, a.default_inputs(), nullptr, u1, xs, legs);
    a.count(r.iterations, r.jacobian_evaluations);
    if (!r.converged) continue;
    a.x = xs;
    a.summary = r.last;
    a.summary.message = "converged by " + std::string(how) + " (waypoint " + std::to_string(k + 1) + ", " +
                        std::to_string(r.steps) + " steps, " + std::to_string(r.fine_jacobians) +
                        " fresh Jacobians on the requested mesh)";
    return true;
  }
  a.summary.message +=
      "; " + std::string(how) + ": none of " + std::to_string(kWaypoints) + " waypoints led there";
  return false;
}

bool one_input_at_a_time(FkAttempt& a, const char* how) {
  if (!a.x_default) return false;
  VecX xs = *a.x_default;
  const ContinuationResult r = continue_one_input_at_a_time(
      a.solve_at(false), a.default_inputs(), a.inputs, kDirectJacobianEvaluations,
      kThoroughStepJacobianEvaluations, kOneInputOrders, xs, kThoroughSteps);
  return finish_continuation(a, r, xs, how);
}

namespace {

/// The fold-aware continuation's options in FK: snap at folds, unstable modes counted only at folds and
/// snap landings (a verdict costs about a cold solve).
PathThroughFoldsOptions arclength_options() {
  PathThroughFoldsOptions o;
  o.at_fold = FoldPolicy::Snap;
  o.count_unstable_modes = false;
  o.max_steps = kArclengthSteps;
  return o;
}

int snaps_of(const SegmentOutcome& seg) {
  int snaps = 0;
  for (const PathEvent& e : seg.events) snaps += e.kind == PathEventKind::Snap ? 1 : 0;
  return snaps;
}

/// The fold-aware continuation from (u0, x_from: an equilibrium of the requested mesh, or the default
/// equilibrium when nullptr) on the coarse mesh, then Newton on the requested mesh from the coarse
/// equilibrium (coarse_continuation.hpp): false where there is no coarse mesh or either stage fails (the
/// continuation on the requested mesh follows).
bool coarse_arclength(FkAttempt& a, const VecX& u0, const VecX* x_from, const char* how) {
  if (!has_coarse_mesh(a.data)) return false;
  int snaps = 0;
  const VecX& u1 = a.inputs;
  const CoarseContinuation along = [&u1, &snaps](FkData& coarse, const ContinuationWeights&, const VecX& u0,
                                                 VecX& xc) {
    const FkModel& m = *coarse.model;
    const SegmentOutcome seg =
        continue_segment(*m.assembly, xc, -1, u0, u1, 0, m.options.tolerance, arclength_options());
    ContinuationResult r;
    r.converged = seg.reached;
    r.steps = seg.steps;
    r.iterations = seg.iterations;
    r.jacobian_evaluations = seg.jacobian_evaluations;
    r.stopped_at = seg.stopped;
    if (seg.reached) xc = seg.x;
    snaps = snaps_of(seg);
    return r;
  };
  VecX xs;
  const CoarseOutcome r = coarse_then_fine(a.data, u0, x_from, a.inputs, xs, along);
  a.count(r.iterations, r.jacobian_evaluations);
  if (!r.converged) {
    if (!r.stopped.empty()) a.summary.message += "; coarse-mesh " + std::string(how) + ": " + r.stopped;
    return false;
  }
  // The coarse snap landing carried to the requested mesh can lie nearer one of its unstable equilibria
  // (1 of 300 random Stewart-Gough cold solves): the path on the requested mesh decides then. The verdict
  // is kept with the result (FK reports it instead of computing it again).
  const RobotAssembly& assembly = *a.data.model->assembly;
  const Stability verdict = robot_stability(assembly, xs.head(assembly.problem().num_variables()));
  if (unstable_mode_count(verdict) > 0) {
    a.summary.message += "; coarse-mesh " + std::string(how) + ": unstable on the requested mesh";
    return false;
  }
  a.x = xs;
  a.verdict = verdict;
  a.summary = r.last;
  a.summary.message = "converged by coarse-mesh " + std::string(how) + " (" + std::to_string(r.steps) +
                      " steps, " + std::to_string(snaps) + " snaps, " + std::to_string(r.fine_jacobians) +
                      " fresh Jacobians on the requested mesh)";
  return true;
}

/// The fold-aware continuation on the requested mesh from the equilibrium x0 at inputs u0.
bool fine_arclength(FkAttempt& a, const VecX& x0, const VecX& u0, const char* how) {
  const FkModel& m = *a.data.model;
  const SegmentOutcome seg =
      continue_segment(*m.assembly, x0, -1, u0, a.inputs, 0, m.options.tolerance, arclength_options());
  a.count(seg.iterations, seg.jacobian_evaluations);
  if (!seg.reached) {
    a.summary.message += "; " + std::string(how) + " stopped: " + seg.stopped;
    return false;
  }
  a.x = seg.x;
  VecX c;
  m.assembly->problem().evaluate_residuals(a.x, c);
  a.summary = SolveSummary{};
  a.summary.status = SolveStatus::Converged;
  a.summary.solver = "newton-arclength";
  a.summary.residual_max_abs = c.size() ? (c - m.assembly->problem().row_lower()).cwiseAbs().maxCoeff() : 0.0;
  a.summary.message = "converged by " + std::string(how) + " (" + std::to_string(seg.steps) + " steps, " +
                      std::to_string(snaps_of(seg)) + " snaps)";
  return true;
}

}  // namespace

/// Pseudo-arclength continuation from the default inputs along the straight line, through folds: at a
/// fold it follows the stable equilibrium the robot snaps to (fold_continuation.hpp). From a stable
/// default equilibrium on the coarse mesh first (as the cold solves' strategy 4 below); from an unstable
/// one on the requested mesh only (a coarse landing is accepted only without unstable modes).
bool arclength_from_default_inputs(FkAttempt& a, const char* how) {
  if (!a.x_default || a.tried_arclength) return false;
  a.tried_arclength = true;
  if (a.data.model->options.solver != SolverKind::Newton) return false;
  if (a.data.model->default_unstable_modes() == 0 && coarse_arclength(a, a.default_inputs(), nullptr, how))
    return true;
  return fine_arclength(a, *a.x_default, a.default_inputs(), how);
}

/// A cold solve (no solution yet) whose continuations in the inputs from the default inputs stopped follows
/// the same line through its folds next: the equilibrium the robot reaches from its default state. Only
/// from a stable default equilibrium: from an unstable one (the planar robots' out-of-plane mode) no such
/// path exists, and the later strategies reach an equilibrium at a tenth of the cost (random
/// planar_three_rod cold solves: 38 against 344 ms median, 6.0 against 7.5 % stable).
bool cold_arclength_from_default_inputs(FkAttempt& a, const char* how) {
  if (a.data.has_solution || !a.x_default || a.data.model->options.solver != SolverKind::Newton) return false;
  return a.data.model->default_unstable_modes() == 0 && arclength_from_default_inputs(a, how);
}

bool arclength_from_last_solution(FkAttempt& a, const char* how) {
  if (!a.data.has_solution || a.data.model->options.solver != SolverKind::Newton) return false;
  const VecX u0 = a.data.model->assembly->inputs(a.data.x);
  return coarse_arclength(a, u0, &a.data.x, how) || fine_arclength(a, a.data.x, u0, how);
}

/// The last resort (energy_fallback.hpp): minimise the total potential energy at the inputs, then Newton
/// from the minimiser; accepted only at a stable equilibrium.
bool energy_minimisation(FkAttempt& a, const char* how) {
  const std::vector<EnergyStart> starts{{&a.x, "the last failed attempt's state"},
                                        {a.x_default, "the default equilibrium"},
                                        {a.data.has_solution ? &a.data.x : nullptr, "the last solution"}};
  const EnergyFallback r = minimise_energy_then_newton(a.data, a.inputs, starts);
  a.count(r.iterations, r.jacobians);
  if (!r.converged) {
    a.summary.message += "; " + std::string(how) + ": " + r.message;
    return false;
  }
  a.x = r.x;
  a.verdict = r.verdict;
  a.summary = r.summary;
  a.summary.message = "converged by " + std::string(how) + " (" + r.message + ")";
  return true;
}

}  // namespace pcr::kinematics::strategies
