#pragma once
// One FK solve in progress and the budgets of its attempts (internal header of pcr::robots): shared by
// the strategies of fk_strategies.cpp (direct attempts and continuations in the inputs) and
// fk_last_resorts.cpp (waypoints, one input at a time, through folds, energy minimisation).
#include <optional>
#include <string>

#include "continuation_weights.hpp"
#include "fk_data.hpp"
#include "input_continuation.hpp"

namespace pcr::kinematics::strategies {

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
  bool tried_arclength = false;       // the fold-aware continuation from the default inputs was tried
  std::optional<Stability> verdict;   // of x, where the attempt that reached x computed it

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

/// Takes a continuation's result: on success its state and summary, else a note on where it stopped
/// (fk_strategies.cpp).
bool finish_continuation(FkAttempt& a, const ContinuationResult& r, const VecX& xr, const std::string& how);

// The last resorts (fk_last_resorts.cpp), strategies 6-9 of fk_strategies.cpp.
bool coarse_via_waypoints(FkAttempt& a, const char* how);
bool via_waypoints(FkAttempt& a, const char* how);
bool one_input_at_a_time(FkAttempt& a, const char* how);
bool arclength_from_default_inputs(FkAttempt& a, const char* how);
bool cold_arclength_from_default_inputs(FkAttempt& a, const char* how);
/// The fold-aware continuation from the last solution along the line to the inputs (coarse mesh first).
bool arclength_from_last_solution(FkAttempt& a, const char* how);
bool energy_minimisation(FkAttempt& a, const char* how);

}  // namespace pcr::kinematics::strategies
