#pragma once
// The total potential energy of a robot at fixed inputs as an optimisation problem (the last FK strategy,
// energy_fallback.hpp; docs/design.md "Energy minimisation (the last FK strategy)"), internal header of
// pcr::robots:
//   min  V = sum_rods int_0^L [1/2 (v - v*)^T K_SE (v - v*) + 1/2 (u - u*)^T K_BT (u - u*) - f . p] ds
//          - sum_free_rod_ends F . p
//          - sum_platforms (m g + F) . (weights' and dead forces' points)
//          + sum_passive 1/2 k (q - rest)^2 - (weights and dead forces on links moved by passive joints)
//   s.t. each attached rod end in its link frame (the kinematic part of its coupling), unit quaternions,
//        and each rod's gaps to its obstacles >= 0 at the collocation's contact midpoints (frictionless
//        contact: a workless reaction, the multiplier of its gap row).
// Discretisation (Ritz form): each rod's p(u), q(u) are B-splines on the rod's own knots (those of its
// collocation form), so the minimiser maps onto the collocation unknowns control point by control point;
// v = R(q)^T p_s, u = 2 vec(conj(q) q_s) / |q|^2 (R(q) of the normalised q), integrated by Gauss-Legendre
// with degree + 1 nodes per element. Unknowns: per control point [P (3), Q (4)], per platform [x (3),
// Q (4)], per passive joint its value (unbounded, as the collocation's: joint limits are not enforced);
// the rod lengths are the inputs. The energy is scaled by the assembly's moment scale M0 [J], coupling
// positions by its length scale L0.
#include <string>
#include <vector>

#include "pcr/robots/robot_assembly.hpp"
#include "pcr/solve/problem.hpp"

namespace pcr::kinematics {

/// Why the energy above cannot describe the model, or "" when it can: it needs conservative loads (no
/// dead torque, no distributed couple, no moment applied at a rod end, no drawn rod), contact only with
/// distributed obstacles not carried by a platform (no sharp obstacle, point contact or adhesion), and no
/// passive joint below a platform.
std::string energy_model_refusal(const RobotModel& model);

class EnergyModel {
 public:
  /// The energy of the assembly's robot at the inputs (and rod lengths) that the collocation state x
  /// holds. Precondition: energy_model_refusal(assembly.model()) is empty.
  EnergyModel(const RobotAssembly& assembly, const VecX& x);

  /// The optimisation problem: objective V / M0, constraint rows (coupling positions / L0, coupling
  /// rotations, |Q|^2 - 1).
  const Problem& problem() const { return problem_; }
  /// The energy unknowns of a collocation state (P, Q of every control point, platform poses, passive
  /// joint values).
  VecX from_state(const VecX& x) const;
  /// Writes the energy unknowns e into the collocation state x (which holds the inputs): control points'
  /// P, Q; mixed rods' N, M interpolating the constitutive forces and moments at the Greville points;
  /// condensed rods' constant wrench and running integrals; platforms; passive joints; per contact
  /// midpoint and obstacle the density of the gap row's point force (row_multipliers: the minimiser's,
  /// IpoptSolver's sign) spread over the midpoint's cell (0 without row_multipliers).
  void to_state(const VecX& e, VecX& x, const VecX& row_multipliers = VecX()) const;
  /// e moved off any symmetry plane of the robot: control point and platform positions by up to
  /// size L0, their quaternions and the passive joint values by up to size, in a fixed pattern (a
  /// minimiser started on a symmetric state stays on it by symmetry, where the equilibrium may be a saddle
  /// of the full energy: planar robots' in-plane states).
  VecX perturbed(const VecX& e, double size) const;
  /// V [J] at the energy unknowns e.
  double energy(const VecX& e) const;
  double energy_scale() const { return energy_scale_; }

 private:
  const RobotAssembly& assembly_;
  Problem problem_;
  std::vector<std::vector<VariableId>> rod_points_;  // per rod: its control points [P, Q]
  std::vector<VariableId> platforms_, passive_;
  std::vector<std::vector<Obstacle>> rod_obstacles_;  // per rod: its distributed obstacles, placed
  std::vector<std::vector<ResidualId>> gap_rows_;     // per rod: its gap rows per contact midpoint
  double energy_scale_ = 1.0;
  /// A run of unknowns the collocation state and the energy unknowns share (a control point's P or Q, a
  /// platform pose, a passive joint value): from_state and to_state copy them one way and the other.
  struct SharedSlice {
    int state_offset, energy_offset, size;
  };
  std::vector<SharedSlice> shared_;

  /// The links' configuration at the state the model is built at: the joint values (inputs and passive
  /// joints) and the platform poses, which place loads, attachments and obstacles in the link frames.
  struct LinkState {
    VecX joint_values;
    std::vector<Pose> platform_poses;
  };
  void add_rods(const VecX& x);
  void add_platforms_and_passive_joints(const LinkState& links);
  void add_couplings(const LinkState& links);
  void add_obstacle_gaps(const LinkState& links);
  void write_contact_forces(int rod, const VecX& row_multipliers, VecX& x) const;
  void write_rod_forces(int rod, const VecX& e, VecX& x) const;
  void find_shared_slices();
};

}  // namespace pcr::kinematics
