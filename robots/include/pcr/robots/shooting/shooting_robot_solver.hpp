#pragma once
// Forward and inverse kinematics of a RobotModel by shooting (Black, Till & Rucker 2018, "Parallel
// continuum robots: modeling, analysis, and actuation-based force sensing", IEEE T-RO 34(1);
// docs/design.md §6): the independent reference of the collocation solver (kinematics.hpp).
//
// Unknowns: for every rod its six base unknowns (world frame): n(0), m(0) for a clamped start;
// n(0), the joint angles and the transmitted moment components for a universal or revolute start
// (pcr/rods/shooting/joint_ends.hpp: R(0) = R_T R_a(theta1) R_b(theta2) with m(0) = -mu t, or
// R(0) = R_T R_a(theta) with m(0) = -R_T (mu1 c1 + mu2 c2)); for FK every platform pose (position x and
// a world rotation vector increment: R <- exp(hat(dtheta)) R), for IK the inputs (the platform poses
// are the targets, so the system is square when the model has 6 inputs per platform); every passive
// joint's value. Residuals: each rod's tip coupling against the platform pose (clamped: position +
// 2 vec(q_e); collar: position, the two components of R_T^T d3 normal to the frame axis, m(L) . d3 = 0;
// spherical: position, m(L) = 0; universal / revolute: position and the joint's rows of joint_ends.hpp),
// each platform's balance (docs/design.md §3)
//   F_ext + m g - sum n(L) = 0,
//   M_ext + (x_c - x) x m g + (r_F - x) x F_ext - sum (m(L) + (p(L) - x) x n(L)) = 0
// and each passive joint's balance Q - k (q - rest) = 0, Q = w . sum (m(0) + (p(0) - o) x n(0)) + w . sum
// (c - o) x m_l g over the rods starting and the links with mass beyond the joint (axis w, origin o;
// prismatic: Q = w . (sum n(0) + sum m_l g)); link masses elsewhere are carried by the world or counted
// in the platform's mass (Link::mass).
// Base frames follow the URDF forward kinematics of the current joint values (inputs and passive
// joints). Newton (the shared loop, pcr/solve/newton_loop.hpp) with the Jacobian from the variational
// equations (integrate_rod with tangents; d y(L)/dL = f(L, y(L)) for fed lengths; for a base frame moved
// by an unknown joint value, a second tangent pass on the same steps for the frame's rotation, its
// translation moving the whole rod) and central differences of the algebraic tip/balance functions,
// step cap, backtracking line search,
// Levenberg-Marquardt fallback, stall test; with Dormand-Prince the step sequence of every rod is
// frozen once the residual is small (a smooth map, so Newton converges to round-off).
// Every solve is warm-started from the previous converged one (for paths), first with chord steps
// (the previous Jacobian's LU, state-only integrations) while they halve the residual. A cold FK goes
// through the default inputs (the URDF's initial platform pose is meant for them); a failed solve
// (stalled or out of iterations) is retried by continuation in the inputs (FK) or the target poses
// (IK) from the last solution, in 4, 8, ..., 64 steps.
//
// Supported: rods that start clamped, universal or revolute on a link not carried by a platform (fixed
// to the world or moved by actuated or passive revolute, continuous or prismatic joints), fixed or
// actuated length, and end on a link carried by a platform with a clamped, collar, spherical, universal or
// revolute coupling; gravity on rods, platforms and links beyond passive joints; external loads on
// platform-carried links. Anything else (rods between two platforms, free ends, collar or spherical
// starts, moving joints on platforms, loads on links moved by passive joints) throws InputError naming
// the rod, joint or link.
#include <memory>
#include <string>
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/robots/pose.hpp"
#include "pcr/robots/robot_model.hpp"
#include "pcr/robots/robot_solution.hpp"
#include "pcr/rods/shooting/integrator_method.hpp"

namespace pcr {

struct ShootingRobotOptions {
  IntegratorMethod integrator = IntegratorMethod::DormandPrince;
  int rk4_steps = 40;  ///< RK4: steps per rod
  /// Dormand-Prince: local error tolerances per step; the absolute one per state component times L,
  /// 1, F_c, M_c of the rod (IntegratorOptions).
  double integration_relative_tolerance = 1e-10;
  double integration_absolute_tolerance = 1e-12;
  /// Convergence: max-abs of the residuals divided by L_max (positions), 1 (directions), F_s (forces),
  /// F_s L_max (moments), F_s = max(max EI / L^2, total applied force), at most this
  /// (SolveSummary::residual_scaled_max_abs).
  double tolerance = 1e-10;
  int max_iterations = 100;
  /// Dormand-Prince: freeze each rod's step sequence once the scaled residual is below this.
  double freeze_mesh_below = 1e-6;
  /// Largest change of any unknown per iteration in units of its scale (F_s, F_s L_max, L_max, 1 rad).
  double max_step = 0.5;
  bool levenberg_marquardt = true;
  /// A solve stops as stalled when the residual norm fell by less than 10 % over this many
  /// iterations (0 = never); continuation then takes over. (10 stops the capped-step approach from
  /// the cold guess of R5a with mixed couplings that converges in 25.)
  int stall_window = 20;
  /// Warm-started solves first take chord steps with the previous solve's Jacobian (state-only
  /// integrations) while each halves the residual, then Newton.
  bool reuse_jacobian = true;
};

class ShootingRobotSolver {
 public:
  /// Throws InputError for an unsupported model feature (see above) or bad options.
  ShootingRobotSolver(std::shared_ptr<const RobotModel> model, const ShootingRobotOptions& options = {});
  ~ShootingRobotSolver();
  ShootingRobotSolver(ShootingRobotSolver&&) noexcept;
  ShootingRobotSolver& operator=(ShootingRobotSolver&&) noexcept;

  /// Platform poses for the given inputs (model order); InputError for a wrong size or out of bounds.
  /// Fills of RobotSolution: summary (with load_steps: continuation steps), inputs, platforms, passive joint
  /// values, and per rod name, length, base and tip wrenches, axial force, centerline (the integrator's
  /// steps) and smallest axial stretch at them; not jacobian_sign (collocation only).
  RobotSolution fk(const VecX& inputs);
  /// Inputs that put every platform at its target pose (platform order). Needs 6 inputs per platform
  /// (square system); InputError otherwise or for a wrong number of targets.
  RobotSolution ik(const std::vector<Pose>& platform_targets);
  /// Forget the warm start (the next solve starts from the cold guess).
  void reset();

  const RobotModel& model() const;
  const ShootingRobotOptions& options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pcr
