#pragma once
// Private to the rod shooting solver: one rod's shooting map z -> r(z) as a NonlinearSystem for the
// shared Newton loop (pcr/solve/newton_loop.hpp). Unknowns: the six base quantities of the base kind,
// moved by shooting::retract_base; residuals: the tip residuals divided by their scales (L, 1, F_c,
// M_c); Jacobian: the variational equations. With Dormand-Prince the integration mesh is frozen once
// the scaled residual is below freeze_mesh_below (a smooth map, so Newton reaches round-off).
#include <string>
#include <vector>

#include "pcr/rods/shooting/rod_shooting.hpp"
#include "pcr/solve/dense_system.hpp"
#include "shooting_ends.hpp"

namespace pcr {
namespace shooting {

/// Outcome of one Newton solve of the shooting map.
struct NewtonOutcome {
  SolveStatus status = SolveStatus::Failed;
  int iterations = 0;
  int jacobian_evaluations = 0;
  std::string message;
  std::vector<double> mesh;  ///< the frozen Dormand-Prince mesh (empty if none)
};

/// Newton (step cap, backtracking, Levenberg-Marquardt, stall test; ShootingOptions) on the shooting map
/// of `model` from the base state y0, which holds the last iterate afterwards.
NewtonOutcome solve_newton(const RodModel& model, const IntegratorOptions& integrator, RodStateVector& y0,
                           const ShootingOptions& options);

// One evaluation of the shooting map at a base state.
struct Evaluation {
  bool ok = false;
  std::string message;
  Vec6 residual = Vec6::Zero();  ///< scaled
  Mat6 jacobian = Mat6::Zero();  ///< scaled rows
  std::vector<double> mesh;      ///< accepted steps of an adaptive integration (empty otherwise)
  int steps = 0;
};

class RodShootingSystem : public DenseNonlinearSystem<6> {
 public:
  RodShootingSystem(const RodModel& model, const IntegratorOptions& integrator, const RodStateVector& y0,
                    double freeze_mesh_below);

  const RodStateVector& base_state() const { return y_; }
  /// The frozen mesh (empty while none).
  const std::vector<double>& frozen_mesh() const { return mesh_; }

  int size() const override { return 6; }
  double step_size(const VecX& dx) const override;
  PointUpdate on_new_point(double r_max, VecX& r) override;
  std::string evaluation_failure() const override { return failure_; }

 protected:
  bool evaluate_at(const VecX* dx, VecX& r, Mat6* J) override;
  void accept() override;

 private:
  /// The residual at a base state, and its Jacobian (variational equations, ~6x the cost) if asked.
  /// Dormand-Prince: on the frozen mesh if any (no error control), else adaptively, returning the
  /// accepted steps in e.mesh.
  void evaluate(const RodStateVector& y0, bool with_jacobian, Evaluation& e) const;

  const RodModel& model_;
  RodOde ode_;
  IntegratorOptions integrator_;
  Vec6 scale_, unknown_scale_;
  double freeze_mesh_below_;
  RodStateVector y_, trial_y_;  // base states of the current and trial points
  Evaluation current_, trial_;  // their evaluations
  std::vector<double> mesh_;    // frozen mesh
  bool frozen_ = false;
  std::string failure_;
};

}  // namespace shooting
}  // namespace pcr
