#pragma once
// The Morse index of one rod's second variation with its ends held as their couplings allow (links
// fixed), by Morse's broken-extremal reduction in the form of the Wittrick-Williams algorithm
// (docs/design.md §4; Wittrick & Williams 1973, J. Struct. Mech. 1(4):497-518):
//  1. cut [0, L] into segments short enough to hold no conjugate point of their own;
//  2. per segment, integrate the 12 x 12 transfer matrix of the linearised equilibrium (Jacobi)
//     equations z' = A(s) z, z = (dp, dth, dn, dm) (world frame, dth the spatial rotation vector), by
//     classical RK4 on the equilibrium state;
//  3. change to canonical variables (x, pi) = (dp, dth, dn, dm + 1/2 m x dth), in which the system is
//     Hamiltonian and the transfer matrix symplectic, and turn it into the symmetric segment stiffness
//     K_k with [x_a; x_b]^T K_k [x_a; x_b] = the second variation on the segment;
//  4. assemble the quadratic form on the node values (the end nodes restricted to the variations their
//     couplings admit, x_e = Z_e phi_e, plus the coupling's curvature term phi^T B_e phi) and eliminate
//     node by node (block LDL^T): by Haynsworth's inertia additivity the index is the sum of the pivots'
//     numbers of negative eigenvalues.
// Variables are dimensionless throughout: s / L, dp / L, dth, dn / F, dm / M with M = max(K_BT) / L and
// F = M / L, so that K_k is the second variation divided by M.
#include <functional>
#include <string>
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/rods/rod_model.hpp"

namespace pcr {

/// What the Jacobi equations need from the equilibrium at arc length s (world frame).
struct JacobiState {
  Mat3 rotation = Mat3::Identity();  ///< R = [d1 d2 d3]
  Vec3 force = Vec3::Zero();         ///< n (part s+ on part s-)
  Vec3 moment = Vec3::Zero();        ///< m
  Vec3 tangent = Vec3::UnitZ();      ///< p' = R v, v = K_SE^-1 R^T n + e3 + eps0
  double curvature = 0.0;            ///< |u|, u = K_BT^-1 R^T m + kappa0 (sizes the integration steps)
  /// How far the state is from an exact equilibrium of the rod: the largest difference between the
  /// strains of the centerline and frame (p', R' of a discrete solution) and those of the constitutive law
  /// with n, m, |dv| and |du| L (0 for a state integrated from the ODE). Widens the neutral tolerance.
  double strain_mismatch = 0.0;
};
using JacobiStateAt = std::function<JacobiState(double s)>;

/// The variations an end admits with its link held (world vectors at the equilibrium).
struct HeldEnd {
  RodEndKind kind = RodEndKind::Clamped;
  Vec3 axis = Vec3::UnitX();         ///< revolute: the pin axis; universal: the first axis (link-fixed)
  Vec3 second_axis = Vec3::UnitY();  ///< universal: the second axis (rod-fixed)
};

struct HeldRod {
  double length = 0.0;
  Vec3 shear_extension_stiffness = Vec3::Zero();  ///< diagonal of K_SE [N]
  Vec3 bending_torsion_stiffness = Vec3::Zero();  ///< diagonal of K_BT [N m^2]
  HeldEnd base, tip;
};

struct HeldRodIndex {
  bool ok = false;      ///< false: failure says why (no count)
  std::string failure;  ///< e.g. a segment that could not be made free of conjugate points
  int unstable_modes = 0;
  /// Eigenvalues of the probe pivot (the last one) within neutral_tolerance of zero: the rod is at a
  /// conjugate point (a fold or bifurcation with its ends held) or has a symmetry.
  int neutral_modes = 0;
  /// Smallest eigenvalue of the probe pivot: the dimensionless stiffness of the rod (ends held) against
  /// a motion of its free end's admitted components, or of its middle section when no end moves.
  double margin = 0.0;
  double length_scale = 0.0, energy_scale = 0.0;  ///< of the margin: L [m] and M = max(K_BT) / L [J]
  double asymmetry = 0.0;          ///< largest relative asymmetry of a segment stiffness before symmetrising
  double neutral_tolerance = 0.0;  ///< |eigenvalue| below which a probe eigenvalue counts as neutral
  double strain_mismatch = 0.0;    ///< largest JacobiState::strain_mismatch at the sample points
  int segments = 0;
};

struct HeldRodOptions {
  int rk4_substeps = 4;  ///< RK4 steps per segment
  /// Segments over the rod at least (e.g. the collocation elements, over which the state is smooth); more
  /// where the forces, moments or curvature need them (held_rod.cpp).
  int min_segments = 4;
};

/// Morse index of the rod's second variation with its ends held (see above). `state` gives the
/// equilibrium at any s in [0, L]; the loads must be conservative (dead forces; no dead couple where an
/// end can rotate, no distributed couple): the caller checks (rod_stability.hpp).
HeldRodIndex held_rod_index(const HeldRod& rod, const JacobiStateAt& state,
                            const HeldRodOptions& options = {});

namespace stability {

using Mat12 = Eigen::Matrix<double, 12, 12>;

/// Dimensionless symmetric segment stiffness of [s_a, s_b] (step 2-3 above) from `substeps` RK4 steps;
/// `asymmetry` receives its relative asymmetry before symmetrising. Returns false when the segment
/// holds a conjugate point (det of the transfer matrix's dx/dpi block not positive at a step).
bool segment_stiffness(const HeldRod& rod, const JacobiStateAt& state, double s_a, double s_b, int substeps,
                       Mat12& stiffness, double& asymmetry);

}  // namespace stability

}  // namespace pcr
