// Defaults of NonlinearSystem and the dense-Jacobian system (see dense_system.hpp).
#include "pcr/solve/dense_system.hpp"

#include <cstdio>

namespace pcr {

SystemStatus NonlinearSystem::newton_direction(const VecX& r, VecX& dx) {
  solve(r, dx);
  dx = -dx;
  if (!dx.allFinite()) return SystemStatus::failed(SolveStatus::Singular, "non-finite Newton step");
  return SystemStatus::success();
}

double NonlinearSystem::step_size(const VecX& dx) const {
  return dx.lpNorm<Eigen::Infinity>();
}

template <int N>
bool DenseNonlinearSystem<N>::evaluate_start(bool with_jacobian, VecX& r) {
  jacobian_current_ = false;
  if (!evaluate_at(nullptr, r, with_jacobian ? &jacobian_ : nullptr)) return false;
  jacobian_current_ = with_jacobian;
  return true;
}

template <int N>
bool DenseNonlinearSystem<N>::evaluate_trial(const VecX& dx, bool with_jacobian, VecX& r) {
  trial_has_jacobian_ = false;
  if (!evaluate_at(&dx, r, with_jacobian ? &trial_jacobian_ : nullptr)) return false;
  trial_has_jacobian_ = with_jacobian;
  return true;
}

template <int N>
void DenseNonlinearSystem<N>::accept_trial() {
  accept();
  jacobian_current_ = trial_has_jacobian_;
  if (trial_has_jacobian_) jacobian_.swap(trial_jacobian_);
  trial_has_jacobian_ = false;
}

template <int N>
bool DenseNonlinearSystem<N>::reevaluate_current(VecX& r) {
  if (evaluate_at(nullptr, r, jacobian_current_ ? &jacobian_ : nullptr)) return true;
  jacobian_current_ = false;
  return false;
}

template <int N>
SystemStatus DenseNonlinearSystem<N>::factorize(VecX& r) {
  if (!jacobian_current_) {
    if (!evaluate_at(nullptr, r, &jacobian_))
      return SystemStatus::failed(SolveStatus::Failed,
                                  "evaluation of the Jacobian failed: " + evaluation_failure());
    jacobian_current_ = true;
  }
  lu_.compute(jacobian_);
  factorized_ = true;
  if (min_rcond_ > 0.0) {
    const double rcond = lu_.rcond();
    if (!(rcond > min_rcond_)) {
      factorized_ = false;
      char buffer[96];
      std::snprintf(buffer, sizeof buffer, "Jacobian rcond = %.3g", rcond);
      return SystemStatus::failed(SolveStatus::Singular, buffer);
    }
  }
  return SystemStatus::success();
}

template <int N>
bool DenseNonlinearSystem<N>::dense_jacobian(MatX& J) const {
  J = jacobian_;
  return true;
}

template class DenseNonlinearSystem<Eigen::Dynamic>;
template class DenseNonlinearSystem<6>;

}  // namespace pcr
