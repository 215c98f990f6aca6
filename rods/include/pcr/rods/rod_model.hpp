#pragma once
// Description of one Cosserat rod (docs/design.md §1): geometry, stiffness, intrinsic strains, loads and
// the conditions at its two ends. Shared by the collocation rods and the shooting reference, so that
// both solve exactly the same problem. SI units; vectors in the world frame unless named _body.
#include <functional>
#include <string>

#include "pcr/core/types.hpp"
#include "pcr/math/quaternion.hpp"

namespace pcr {

struct Material {
  double youngs_modulus = 0.0;  ///< E [Pa]
  double shear_modulus = 0.0;   ///< G [Pa]
  double density = 0.0;         ///< rho [kg/m^3]
  /// G = E / (2 (1 + nu)).
  static Material from_poisson_ratio(double youngs_modulus, double poisson_ratio, double density);
};

struct CrossSection {
  double area = 0.0;              ///< A [m^2]
  double second_moment_1 = 0.0;   ///< I1 about d1 [m^4]
  double second_moment_2 = 0.0;   ///< I2 about d2 [m^4]
  double torsion_constant = 0.0;  ///< J [m^4]
  double shear_coefficient =
      1.0;                    ///< k in K_SE = diag(k G A, k G A, E A); 1 as in Till & Rucker's PCR models
  double outer_radius = 0.0;  ///< largest distance of a section point from the centerline [m] (for stresses)
  /// Solid circle of the given radius: A = pi r^2, I1 = I2 = pi r^4 / 4, J = pi r^4 / 2.
  static CrossSection circle(double radius);
  /// Solid rectangle, width along d1, height along d2: I1 = w h^3 / 12, I2 = h w^3 / 12, J by the
  /// series approximation a b^3 (1/3 - 0.21 (b/a) (1 - b^4 / (12 a^4))), a >= b; k = 5/6.
  static CrossSection rectangle(double width, double height);
};

/// Kind of condition at a rod end (docs/design.md §1; Dirichlet = kinematic, Neumann = loads).
enum class RodEndKind {
  Clamped,    ///< p = position, R = R(orientation)                           (Dirichlet)
  Collar,     ///< p = position, d3 parallel to R(orientation) e3, m . d3 = moment . d3 (free in torsion)
  Spherical,  ///< p = position, m = applied moment (0 for a pin)
  /// Hooke joint: p = position; the rod frame turns only about a first axis a fixed in the end frame and
  /// a second axis b fixed in the rod (b = e3 x a / |e3 x a| in the rod's body frame, i.e. normal to a and
  /// to the tangent when the rod frame equals the end frame); no moment about a or b (the applied moment
  /// aside); torsion is transmitted.
  Universal,
  /// Pin: p = position; the rod frame turns only about the axis a fixed in the end frame; no moment about a
  /// (the applied moment aside).
  Revolute,
  Free  ///< applied force and moment (dead loads)                    (Neumann)
};
const char* to_string(RodEndKind kind);

struct RodEnd {
  RodEndKind kind = RodEndKind::Free;
  Vec3 position = Vec3::Zero();  ///< prescribed position (Clamped, Collar, Spherical)
  Quat orientation =
      Quat(1, 0, 0, 0);  ///< prescribed frame (Clamped, Universal, Revolute) or axis R e3 (Collar)
  /// Universal: the first joint axis a; Revolute: the pin axis a. A vector in the end frame
  /// (`orientation`), normalised where used (end_axes.hpp), not along its z axis for Universal.
  Vec3 axis = Vec3::UnitX();
  /// External force and moment applied *to the rod* at this end (world frame). With n, m the force
  /// and moment that the part s+ exerts on s-: at s = L, n = force, m = moment; at s = 0,
  /// n = -force, m = -moment.
  Vec3 force = Vec3::Zero();
  Vec3 moment = Vec3::Zero();
};

/// Intrinsic (stress-free) strains eps0, kappa0 in the body frame; constant unless `varying` is set.
struct IntrinsicStrains {
  Vec3 shear_extension = Vec3::Zero();  ///< eps0
  Vec3 curvature = Vec3::Zero();        ///< kappa0 [1/m]
  /// Optional s-dependent strains: varying(s, eps0, kappa0) overrides the constants.
  std::function<void(double s, Vec3& eps0, Vec3& kappa0)> varying;
  void at(double s, Vec3& eps0, Vec3& kappa0) const;
  bool is_zero() const;
};

struct DistributedLoads {
  Vec3 gravity = Vec3::Zero();            ///< g [m/s^2]; contributes f = rho A g
  Vec3 force_per_length = Vec3::Zero();   ///< f [N/m], world frame
  Vec3 moment_per_length = Vec3::Zero();  ///< l [N], world frame
};

struct RodModel {
  std::string name = "rod";
  double length = 0.0;  ///< L [m]
  /// Diagonals of K_SE = diag(k G A, k G A, E A) [N] and K_BT = diag(E I1, E I2, G J) [N m^2].
  Vec3 shear_extension_stiffness = Vec3::Zero();
  Vec3 bending_torsion_stiffness = Vec3::Zero();
  double mass_per_length = 0.0;  ///< rho A [kg/m]
  double outer_radius = 0.0;     ///< for stress post-processing (0 = unknown)
  double youngs_modulus = 0.0;   ///< E [Pa], for stresses from forces (0 = unknown)
  IntrinsicStrains intrinsic;
  DistributedLoads loads;
  /// Drawing speed c [m/s]: the rod's material moves steadily along the fixed shape at c reference
  /// lengths per second (a rod drawn through guides; docs/design.md §1 "Drawn rods"). 0 = at rest. The
  /// steady shape depends on c^2 only. Needs a uniform rod (no s-varying intrinsic strains) and
  /// K_SE - rho A c^2, K_BT - rho c^2 J_rho positive definite (drawing_speed_problem).
  double drawing_speed = 0.0;
  RodEnd base;  ///< end at s = 0
  RodEnd tip;   ///< end at s = L

  /// Fills the stiffnesses, mass per length and outer radius from a material and a section.
  void set_material_and_section(const Material& material, const CrossSection& section);
  /// Distributed force f(s) = rho A g + force_per_length (constant along s).
  Vec3 distributed_force() const;
  /// Throws InputError naming the rod, the parameter and its value when the model is not usable:
  /// non-positive or non-finite length or stiffness, zero quaternion, a zero or non-finite joint axis
  /// (a universal one along the end's z axis), or ends that leave the equilibrium undetermined: one end
  /// must hold the twist (clamped, universal, or revolute with the pin not along the tangent; collars
  /// and spherical joints at both ends leave a free twist), and the two ends together must hold the rod
  /// as a rigid body (e.g. a universal or revolute end with the other end free does not).
  void validate() const;
  /// Why drawing_speed is not usable (empty when it is): not finite, c != 0 on a rod with s-varying
  /// intrinsic strains, or an effective stiffness (drawn_rod.hpp) not positive, naming the limit and its
  /// value. Also checked by validate().
  std::string drawing_speed_problem() const;
};

/// Arc length s checked against [0, length] and clamped into it. Up to 1e-12 length beyond either
/// end is accepted as round-off (a caller's s = L i / N); farther, or not finite, throws InputError
/// naming `who` (the rod's name, or the caller). Shared by the collocation and shooting solutions'
/// post-processing.
double checked_arc_length(double s, double length, const std::string& who);

}  // namespace pcr
