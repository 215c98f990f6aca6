#pragma once
// Shooting-method solution of one rod's boundary value problem (docs/design.md §6): the six unknown base
// quantities z are found by Newton (the shared loop pcr/solve/newton_loop.hpp; Jacobian from the
// variational equations, backtracking line search), with a Levenberg-Marquardt step when Newton stalls and
// load stepping (continuation in a load factor with warm starts) when the full load fails. Independent of the
// collocation code: it shares only pcr::RodModel and the math headers.
//
// Unknowns by base kind (the base state y(0) is updated by a retraction, never leaving its constraints):
//   clamped:   n(0), m(0)                                    (p, R given)
//   collar:    n(0), two moment components m(0) . R_bar e1, m(0) . R_bar e2, twist psi about d3
//              (R(0) = R_bar R_z(psi)), with m(0) . d3 = -moment . d3
//   spherical: n(0), rotation R(0) <- R(0) exp(hat(theta))   (p given, m(0) = -moment)
//   free:      p(0), rotation theta                          (n(0) = -force, m(0) = -moment)
//   universal: n(0), joint angles theta1, theta2, transmitted torsion mu  (R(0) = R_T R_a(theta1)
//   R_b(theta2),
//              m(0) = -moment - mu t, t = (R_T a) x (R(0) b); joint_ends.hpp)
//   revolute:  n(0), joint angle theta, transmitted moments mu1, mu2 normal to the pin
//              (R(0) = R_T R_a(theta), m(0) = -moment - R_T (mu1 c1 + mu2 c2))
// Residuals by tip kind (6), with the sign convention of RodEnd (n(L) = force, m(L) = moment):
//   clamped:   p(L) - p_bar, 2 vec(q_e), q_e = conj(q_bar) (x) q with w >= 0 (= sin(theta/2) axis of
//              R_bar^T R: zero only at R = R_bar, unlike vee(R_bar^T R - R^T R_bar) that also vanishes
//              at half turns)
//   collar:    p(L) - p_bar, first two components of g (e3 x b), b = R_bar^T d3, g = 2 / sqrt(2 (1 + b_z))
//              (the smallest rotation from d3_bar to d3; zero only for d3 = +d3_bar), (m(L) - moment) . d3
//   spherical: p(L) - p_bar, m(L) - moment
//   free:      n(L) - force, m(L) - moment
//   universal: p(L) - p_bar, (R_bar a) . (R b), (m(L) - moment) . R_bar a, (m(L) - moment) . R b
//   revolute:  p(L) - p_bar, two components of the smallest rotation from R_bar a to R a (zero only for
//              R a = R_bar a), (m(L) - moment) . R_bar a
// Every pairing that RodModel::validate accepts is supported (one end holds the twist: clamped,
// universal or revolute; the two ends hold the rod as a rigid body). A collar
// honours the torsional part of its applied moment (m . d3 = moment . d3; docs/design.md's m . d3 = 0 is
// the unloaded case).
//
// Strategy: Newton from the warm start, or else from the unloaded rod (clamped base: n(0) = m(0) = 0;
// joint bases: the end frame turned towards the prescribed tip; other bases: a straight rod ending at
// the clamped tip), with every step capped to max_step (in units
// of EI/L^2, EI/L, L, 1 rad), a backtracking line search, Levenberg-Marquardt when that fails, and stall
// detection. With Dormand-Prince the step sequence is frozen once the residual is below
// freeze_mesh_below, so that the map is smooth near the root. If the full-load solve fails, load
// stepping restarts from lambda = 0.
//
// Load stepping scales the distributed loads and the loads at both ends by lambda in (0, 1]; when the
// base is clamped, a prescribed tip position/orientation (every tip kind but free) moves
// with lambda from the unloaded tip pose (lambda = 0) to the prescribed one (lambda = 1).
#include <memory>
#include <vector>

#include "pcr/rods/rod_model.hpp"
#include "pcr/rods/shooting/rod_integrator.hpp"
#include "pcr/rods/shooting/rod_ode.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr {

struct ShootingOptions {
  using Integrator = IntegratorMethod;
  Integrator integrator = Integrator::DormandPrince;
  int rk4_steps = 100;
  /// Dormand-Prince: local error tolerances per step (IntegratorOptions); the absolute one is relative
  /// to L, 1, F_c, M_c per state component (RodOde::state_scale).
  double integration_relative_tolerance = 1e-10;
  double integration_absolute_tolerance = 1e-12;
  double min_step_fraction = 1e-12;
  int max_integration_steps = 100000;
  /// Convergence: max-abs of the tip residuals divided by L (positions), 1 (directions), F_c (forces),
  /// M_c (moments) at most this (SolveSummary::residual_scaled_max_abs).
  double tolerance = 1e-10;
  int max_iterations = 50;  ///< per load step
  /// Dormand-Prince: when the scaled residual falls below this, the step sequence is frozen for the
  /// rest of the Newton solve (a smooth map, so Newton reaches round-off instead of the tolerance-sized
  /// noise of changing steps); the converged answer is then re-checked by an adaptive integration
  /// (re-solving on the new mesh up to 3 times if that check fails).
  double freeze_mesh_below = 1e-6;
  /// Largest change of any base unknown per iteration, in units of its scale (max(K_BT) / L^2 for
  /// forces, max(K_BT) / L for moments, L, 1 rad):
  /// keeps Newton from jumping to a rod curled into many loops when the Jacobian is nearly singular.
  double max_step = 2.0;
  /// A solve stops as stalled when the scaled residual norm fell by less than a factor stall_ratio over
  /// the last stall_window iterations (0 = never): load stepping then takes over.
  int stall_window = 4;
  double stall_ratio = 0.9;
  bool levenberg_marquardt = true;
  bool load_stepping = true;
  double initial_load_increment = 0.25;  ///< first lambda increment after a failed full-load solve
  /// Largest lambda increment (increments double after each success up to this): small enough that a
  /// warm start stays on the branch of the previous solution (Bisshopp-Drucker alpha = 100 jumps to
  /// an equilibrium with the tip bent past vertical with increments of 0.5).
  double max_load_increment = 0.25;
  double min_load_increment = 1e-3;  ///< give up when the increment is halved below this
  int max_load_steps = 200;
  bool store_trajectory = true;  ///< keep the state at every step of the final integration

  IntegratorOptions integrator_options() const;
};

class ShootingSolution {
 public:
  SolveSummary summary;               ///< with load_steps and integration_steps
  ShootingState base;                 ///< state at s = 0 (the converged unknowns, or the last iterate)
  ShootingState tip;                  ///< state at s = L
  std::vector<double> s;              ///< accepted integration steps (if store_trajectory)
  std::vector<ShootingState> states;  ///< state at each s

  /// State at any s in [0, L]: one step of the solve's integrator from the stored step at or before s
  /// (re-integration, same order as the solve). Throws InputError for s outside [0, L] or no trajectory.
  ShootingState at(double s) const;
  /// States at many s (any order).
  std::vector<ShootingState> sample(const std::vector<double>& s_values) const;
  /// Force and moment (about p(0)) that the base support applies to the rod: -n(0), -m(0).
  Vec3 base_force() const { return -base.n; }
  Vec3 base_moment() const { return -base.m; }
  Vec3 tip_position() const { return tip.p; }
  Mat3 tip_orientation() const { return tip.R(); }

 private:
  friend ShootingSolution solve_rod_shooting(const RodModel&, const ShootingOptions&,
                                             const ShootingSolution*);
  std::shared_ptr<const RodOde> ode_;
  IntegratorMethod method_ = IntegratorMethod::DormandPrince;
};

/// Solves the rod's equilibrium by shooting. Throws InputError for an invalid model or options;
/// solver outcomes (not converged, integration failure) are reported in summary, never as NaN.
/// warm_start: a previous solution whose base state is the initial guess (e.g. along a trajectory).
ShootingSolution solve_rod_shooting(const RodModel& model, const ShootingOptions& options = ShootingOptions(),
                                    const ShootingSolution* warm_start = nullptr);

}  // namespace pcr
