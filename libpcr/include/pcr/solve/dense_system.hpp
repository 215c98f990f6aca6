#pragma once
// A NonlinearSystem with a dense Jacobian and a partial-pivoting LU (the shooting solvers: a few
// unknowns per rod and platform). Derived classes evaluate the residual (and Jacobian) at the current
// or trial point and move the trial point to the current one; this class keeps J at the current point
// and at the trial point (when evaluated with it), and the factorisation J0, which outlives a solve
// (chord steps of the next warm-started solve). N: the number of unknowns when fixed at compile time
// (one rod: 6), else Eigen::Dynamic; instantiated for both (dense_system.cpp).
#include <Eigen/LU>

#include "pcr/solve/nonlinear_system.hpp"

namespace pcr {

template <int N>
class DenseNonlinearSystem : public NonlinearSystem {
 public:
  using Matrix = Eigen::Matrix<double, N, N>;

  /// min_rcond > 0: a J0 whose reciprocal condition estimate (1-norm) is at most this is reported
  /// Singular by factorize() (the loop then tries Levenberg-Marquardt, if enabled).
  explicit DenseNonlinearSystem(double min_rcond = 0.0) : min_rcond_(min_rcond) {}

  bool evaluate_start(bool with_jacobian, VecX& r) override;
  bool evaluate_trial(const VecX& dx, bool with_jacobian, VecX& r) override;
  void accept_trial() override;
  SystemStatus factorize(VecX& r) override;
  bool jacobian_refreshes_residual() const override { return true; }
  bool has_factorization() const override { return factorized_; }
  void solve(const VecX& b, VecX& y) override { y = lu_.solve(b); }
  bool dense_jacobian(MatX& J) const override;
  /// The next solve starts without J0 (e.g. the unknowns changed meaning).
  void forget_factorization() { factorized_ = false; }

 protected:
  /// r, and J if non-null, at the current point (dx == nullptr) or at the trial point x (+) *dx
  /// (remembered as the trial point). False when the evaluation failed.
  virtual bool evaluate_at(const VecX* dx, VecX& r, Matrix* J) = 0;
  /// The trial point of the last evaluate_at(dx) becomes the current point.
  virtual void accept() = 0;
  /// Re-evaluates r (and J, if there was one) at the current point, e.g. after a change of the
  /// discretisation. False when that failed.
  bool reevaluate_current(VecX& r);

 private:
  double min_rcond_ = 0.0;
  Matrix jacobian_, trial_jacobian_;  // at the current and the trial point
  bool jacobian_current_ = false, trial_has_jacobian_ = false;
  Eigen::PartialPivLU<Matrix> lu_;  // J0
  bool factorized_ = false;
};

}  // namespace pcr
