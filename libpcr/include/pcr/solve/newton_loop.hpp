#pragma once
// The Newton loop shared by the collocation Newton solver (NewtonSolver, a sparse or bordered-block LU)
// and the shooting solvers (dense LU, Levenberg-Marquardt): a loop over named steps on a
// NonlinearSystem (nonlinear_system.hpp),
//   1. checks of the current point: finite residual, converged (max |r_i| <= tolerance), iterations,
//      stall (|r| fell by less than stall_ratio over stall_window iterations);
//   2. a quasi-Newton step on the last factorisation J0 when one is in use (Broyden's updates, or
//      plain chord steps), else or when it does not contract:
//   3. a Newton step: fresh Jacobian and factorisation, dx = -J^-1 r capped to max_step, and a
//      backtracking line search x (+) alpha dx, alpha = 1, backtrack, ... >= min_step, accepting
//        |r(x (+) alpha dx)|_2 <= (1 - armijo alpha) |r(x)|_2   (Armijo on |r|), or, with
//        natural_monotonicity, |J0^-1 r(x (+) alpha dx)|_2 <= (1 - alpha / 2) |dx|_2 (Deuflhard's natural
//        monotonicity test: affine invariant, not fooled by rows of very different scales);
//   4. when the Newton step fails (singular J, no decrease): a Levenberg-Marquardt step, if enabled,
//      (J^T J + mu D) dx = -J^T r with Marquardt's scaling D = diag(J^T J) (Nocedal & Wright,
//      Numerical Optimization, sec. 10.3), mu raised until |r| decreases;
//   5. when the loop stops short of the tolerance (iterations or Jacobians used up, stalled, no decrease)
//      at a point where every residual above the tolerance is within the round-off of its evaluation
//      (NonlinearSystem::within_round_off): converged all the same, with the bound reported - no point in
//      double precision need have a smaller residual.
// The loop owns its workspace (sized once per system size: no allocation per iteration) and the
// Broyden updates, which can carry over from one solve to the next along a path (continue_path).
#include <Eigen/Cholesky>
#include <limits>
#include <string>
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/solve/broyden_updates.hpp"
#include "pcr/solve/nonlinear_system.hpp"

namespace pcr {

enum class QuasiNewtonKind {
  None,     ///< a fresh Jacobian at every step
  Broyden,  ///< Broyden (QNERR) updates of J0 while the steps contract (broyden_updates.hpp)
  Chord,    ///< plain J0 while each step reduces |r| by chord_decrease; Newton for the rest of the solve
};

struct NewtonLoopOptions {
  double tolerance = 1e-10;           ///< converged when max_i |r_i| <= tolerance (r as the system scales it)
  int max_iterations = 50;            ///< steps of any kind
  double armijo = 1e-4;               ///< sufficient decrease factor of the line search
  double backtrack = 0.5;             ///< step reduction factor of the line search
  double min_step = 1e-8;             ///< smallest alpha the line search tries
  bool natural_monotonicity = false;  ///< also accept alpha by Deuflhard's test (see above)
  /// Cap on the size of Newton, chord and Levenberg-Marquardt steps (NonlinearSystem::step_size):
  /// keeps a step from jumping far when J is nearly singular. Broyden steps are not capped.
  double max_step = std::numeric_limits<double>::infinity();
  QuasiNewtonKind quasi_newton = QuasiNewtonKind::None;
  double broyden_contraction = 0.7;  ///< Broyden: keep updating while theta <= this
  double chord_decrease = 0.5;       ///< Chord: keep J0 while |r_new| < chord_decrease |r|
  /// The system evaluates its Jacobian together with each trial residual of the line search and of
  /// Levenberg-Marquardt (shooting robots: the variational equations ride along with the state, so an
  /// accepted trial needs no second integration), instead of at the next Newton step.
  bool jacobian_with_trials = false;
  bool levenberg_marquardt = false;  ///< needs NonlinearSystem::dense_jacobian
  double lm_initial_damping = 1e-3;  ///< mu of the first Levenberg-Marquardt step (relative to D)
  double lm_damping_increase = 4.0;  ///< mu factor after a rejected step (and to fit max_step)
  int lm_max_tries = 30;             ///< trial evaluations per Levenberg-Marquardt step
  /// A step longer than max_step: raise mu until it fits (true), or shorten it to max_step (false).
  bool lm_cap_by_damping = true;
  /// Keep mu from one Levenberg-Marquardt step to the next (divided by 3 after a success); otherwise each
  /// starts at lm_initial_damping.
  bool lm_keep_damping = true;
  int stall_window = 0;  ///< 0: no stall test
  double stall_ratio = 0.9;
};

/// Per-solve limits (the options' by default).
struct NewtonLoopLimits {
  int max_iterations = 0;
  int max_jacobian_evaluations = std::numeric_limits<int>::max();
};

struct NewtonLoopResult {
  SolveStatus status = SolveStatus::Failed;
  std::string message;
  int iterations = 0;
  int jacobian_evaluations = 0;
  double residual_max_abs = 0.0;  ///< max |r_i| at the returned (current) point
  /// Converged above the tolerance (round_off_bound > 0): the round-off bound every residual above the
  /// tolerance is within (NonlinearSystem::within_round_off); 0 otherwise.
  double round_off_bound = 0.0;
};

class NewtonLoop {
 public:
  explicit NewtonLoop(const NewtonLoopOptions& options = {});
  /// Throws InputError for unusable options (non-positive tolerance, factors outside (0, 1), ...).
  static void check(const NewtonLoopOptions& options);

  /// Solves from the system's current point; it holds the final iterate afterwards. quasi_start: the
  /// first step may be a quasi-Newton step on the J0 of an earlier solve (if the system has one).
  NewtonLoopResult run(NonlinearSystem& system, const NewtonLoopLimits& limits, bool quasi_start);
  /// The next run continues the path of the last ones: its first Broyden step uses the updates kept from
  /// them. Otherwise a run starts from the plain J0.
  void continue_path() { continue_path_ = true; }
  /// r at the current point after run().
  const VecX& residual() const { return r_; }
  const NewtonLoopOptions& options() const { return options_; }

 private:
  // After a step: the next iteration (from the new current point), a Newton step in this iteration (a
  // quasi-Newton step that did not contract), or the end of the run.
  enum class Step { Next, Newton, Done };
  enum class Phase { QuasiNewton, Newton };

  // The state of one run (the workspace is below).
  struct Run {
    NonlinearSystem* system = nullptr;
    NewtonLoopLimits limits;
    NewtonLoopResult result;
    Phase phase = Phase::Newton;
    bool broyden_step_ready = false;  // the last Broyden step is the next step from the current point
    bool r_finite = true;
    double r_norm = 0.0, r_max = 0.0;  // of r_
    double damping = 0.0;              // Levenberg-Marquardt mu
  };

  void resize(int n);
  Step check_point(Run& run);
  Step quasi_newton_step(Run& run);
  Step broyden_step(Run& run);
  Step chord_step(Run& run);
  Step newton_step(Run& run);
  /// Backtracking along dx_; true with the accepted trial in r_trial_ (not yet accepted), alpha in *alpha.
  bool line_search(Run& run, double* alpha);
  /// One Levenberg-Marquardt step from the current point; true when it was accepted.
  bool levenberg_marquardt_step(Run& run);
  /// Trial at x (+) step: r_trial_ and its norms; false when it failed or is not finite.
  bool try_point(Run& run, const VecX& step, bool with_jacobian, double* norm, double* max_abs);
  void accept(Run& run, double norm, double max_abs);
  void measure_residual(Run& run);
  void cap(const NonlinearSystem& system, VecX& dx) const;
  Step finish(Run& run, SolveStatus status, std::string message);
  /// Stopped short of the tolerance: Converged where the residual is at its round-off (step 5), else
  /// finish(status, message).
  Step stop_short(Run& run, SolveStatus status, std::string message);

  NewtonLoopOptions options_;
  BroydenUpdates broyden_;
  bool continue_path_ = false;
  // Workspace, sized once per system size.
  VecX r_, r_trial_, dx_, step_, work_;
  std::vector<double> stall_history_;  // |r| per iteration
  MatX jacobian_, normal_, damped_;    // J, J^T J and J^T J + mu D
  VecX gradient_, marquardt_;          // J^T r and D
  Eigen::LDLT<MatX> ldlt_;
};

}  // namespace pcr
