#pragma once
// Stability verdict of a robot equilibrium (docs/design.md §4 "Stability"). The second variation H of the
// total potential energy on the admissible variations (rod shapes, platform poses; inputs fixed) splits,
// with the rods' variations first and the platforms' last, as
//   H = [A B; B^T D],  K_red = D - B^T A^-1 B,
// A = the rods with their couplings held in fixed link frames. By Haynsworth's inertia additivity
// (Linear Algebra Appl. 1:73-81, 1968), when A is regular
//   unstable modes = sum over rods of their index with links held (held_rod.hpp) + negative eigenvalues of
//   K_red,
// K_red being the Hessian of the energy reduced to the platform poses (rods in equilibrium): the tangent
// stiffness of the platforms, the inverse of their full compliance, which the implicit function theorem
// gives from the FK Jacobian at the solution (ForwardKinematics::compliance is its diagonal block). The
// compliance is taken in (dx, world rotation vector) against (force, moment about the platform origin),
// the pairing in which it is a Hessian (symmetric at an equilibrium; the collocation makes it so up to
// its discretisation error, reported as the asymmetry).
// Assumptions (else the verdict is `unknown` with the reason): conservative loads (dead forces and
// gravity; no dead couple on a platform or at a rod end that can turn, no distributed couple, no dead
// torque on a link). Where a rod is at a conjugate point with its links held (A singular) the whole robot
// is counted on the energy's Ritz form instead (docs/design.md §4; `unknown` where the energy does not
// describe the model). Contact: with every
// contact open the equilibrium is one of the robot without obstacles (small variations keep it so);
// where a rod touches an obstacle the count is taken on the energy's Ritz form with the touching contacts
// held (docs/design.md §4; `unknown` where one carries no force, or for contact the energy does not
// describe: sharp obstacles, point contact, adhesion, obstacles on a platform). Passive joints are border
// coordinates beside the platform poses (docs/design.md §4).
#include <string>

#include "pcr/robots/robot_assembly.hpp"
#include "pcr/rods/stability/stability.hpp"

namespace pcr {

/// The reduced stiffness of the border coordinates at the converged FK state x in the dimensionless form
/// K_hat = D K_red D / M0 (before symmetrising), or a failure. Coordinates: per platform (RobotModel
/// order) [dx / L0 (3), dtheta (3)] (world frame, rotation vector), then per passive joint
/// (RobotModel::passive_joints() order) dq / L0 (prismatic) or dq [rad] (revolute, continuous); D holds
/// L0 or 1 for each (coordinate_scale), L0 = length_scale, M0 = energy_scale (the assembly's length and
/// moment scales). K_red = M0 D^-1 K_hat D^-1 is the stiffness in SI units: N/m, N/rad, N m/rad against
/// (dx, dtheta, dq). Empty (ok) without platforms and passive joints.
struct BorderStiffness {
  bool ok = false;
  std::string failure;
  MatX stiffness;
  VecX coordinate_scale;  ///< D
  double length_scale = 0.0, energy_scale = 0.0;
};
BorderStiffness robot_border_stiffness(const RobotAssembly& assembly, const VecX& x);

/// Verdict on the equilibrium x of the assembly's FK system (inputs at the values x holds); x must be a
/// converged solution. Rod counts, border count and margin as in Stability (margin: smallest eigenvalue
/// of the border's reduced stiffness K_hat (robot_border_stiffness); without platforms and passive joints,
/// the smallest rod margin).
Stability robot_stability(const RobotAssembly& assembly, const VecX& x);

}  // namespace pcr
