#pragma once
// A square nonlinear system r(x) = 0 as the shared Newton loop (newton_loop.hpp) sees it. The system
// owns its unknowns x (a vector, rod base states, platform poses, ...) and moves them by a retraction
// x (+) dx, dx in R^n (e.g. a rotation vector for a rotation); the loop owns the residuals and steps.
// It keeps a current point and a trial point: evaluate_trial() evaluates x (+) dx, accept_trial()
// makes that the current point. J0 is the last factorised Jacobian (of the current point when
// factorize() was called, possibly older: quasi-Newton and chord steps reuse it).
#include <string>
#include <utility>

#include "pcr/core/types.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr {

/// Outcome of a step of the system that can fail: ok(), or the status and reason to report.
struct SystemStatus {
  SolveStatus failure = SolveStatus::Converged;  ///< Converged: no failure
  std::string message;

  bool ok() const { return failure == SolveStatus::Converged; }
  static SystemStatus success() { return {}; }
  static SystemStatus failed(SolveStatus status, std::string why) { return {status, std::move(why)}; }
};

class NonlinearSystem {
 public:
  virtual ~NonlinearSystem() = default;

  /// Number of unknowns (the length of dx) = number of residuals (the length of r).
  virtual int size() const = 0;
  /// r at the current point (the start of a solve). with_jacobian: also the Jacobian there, for systems
  /// that get it together with the residual (a hint). False when the evaluation failed (why:
  /// evaluation_failure()); a non-finite r is not a failure of the evaluation.
  virtual bool evaluate_start(bool with_jacobian, VecX& r) = 0;
  /// r at the trial point x (+) dx; otherwise as evaluate_start.
  virtual bool evaluate_trial(const VecX& dx, bool with_jacobian, VecX& r) = 0;
  /// The last trial point becomes the current point.
  virtual void accept_trial() = 0;
  /// J0 = J(x) at the current point (evaluated, or the one evaluated with the point), factorised. A
  /// system whose Jacobian evaluation recomputes the residual may refresh r. Fails as Singular when J0
  /// cannot be factorised (a dense J0 for Levenberg-Marquardt stays available then).
  virtual SystemStatus factorize(VecX& r) = 0;
  /// Whether factorize() may change r (then the loop measures it again).
  virtual bool jacobian_refreshes_residual() const { return false; }
  /// Whether J0 exists (from this solve or an earlier one: quasi-Newton starts need it).
  virtual bool has_factorization() const = 0;
  /// y = J0^-1 b.
  virtual void solve(const VecX& b, VecX& y) = 0;
  /// The Newton direction dx = -J0^-1 r with the system's own checks of the linear solve (default:
  /// dx finite, else Singular).
  virtual SystemStatus newton_direction(const VecX& r, VecX& dx);
  /// Size of a step for the step cap (NewtonLoopOptions::max_step); default max_i |dx_i|.
  virtual double step_size(const VecX& dx) const;
  /// J at the current point (that of the last factorize()) as a dense matrix, for Levenberg-Marquardt
  /// steps; false when the system has none.
  virtual bool dense_jacobian(MatX& /*J*/) const { return false; }
  /// Called with r of the current point before each convergence test, r_max = max |r_i|: e.g. shooting
  /// freezes its integration mesh there and re-evaluates r (then Changed).
  enum class PointUpdate { Unchanged, Changed, Failed };
  virtual PointUpdate on_new_point(double /*r_max*/, VecX& /*r*/) { return PointUpdate::Unchanged; }
  /// Whether every |r_i| above tolerance is within the round-off of evaluating r_i at the current point
  /// (no point in double precision need do better); bound: the largest such row's bound. Default: no
  /// estimate (false).
  virtual bool within_round_off(const VecX& /*r*/, double /*tolerance*/, double& /*bound*/) const {
    return false;
  }
  /// Why the last failed evaluation failed ("" if unknown).
  virtual std::string evaluation_failure() const { return {}; }
};

}  // namespace pcr
