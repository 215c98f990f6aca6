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
// gravity; no dead couple on a platform or at a rod end that can turn, no distributed couple), no
// passive joints (not yet covered), no rod at a conjugate point with its links held (A singular).
#include "pcr/robots/robot_assembly.hpp"
#include "pcr/rods/stability/stability.hpp"

namespace pcr {

/// Verdict on the equilibrium x of the assembly's FK system (inputs at the values x holds); x must be a
/// converged solution. Rod counts, platform count and margin as in Stability (margin: smallest eigenvalue
/// of the platforms' reduced stiffness K_hat = D K_red D / M0, D = diag(L0, L0, L0, 1, 1, 1) per platform,
/// L0 and M0 the assembly's length and moment scales; without platforms, the smallest rod margin).
Stability robot_stability(const RobotAssembly& assembly, const VecX& x);

}  // namespace pcr
