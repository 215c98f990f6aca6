#pragma once
// Pseudo-transient continuation (PTC) to an equilibrium at fixed inputs (internal header of
// pcr::robots): the robot's platforms and passive joints get viscous dampers anchored at their last
// pose, the rods stay quasi-static, and implicit Euler steps in a pseudo-time tau follow the damped
// motion. Each step solves (Newton) the FK system with the damper rows added,
//
//   R_platform(x) - (1/tau) D (q(x) - q(x_k)) = 0,   q = (position / L0, rotation vector) per platform,
//                                                        (q / L0 or q) per passive joint,
//
// (D = I in the dimensionless rows, L0 the assembly's length scale; R elsewhere unchanged), from x_k;
// tau grows geometrically while the steps converge quickly, shrinks when one fails (Kelley & Keyes,
// "Convergence analysis of pseudo-transient continuation", SIAM J. Numer. Anal. 35(2), 1998). Where
// plain Newton from a state beyond a fold jumps back to the fold or diverges, the damped motion follows
// the robot's descent (for conservative loads: implicit Euler on the gradient flow of the total potential
// energy reduced to the damped coordinates) to an equilibrium, mostly a stable one. The result is only a
// candidate: the caller judges it by its stability verdict. The last step is the FK Newton solver itself
// on the undamped system (the full tolerance).
#include <string>

#include "pcr/robots/robot_assembly.hpp"

namespace pcr::kinematics {

struct PseudoTransientResult {
  bool converged = false;  ///< x is an equilibrium of the FK system to the tolerance
  VecX x;                  ///< the last state (finite)
  int steps = 0, iterations = 0, jacobian_evaluations = 0;
  std::string stopped;  ///< why not converged
};

/// From `start` (inputs written in, the free variables a state near the one to relax) to an
/// equilibrium at the same inputs; tolerance on the max-abs residual (as NewtonSolver's). shift > 0 adds
/// the classic PTC term -(shift / tau) (x_i - x_k,i) to row i of the free unknowns without a damper (row
/// and column i of the square free system, D = I there; Kelley & Keyes): not a physical damper (a row
/// is not the balance of its column's unknown), a regularisation that holds the rods' unknowns near
/// their last values where their own soft modes (a rod with universal and spherical ends turning about
/// its chord) stall the steps with the platforms damped alone; it vanishes as tau grows.
PseudoTransientResult pseudo_transient_equilibrium(const RobotAssembly& assembly, const VecX& start,
                                                   double tolerance, double shift = 0.0);

/// The unstable mode of an equilibrium x's border: the eigenvector w of the most negative eigenvalue of its
/// symmetrised reduced stiffness (robot_border_stiffness: per platform [dx / L0, dtheta], per passive joint
/// dq / L0 or dq), scaled so that its largest coordinate is 1; empty where the border has no negative
/// eigenvalue or no count.
VecX border_unstable_mode(const RobotAssembly& assembly, const VecX& x);
/// A start for the damped motion off x: x moved by amplitude x mode (border_unstable_mode; the sign of
/// amplitude: the direction).
VecX pushed_along_border_mode(const RobotAssembly& assembly, const VecX& x, const VecX& mode,
                              double amplitude);

}  // namespace pcr::kinematics
