#pragma once
// Broyden's "good" rank-one updates of the inverse of a factorised Jacobian J0 in Deuflhard's
// error-oriented form (QNERR; P. Deuflhard, Newton Methods for Nonlinear Problems, 2004, sec. 2.1.4),
// for the quasi-Newton steps of the Newton loop (newton_loop.hpp). With steps s_0 = -J0^-1 r(x_0) (or
// the last Newton step) and x_{k+1} = x_k + s_k:
//   w = -J0^-1 r(x_{k+1});  w += s_{j+1} (s_j . w) / |s_j|^2  for j = 0 .. k-1;
//   theta = |w| / |s_k|,  alpha = (s_k . w) / |s_k|^2,  s_{k+1} = w / (1 - alpha).
// A step is kept while theta <= the contraction bound (affine-invariant contraction; |alpha| <= theta
// keeps 1 - alpha >= 1/2). Convergence is superlinear, against linear for the plain chord step.
// Along a path the updates outlive a solve: a new sequence starts with s = -H r, H the inverse after all
// kept updates (Broyden's good update holds for any step s = -H r, and the recursion skips the pair
// that joins two sequences). The last kCarriedSteps steps (whole sequences) are kept.
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/solve/nonlinear_system.hpp"

namespace pcr {

class BroydenUpdates {
 public:
  static constexpr int kMaxSteps = 16;     ///< then a fresh Jacobian (bounds the update work and storage)
  static constexpr int kCarriedSteps = 6;  ///< steps of earlier sequences kept for a new one

  /// Storage for steps of n unknowns (allocates only when n changes); drops all steps.
  void resize(int n);
  void clear() { num_steps_ = 0; }
  int size() const { return num_steps_; }

  /// x = H b with the kept updates on J0 (system.solve).
  void solve(NonlinearSystem& system, const VecX& b, VecX& x) const;
  /// Starts a sequence with the quasi-Newton step s = -H r from the kept updates (after dropping all
  /// but the last sequences of at most kCarriedSteps steps); returns it.
  const VecX& start_sequence(NonlinearSystem& system, const VecX& r);
  /// Starts a sequence with an exact Newton step s (J0 s = -r), dropping every earlier step.
  void start_with_newton_step(const VecX& s);
  /// After the last step led to the residual r_new: appends the next step and returns true if the
  /// steps contract (theta <= contraction), false if a fresh Jacobian is needed. work: scratch of size n.
  bool next_step(NonlinearSystem& system, const VecX& r_new, double contraction, VecX& work);
  /// The last step (the one to take next).
  const VecX& last_step() const { return steps_[num_steps_ - 1]; }

 private:
  void drop_old_steps();

  std::vector<VecX> steps_;
  std::vector<double> step_norms2_;  // |steps_[j]|^2
  std::vector<char> starts_;         // steps_[j] starts a sequence
  int num_steps_ = 0;
};

}  // namespace pcr
