// ForwardKinematics::solve's attempts, tried in order until one converges (kStrategies). Two tiers: fast
// attempts with short budgets that solve most random inputs, then the thorough ones that converge on more
// of the rest (random sweeps, docs/benchmarks.md "Random FK sweeps"):
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
//     continuations from the default equilibrium do not; cold solves try it before 3, with the short
//     budget);
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
#include <vector>

#include "coarse_continuation.hpp"
#include "continuation_weights.hpp"
#include "energy_fallback.hpp"
#include "fk_data.hpp"
#include "fold_continuation.hpp"
#include "input_continuation.hpp"

namespace pcr::kinematics {

namespace {

/// Fresh-Jacobian budget of a direct attempt along a path and from the straight initial guess.
constexpr int kDirectJacobianEvaluations = 10;
/// The budget of a direct attempt from a start off a path (a jump in the inputs; the default equilibrium
/// for a cold solve): Newton converges there in a few Jacobians or not at all (random planar_three_rod
/// inputs: 3 gives other equilibria than 6 on 36 of 200 warm solves and twice the fresh Jacobians).
constexpr int kJumpJacobianEvaluations = 6;
/// After this many failed direct attempts from the last solution off a path in a row, such attempts get
/// kProbeJacobianEvaluations only, until one converges: on random Stewart-Gough inputs 196 of 200 fail
/// and each cost 6 fresh Jacobians, a third of a warm solve; the 4 that converge took 2, 3, 3 and 6 (the
/// last reaches the same equilibrium by the continuation); random planar_three_rod jumps converge about
/// every second time, which resets the count.
constexpr int kFailedJumpsBeforeProbe = 5;
constexpr int kProbeJacobianEvaluations = 2;
/// The fast continuation: 4 fresh Jacobians per step, a first step of 0.03 of the line, cut to 0.3 when it
/// fails, the next steps from the predictor's error (0.02: about 1 cm of platform or rod position on the
/// Stewart-Gough robot, rod rotations of 0.02 rad). Random Stewart-Gough inputs: Newton converges from the
/// default equilibrium only within about 0.02-0.05 m of rod length (the platform moves by up to 6 m per m
/// of input there: its legs start parallel, a singular pose of the rigid mechanism, and the solution path
/// bends where they tilt), while a random line is 0.3-0.6 m long; the predictor's error per step grows
/// like h^2 with a constant that falls by more than 10 along the line (docs/benchmarks.md "Random FK
/// sweeps": fewer fresh Jacobians than fixed growth factors, which the failed steps near the start cost).
constexpr int kFastStepJacobianEvaluations = 4;
constexpr LineSteps kFastSteps{0.03, 0.3, 0.02};
/// The thorough continuation: steps that may take 8 fresh Jacobians (a planar robot near a fold needs
/// them), from half the line, halved on failure.
constexpr int kThoroughStepJacobianEvaluations = 8;
constexpr LineSteps kThoroughSteps{0.5, 0.5};
/// Orders tried by the one-input-at-a-time continuation (the last fallback; bounds its cost on inputs
/// without a reachable equilibrium: at most this many orders of one leg per input).
constexpr int kOneInputOrders = 3;
/// Step budget of the fold-aware continuation from the default inputs (snaps included). A universal_passive
/// input of the random sweep (0.260 0.320 0.327 0.212 0.341 0.279) needs 442: two snaps, and 0.56 of the
/// line between them on a branch whose legs buckle one after the other (3-4 corrector iterations per
/// step of 0.003 in the inputs).
constexpr int kArclengthSteps = 600;
/// Waypoints tried by strategy 6. The 7 inputs of a 1,000-input Stewart-Gough sweep that every other
/// strategy failed on all converged through waypoint 1 or 2, to stable equilibria (docs/benchmarks.md
/// "Random FK sweeps").
constexpr int kWaypoints = 8;

/// A continuation's budget and step control; loose: its intermediate steps to kIntermediateTolerance.
struct ContinuationKind {
  int step_jacobians;
  LineSteps steps;
  bool loose;
};
constexpr ContinuationKind kFast{kFastStepJacobianEvaluations, kFastSteps, true};
constexpr ContinuationKind kThorough{kThoroughStepJacobianEvaluations, kThoroughSteps, false};

/// One FK solve in progress.
struct FkAttempt {
  FkAttempt(FkData& d, const VecX& u, VecX& x_out) : data(d), inputs(u), x(x_out) {}
  FkData& data;
  const VecX& inputs;
  VecX& x;               // the result (the last iterate of a failed attempt)
  SolveSummary summary;  // of the converged attempt, else of the first direct one with notes appended
  int iterations = 0, jacobians = 0;  // of all attempts
  const VecX* x_default = nullptr;    // the equilibrium at the default inputs (nullptr: did not converge)
  bool on_path = false;               // the predicted start was extrapolated along a path
  bool fast_from_last = false;        // the fast continuation from the last solution was tried
  bool coarse_from_last = false;      // the coarse-mesh continuation from the last solution was tried
  bool tried_straight = false;        // Newton from the straight initial guess was tried

  void count(int more_iterations, int more_jacobians) {
    iterations += more_iterations;
    jacobians += more_jacobians;
  }
  SolveAtInputs solve_at(bool loose) {
    return [this, loose](const VecX& u, VecX& xs, int max_jacobians, bool intermediate) {
      return data.solve_at(u, xs, max_jacobians, loose && intermediate);
    };
  }
  VecX default_inputs() const { return data.model->assembly->model().default_input_values(); }
  /// The continuation's predictor error weights (continuation_weights.hpp), made on first use.
  const ContinuationWeights& weights() {
    if (weights_.size() == 0) weights_ = continuation_weights(*data.model->assembly);
    return weights_;
  }

 private:
  ContinuationWeights weights_;
};

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
/// Cold solves (no solution yet) try it early, with the short budget: the planar robots' cold solves
/// converge there more often than by the continuations from their default equilibrium (random sweeps).
bool cold_from_straight_guess(FkAttempt& a, const char* how) {
  if (a.data.has_solution) return false;
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

/// Continuation along the line from (u0, x0) to the inputs.
bool continuation(FkAttempt& a, const VecX& u0, const VecX& x0, const ContinuationKind& kind,
                  const char* how) {
  VecX xs = x0;
  const ContinuationResult r = continue_along_line(a.solve_at(kind.loose), u0, a.inputs, kind.step_jacobians,
                                                   xs, kind.steps, a.weights());
  return finish_continuation(a, r, xs, how);
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

/// Pseudo-arclength continuation from the default inputs along the straight line, through folds: at a
/// fold it follows the stable equilibrium the robot snaps to (fold_continuation.hpp). Unstable modes are
/// counted only at folds and snap landings (a verdict costs about a cold solve).
bool arclength_from_default_inputs(FkAttempt& a, const char* how) {
  if (!a.x_default) return false;
  const FkModel& m = *a.data.model;
  if (m.options.solver != SolverKind::Newton) return false;
  PathThroughFoldsOptions o;
  o.at_fold = FoldPolicy::Snap;
  o.count_unstable_modes = false;
  o.max_steps = kArclengthSteps;
  const SegmentOutcome seg =
      continue_segment(*m.assembly, *a.x_default, -1, m.assembly->model().default_input_values(), a.inputs, 0,
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
  a.summary = r.summary;
  a.summary.message = "converged by " + std::string(how) + " (" + r.message + ")";
  return true;
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

}  // namespace

SolveSummary solve_with_fallbacks(FkData& data, const VecX& inputs, VecX& x) {
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
    a.summary.status = SolveStatus::Failed;
    a.summary.message = inadmissible->second.message + "; rod '" + rod +
                        "' compressed to a point or inverted there: the later strategies tried";
  }
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
