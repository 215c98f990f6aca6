// ForwardKinematics::solve's attempts, tried in order until one converges (kStrategies; 6-9 in
// fk_last_resorts.cpp). Two tiers: fast attempts with short budgets that solve most random inputs, then
// the thorough ones that converge on more of the rest (random sweeps, docs/benchmarks.md "Random FK sweeps"):
//  1. Newton from the path predictor's start (the last solution off a path; a short budget after several
//     such attempts failed in a row), or from the default equilibrium (solved once per model,
//     fk_data.hpp) when there is no solution yet;
//  2. Newton from the last solution (when the start extrapolated along a path failed);
//  3. fast continuation in the inputs (input_continuation.hpp: short first step, the next ones from the
//     predictor's error, 4 fresh Jacobians per step, intermediate steps to a looser tolerance) from
//     whichever of the last solution and the default equilibrium has the nearer inputs, then from the
//     other; each first on a coarse mesh of the same rods, finished by Newton on the requested mesh
//     (coarse_continuation.hpp; a jump in 1 and 4 is probed there too), where that fails on the
//     requested mesh;
//  4. Newton from the straight initial guess (it reaches equilibria of the planar robots that the
//     continuations from the default equilibrium do not; cold solves from an unstable default
//     equilibrium try it before 3, with the short budget); a cold solve from a stable one whose
//     continuations from the default inputs stopped tries 8 next (on the coarse mesh first): the
//     equilibrium the robot reaches from its default state through the folds on that line;
//  5. thorough continuation (first step half the line, 8 fresh Jacobians per step, every step to the
//     full tolerance) from the last solution, then from the default inputs;
//  6. fast continuations from the default inputs via a waypoint, a few waypoints spread over the input
//     box (on the coarse mesh first, as in 3): where the line from the default inputs meets a fold with
//     no stable equilibrium to snap to, a bent path may pass around it;
//  7. continuation from the default inputs one input at a time;
//  8. pseudo-arclength continuation from the default inputs along the line, through folds, following the
//     equilibrium the robot snaps to at a fold (fold_continuation.hpp);
//  9. minimisation of the total potential energy at the inputs (Ipopt), then Newton from the minimiser,
//     accepted only at a stable equilibrium (energy_fallback.hpp).
// The later ones cost nothing where an earlier strategy converges (where they fail they take longer
// than all the others together).
#include <optional>
#include <string>
#include <utility>

#include "coarse_continuation.hpp"
#include "fk_attempt.hpp"
#include "pcr/robots/robot_stability.hpp"
#include "solve_support.hpp"

namespace pcr::kinematics {

namespace strategies {

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

namespace {

/// Continuation along the line from (u0, x0) to the inputs.
bool continuation(FkAttempt& a, const VecX& u0, const VecX& x0, const ContinuationKind& kind,
                  const char* how) {
  VecX xs = x0;
  const ContinuationResult r = continue_along_line(a.solve_at(kind.loose), u0, a.inputs, kind.step_jacobians,
                                                   xs, kind.steps, a.weights());
  return finish_continuation(a, r, xs, how);
}

/// A direct Newton attempt from `start` with at most `jacobians` fresh Jacobians. The summary of the
/// first one is the one reported if nothing converges (the later strategies append to its message).
bool direct_attempt(FkAttempt& a, const VecX& start, int jacobians, const char* how) {
  VecX xs = start;
  const SolveSummary s = a.data.solve_at(a.inputs, xs, jacobians);
  a.count(s.iterations, s.jacobian_evaluations);
  if (s.converged() || a.summary.message.empty()) {
    a.x = xs;
    a.summary = s;
  } else {
    a.summary.message += "; Newton from " + std::string(how) + ": " + s.message;
  }
  return s.converged();
}

/// A direct attempt probed on the coarse mesh (coarse_continuation.hpp coarse_direct): Newton there from
/// `start`'s image, then on the requested mesh. A jump in the inputs converges in a few Newton iterations
/// or not at all, on either mesh; the probe costs a fraction of an attempt on the requested mesh.
bool coarse_direct_attempt(FkAttempt& a, CoarseStart start, const VecX* x_from, int jacobians,
                           const char* how) {
  VecX xs;
  const CoarseOutcome r = coarse_direct(a.data, start, x_from, a.inputs, xs, jacobians);
  a.count(r.iterations, r.jacobian_evaluations);
  if (r.converged) {
    a.x = xs;
    a.summary = r.last;
    return true;
  }
  if (a.summary.message.empty()) {
    a.x = start == CoarseStart::FineState ? *x_from : a.data.x;
    a.summary = r.last;
    a.summary.message = "Newton from " + std::string(how) + ": " + r.stopped;
  } else {
    a.summary.message += "; Newton from " + std::string(how) + ": " + r.stopped;
  }
  return false;
}

/// Newton from the path predictor's start (the last solution off a path), or from the default
/// equilibrium when there is no solution yet. A start off a path (a jump in the inputs) gets the short
/// budget: Newton converges there only from close by, and a continuation is cheaper than a long attempt.
bool from_prediction(FkAttempt& a, const char* how) {
  if (!a.data.has_solution) {
    if (a.x_default && has_coarse_mesh(a.data))
      return coarse_direct_attempt(a, CoarseStart::DefaultEquilibrium, nullptr, kJumpJacobianEvaluations,
                                   how);
    return direct_attempt(a, a.x_default ? *a.x_default : a.data.x, kJumpJacobianEvaluations, how);
  }
  const VecX start = a.data.predictor.predict(a.data.x, a.inputs, &a.on_path);
  if (a.on_path && a.data.newton) a.data.newton->continue_path();
  if (a.on_path) return direct_attempt(a, start, kDirectJacobianEvaluations, how);
  const int budget =
      a.data.failed_jumps >= kFailedJumpsBeforeProbe ? kProbeJacobianEvaluations : kJumpJacobianEvaluations;
  // A jump probed on the coarse mesh; Newton from the last solution at its own inputs stays on the requested
  // mesh (nothing to do there when it is the solution).
  const bool jump = a.inputs != a.data.model->assembly->inputs(a.data.x);
  const bool converged = jump && has_coarse_mesh(a.data)
                             ? coarse_direct_attempt(a, CoarseStart::FineState, &start, budget, how)
                             : direct_attempt(a, start, budget, how);
  a.data.failed_jumps = converged ? 0 : a.data.failed_jumps + 1;
  return converged;
}

/// Newton from the last solution when the predicted start was another point (extrapolated along a path).
bool from_last_solution(FkAttempt& a, const char* how) {
  return a.data.has_solution && a.on_path && direct_attempt(a, a.data.x, kDirectJacobianEvaluations, how);
}

/// Newton from the straight initial guess (not the same start as strategy 1 when a default equilibrium
/// exists).
bool from_straight_guess(FkAttempt& a, const char* how, int jacobians) {
  if (!a.x_default || a.tried_straight) return false;
  a.tried_straight = true;
  if (!direct_attempt(a, a.data.model->assembly->initial_guess(), jacobians, how)) return false;
  a.summary.message = "converged by Newton from " + std::string(how);
  return true;
}
/// Cold solves (no solution yet) try it early, with the short budget, where the default equilibrium is not
/// stable: the planar robots' cold solves converge there more often than by the continuations from their
/// default equilibrium (random sweeps). From a stable default equilibrium the continuations come first
/// (the equilibrium the robot reaches from its default state; on random Stewart-Gough inputs Newton
/// converges from the straight guess on 0.06 % of cold solves, and the attempt cost 15-20 % of one).
bool cold_from_straight_guess(FkAttempt& a, const char* how) {
  if (a.data.has_solution || (a.x_default && a.data.model->default_unstable_modes() == 0)) return false;
  if (!a.x_default || a.tried_straight || !has_coarse_mesh(a.data))
    return from_straight_guess(a, how, kJumpJacobianEvaluations);
  a.tried_straight = true;
  if (!coarse_direct_attempt(a, CoarseStart::StraightGuess, nullptr, kJumpJacobianEvaluations, how))
    return false;
  a.summary.message = "converged by Newton from " + std::string(how);
  return true;
}
bool warm_from_straight_guess(FkAttempt& a, const char* how) {
  return from_straight_guess(a, how, kDirectJacobianEvaluations);
}

/// Whether the inputs are nearer (Euclidean distance in input space) to the default inputs than to the
/// last solution's: then the fast continuation from the default equilibrium goes first (a shorter path,
/// from a state without bent rods).
bool default_inputs_nearer(const FkAttempt& a) {
  return a.x_default && (a.inputs - a.default_inputs()).norm() <
                            (a.inputs - a.data.model->assembly->inputs(a.data.x)).norm();
}

bool fast_from_last_solution(FkAttempt& a, const char* how) {
  if (!a.data.has_solution || a.fast_from_last) return false;
  a.fast_from_last = true;
  return continuation(a, a.data.model->assembly->inputs(a.data.x), a.data.x, kFast, how);
}
bool fast_from_last_solution_if_nearer(FkAttempt& a, const char* how) {
  return !default_inputs_nearer(a) && fast_from_last_solution(a, how);
}
bool fast_from_default_inputs(FkAttempt& a, const char* how) {
  return a.x_default && continuation(a, a.default_inputs(), *a.x_default, kFast, how);
}
bool thorough_from_last_solution(FkAttempt& a, const char* how) {
  return a.data.has_solution &&
         continuation(a, a.data.model->assembly->inputs(a.data.x), a.data.x, kThorough, how);
}
bool thorough_from_default_inputs(FkAttempt& a, const char* how) {
  return a.x_default && continuation(a, a.default_inputs(), *a.x_default, kThorough, how);
}

/// The fast continuation on the coarse mesh from (u0, x_from: an equilibrium of the requested mesh, or
/// the default equilibrium when nullptr), then Newton on the requested mesh (coarse_continuation.hpp).
/// Where it fails the same continuation on the requested mesh follows in kStrategies.
bool coarse_continuation(FkAttempt& a, const VecX& u0, const VecX* x_from, const char* how) {
  const VecX& u1 = a.inputs;
  const CoarseContinuation steps = [&u1](FkData& coarse, const ContinuationWeights& w, const VecX& from,
                                         VecX& xc) {
    // Every coarse step to the intermediate tolerance: the coarse equilibrium is only a start.
    const SolveAtInputs loose = [&coarse](const VecX& u, VecX& xs, int max_jacobians, bool) {
      return coarse.solve_at(u, xs, max_jacobians, true);
    };
    return continue_along_line(loose, from, u1, kFast.step_jacobians, xc, kFast.steps, w);
  };
  VecX xs;
  const CoarseOutcome r = coarse_then_fine(a.data, u0, x_from, a.inputs, xs, steps);
  a.count(r.iterations, r.jacobian_evaluations);
  if (!r.converged) {
    if (!r.stopped.empty()) a.summary.message += "; " + std::string(how) + ": " + r.stopped;
    return false;
  }
  a.x = xs;
  a.summary = r.last;
  a.summary.message = "converged by " + std::string(how) + " (" + std::to_string(r.steps) + " steps, " +
                      std::to_string(r.fine_jacobians) + " fresh Jacobians on the requested mesh)";
  return true;
}
bool coarse_from_last_solution(FkAttempt& a, const char* how) {
  if (!a.data.has_solution || a.coarse_from_last) return false;
  a.coarse_from_last = true;
  return coarse_continuation(a, a.data.model->assembly->inputs(a.data.x), &a.data.x, how);
}
bool coarse_from_last_solution_if_nearer(FkAttempt& a, const char* how) {
  return !default_inputs_nearer(a) && coarse_from_last_solution(a, how);
}
bool coarse_from_default_inputs(FkAttempt& a, const char* how) {
  return a.x_default && coarse_continuation(a, a.default_inputs(), nullptr, how);
}

/// The name of the first rod of the equilibrium x with an axial stretch v3 <= 0 at a sample point (as
/// read_solution samples it; admissible_axial_stretch), or "" when all are admissible.
std::string inadmissible_rod(const FkModel& m, const VecX& x) {
  const RobotAssembly& a = *m.assembly;
  std::vector<Vec3> centerline;
  std::vector<double> stretches;
  for (int i = 0; i < a.num_rods(); ++i) {
    a.rod(i).sample_centerline(x, a.rod_variables(i), m.sample_bases[i], centerline, stretches);
    for (double v3 : stretches)
      if (!admissible_axial_stretch(v3)) return a.rod(i).model().name;
  }
  return "";
}

/// A strategy returns whether it converged; the name is what the summary's message calls it.
struct FkStrategy {
  const char* name;
  bool (*attempt)(FkAttempt& a, const char* name);
};

constexpr FkStrategy kStrategies[] = {
    {"the predicted start", from_prediction},
    {"the last solution", from_last_solution},
    {"the straight initial guess", cold_from_straight_guess},
    {"coarse-mesh continuation in the inputs from the last solution", coarse_from_last_solution_if_nearer},
    {"continuation in the inputs from the last solution", fast_from_last_solution_if_nearer},
    {"coarse-mesh continuation in the inputs from the default inputs", coarse_from_default_inputs},
    {"continuation in the inputs from the default inputs", fast_from_default_inputs},
    {"fold-aware arclength continuation from the default inputs", cold_arclength_from_default_inputs},
    {"coarse-mesh continuation in the inputs from the last solution", coarse_from_last_solution},
    {"continuation in the inputs from the last solution", fast_from_last_solution},
    {"the straight initial guess", warm_from_straight_guess},
    {"thorough continuation in the inputs from the last solution", thorough_from_last_solution},
    {"thorough continuation in the inputs from the default inputs", thorough_from_default_inputs},
    {"coarse-mesh continuation from the default inputs via a waypoint", coarse_via_waypoints},
    {"continuation from the default inputs via a waypoint", via_waypoints},
    {"continuation from the default inputs one input at a time", one_input_at_a_time},
    {"fold-aware arclength continuation from the default inputs", arclength_from_default_inputs},
    {"energy minimisation (Ipopt) then Newton", energy_minimisation},
};

/// A solve that starts from a stable equilibrium (cold: the default one; warm: the last solution) and
/// ends on an unstable one has left the stable path (a continuation passed a fold or a bifurcation
/// unseen, or a jump landed on another branch: random planar_pinned cold solves reached equilibria with
/// 300-700 unstable modes, their rods crushed). With the verdict asked for (it is computed anyway), the
/// fold-aware continuation along the line from that start is tried too where it was not yet, and the
/// result with fewer unstable modes is kept (the first on a tie).
void prefer_the_stable_path(FkAttempt& a) {
  const FkModel& m = *a.data.model;
  if (!m.options.stability_verdict || a.tried_arclength) return;
  const bool cold = !a.data.has_solution;
  if (cold ? !a.x_default || m.default_unstable_modes() != 0 : a.data.last_unstable_modes != 0) return;
  const int n = m.assembly->problem().num_variables();
  if (!a.verdict) a.verdict = robot_stability(*m.assembly, a.x.head(n));
  if (a.verdict->verdict != StabilityVerdict::Unstable) return;
  const VecX first_x = a.x;
  const SolveSummary first = a.summary;
  const Stability first_verdict = *a.verdict;
  const std::string how = std::string("fold-aware arclength continuation from the ") +
                          (cold ? "default inputs" : "last solution");
  a.verdict.reset();  // the attempt below sets it where it computes the verdict of its result
  const bool reached = cold ? cold_arclength_from_default_inputs(a, how.c_str())
                            : arclength_from_last_solution(a, how.c_str());
  if (reached && inadmissible_rod(m, a.x).empty()) {
    const Stability v = a.verdict ? *a.verdict : robot_stability(*m.assembly, a.x.head(n));
    const int modes = definite_unstable_modes(v);
    if (modes >= 0 && modes < first_verdict.unstable_modes) {
      a.verdict = v;
      a.summary.message += "; preferred to an equilibrium with " +
                           unstable_modes_text(first_verdict.unstable_modes) + " (" + first.message + ")";
      return;
    }
  }
  a.x = first_x;
  a.summary = first;
  a.summary.message +=
      "; " + unstable_modes_text(first_verdict.unstable_modes) + ": the " + how + " reached none with fewer";
  a.verdict = first_verdict;
}

}  // namespace

}  // namespace strategies

SolveSummary solve_with_fallbacks(FkData& data, const VecX& inputs, VecX& x,
                                  std::optional<Stability>* verdict) {
  using namespace strategies;
  FkAttempt a(data, inputs, x);
  bool solved_here = false;
  const DefaultEquilibrium& start = data.model->default_equilibrium(&solved_here);
  a.x_default = start.converged ? &start.x : nullptr;
  // An equilibrium with a rod compressed to a point or inverted (not admissible: finish_solution marks
  // it failed) does not end the chain: the later strategies may reach an admissible one. If none does,
  // the first inadmissible one is the result (and reported failed with its reason).
  std::optional<std::pair<VecX, SolveSummary>> inadmissible;
  bool converged = false;
  for (const FkStrategy& s : kStrategies) {
    if (!s.attempt(a, s.name)) continue;
    const std::string rod = inadmissible_rod(*data.model, a.x);
    if (rod.empty()) {
      converged = true;
      break;
    }
    if (!inadmissible) inadmissible.emplace(a.x, a.summary);
    a.verdict.reset();  // of the inadmissible state, not of what a later strategy reaches
    a.summary.status = SolveStatus::Failed;
    a.summary.message = inadmissible->second.message + "; rod '" + rod +
                        "' compressed to a point or inverted there: the later strategies tried";
  }
  if (converged) prefer_the_stable_path(a);
  if (verdict) *verdict = converged ? a.verdict : std::nullopt;
  if (!converged && inadmissible) {
    a.x = inadmissible->first;
    a.summary.status = inadmissible->second.status;
  }
  // A failed result is reported at the requested inputs, whatever start its state came from (a failed
  // coarse probe leaves the start of the attempt, at the inputs of the last or default solution).
  if (!converged) data.model->assembly->set_inputs(a.x, inputs);
  if (!a.x_default)
    a.summary.message += "; the default inputs did not converge from the straight initial guess";
  if (solved_here) {
    // This call solved the shared default equilibrium first: its work is part of this solve.
    a.iterations += start.summary.iterations;
    a.jacobians += start.summary.jacobian_evaluations;
    a.summary.message += "; the model's default equilibrium solved first (" +
                         std::to_string(start.summary.iterations) +
                         " iterations, counted here; later solves over the model share it)";
  }
  a.summary.iterations = a.iterations;
  a.summary.jacobian_evaluations = a.jacobians;
  return a.summary;
}

}  // namespace pcr::kinematics
