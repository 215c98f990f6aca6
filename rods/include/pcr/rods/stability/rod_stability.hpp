#pragma once
// Stability verdict of one rod's equilibrium with its model's end conditions (docs/design.md §4): the
// Morse index of held_rod.hpp on the collocation or the shooting solution, `unknown` where the loads are
// not conservative.
#include <string>

#include "pcr/rods/collocation_rod.hpp"
#include "pcr/rods/rod_model.hpp"
#include "pcr/rods/shooting/rod_shooting.hpp"
#include "pcr/rods/stability/held_rod.hpp"
#include "pcr/rods/stability/stability.hpp"

namespace pcr {

/// Why the rod's loads have no potential (empty when they have one): a distributed couple, or a dead
/// couple at an end that can turn about more than one fixed axis (spherical, universal, free). A dead
/// couple M does no exact work on SO(3) (M . dtheta is not a differential; Ziegler, Principles of
/// Structural Stability; Argyris et al., CMAME 1979): its load stiffness has the skew part 1/2 [M]x.
/// A collar's or revolute end's applied moment turns it about one fixed axis (potential -M . a phi).
std::string nonconservative_loads(const RodModel& model);

/// Why a drawn rod's end conditions, which hold for the section force and moment n, m, are not natural
/// conditions of the effective energy that the verdict tests (conditions on N, M; drawn_rod.hpp); empty
/// when they are, and for a rod that is not drawn. Natural: clamped ends; spherical ends without an
/// applied moment on a rod without intrinsic curvature (m = R D R^T M, D diagonal positive, so m = 0 iff
/// M = 0); universal ends likewise, where m_i = lambda M_i in both bending directions (lambda =
/// 1 / (1 - rho c^2 / E) for a homogeneous section), if the state also passes
/// drawn_joint_state_problem. Part of nonconservative_loads.
std::string drawn_end_problem(const RodModel& model);

/// The state part of a drawn rod's universal ends (docs/design.md §1 "Drawn rods"), at the equilibrium
/// `states` with the ends held as in `rod` (world axes): with the body torsion u3 = 0 the section moment
/// is m = lambda M, and with the first axis a normal to d3 (the second one, b = e3 x a, always is)
/// m . a = 0 and m . b = 0 say M . a = 0 and M . b = 0, also to first order about the state (dm . a =
/// lambda dM . a); else the joint's rows are not the effective energy's natural conditions. Returns the
/// reason (naming the end, u3 L and d3 . a) when |u3| L or |d3 . a| exceeds max(1e-8, the state's strain
/// mismatch there); empty otherwise and for rods that are not drawn.
std::string drawn_joint_state_problem(const RodModel& model, const HeldRod& rod, const JacobiStateAt& states);

/// The stiffnesses of the model as a HeldRod, its ends held as its model holds them (end kinds, the
/// revolute and universal axes from the end frames and the rod frame at the end).
HeldRod held_rod(const RodModel& model, const Mat3& base_rotation, const Mat3& tip_rotation);
/// The axes of an end of kind `kind` held in the end frame `end_frame` (world rotation of the link's
/// attachment frame; axis in it), the rod's frame at that end being `rod_rotation`.
HeldEnd held_end(RodEndKind kind, const Mat3& end_frame, const Vec3& axis, const Mat3& rod_rotation);

/// The Jacobi states along a collocation solution (p' and |u| from the constitutive law with n, m).
JacobiStateAt jacobi_states(const CollocationRod& rod, const VecX& x, const RodVariables& vars);

/// Verdict from a held-rod count: Stable / Unstable / Critical, or Unknown with its failure.
Stability held_rod_stability(const HeldRodIndex& index);

/// The verdict of a converged collocation solution (RodSolution: rod_solve.hpp).
Stability rod_stability(const CollocationRod& rod, const VecX& x, const RodVariables& vars);
/// The verdict of a converged shooting solution of `model`.
Stability rod_stability(const RodModel& model, const ShootingSolution& solution);

}  // namespace pcr
