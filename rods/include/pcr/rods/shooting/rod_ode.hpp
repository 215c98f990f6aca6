#pragma once
// The Cosserat rod as an initial value problem in s (docs/design.md §1, §6), for the shooting reference.
//
// State y = [p (3), q (4, [w,x,y,z]), n (3), m (3)] (world frame, 13 numbers). With R = R(q) and the
// body-frame strains
//   v = K_SE^-1 R^T n + eps0 + e3,   u = K_BT^-1 R^T m + kappa0,
// the ODE is (Till & Rucker / Black et al. 2018, quaternion form):
//   p' = R v,   q' = 1/2 q (x) [0, u],   n' = -f,   m' = -p' x n - l.
//
// Orientation: R(q) = R_unit(q) / |q|^2 (pcr/math/quaternion.hpp) is an exact rotation for every
// q != 0, and the flow of q' = 1/2 q (x) [0, u] keeps |q| constant (d|q|^2/ds = q . (q (x) [0,u]) = 0).
// The integrators renormalise q after each step; since R(q) and u do not depend on |q| this only
// removes the O(h^5) drift of |q|, it does not change the computed p, R, n, m.
//
// Tangents (variational equations): for a direction dy, dy' = (df/dy) dy with, for
// omega = 2 vec(conj(q) (x) dq) / |q|^2 (so that dR = R hat(omega)),
//   dv = K_SE^-1 (R^T n x omega + R^T dn),  du = K_BT^-1 (R^T m x omega + R^T dm),
//   dp' = R (omega x v + dv),  dq' = 1/2 (dq (x) [0,u] + q (x) [0,du]),  dn' = 0,
//   dm' = -(dp' x n + p' x dn).
// Integrated with the same steps as the state they give the exact derivative of the discrete map.
//
// Drawn rods (RodModel::drawing_speed, pcr/rods/drawn_rod.hpp): the state holds the effective force and
// moment N = n - rho A c^2 p', M = m - rho c^2 R J_rho kappa, whose balance laws are the static ones
// above, and K_SE, K_BT, eps0, kappa0 are the effective constants (M4). to_effective / to_section
// convert a state (and its tangents) between the section's n, m and N, M: the shooting ends are written
// for n, m.
#include <memory>

#include "pcr/core/types.hpp"
#include "pcr/rods/drawn_rod.hpp"
#include "pcr/rods/rod_model.hpp"

namespace pcr {

constexpr int kRodStateSize = 13;
/// Number of tangent directions integrated alongside the state (the 6 unknowns of a rod end).
constexpr int kRodTangentCount = 6;
using RodStateVector = Eigen::Matrix<double, kRodStateSize, 1>;
/// Column 0: the state y; columns 1..6: tangents dy/dz_j for six parameters z_j.
using RodStateWithTangents = Eigen::Matrix<double, kRodStateSize, 1 + kRodTangentCount>;

/// Offsets of the blocks in RodStateVector.
struct RodStateIndex {
  static constexpr int p = 0, q = 3, n = 7, m = 10;
};

/// One cross-section's state in readable form (world frame).
struct ShootingState {
  Vec3 p = Vec3::Zero();
  Quat q = Quat(1, 0, 0, 0);
  Vec3 n = Vec3::Zero();  ///< internal force (part s+ on part s-)
  Vec3 m = Vec3::Zero();  ///< internal moment (part s+ on part s-)

  Mat3 R() const;
  RodStateVector to_vector() const;
  static ShootingState from_vector(const RodStateVector& y);
};

/// Right-hand side of the rod ODE for one RodModel; cheap to copy, no allocation per evaluation
/// (unless the model has s-varying intrinsic strains, evaluated through their std::function).
class RodOde {
 public:
  /// load_factor scales every distributed load (f = rho A g + force_per_length, l); used by load
  /// stepping. Throws InputError if the model does not validate.
  explicit RodOde(const RodModel& model, double load_factor = 1.0);

  double length() const { return length_; }
  double load_factor() const { return load_factor_; }
  /// Distributed force f and moment l per length (world frame, load factor applied).
  const Vec3& force_per_length() const { return f_; }
  const Vec3& moment_per_length() const { return l_; }
  /// Characteristic sizes used to weigh errors: L, 1 (quaternion), F_c = max(max(K_BT) / L^2, sum of
  /// applied forces |F_base| + |F_tip| + |f| L), M_c = max(max(K_BT) / L, applied moments + F_c L).
  double length_scale() const { return length_; }
  double force_scale() const { return force_scale_; }
  double moment_scale() const { return moment_scale_; }
  /// max(K_BT) / L^2: the force that bends the rod by about a radian (sizes Newton steps).
  double bending_force_scale() const { return bending_force_scale_; }
  /// Per-component scale of the state (the absolute tolerance is multiplied by it).
  const RodStateVector& state_scale() const { return state_scale_; }

  /// Drawn rods: a state (with its tangents) with the section's n, m turned into one with N, M, and back.
  /// Nothing changes for a rod that is not drawn.
  bool drawn() const { return drawn_.drawn(); }
  void to_effective(RodStateVector& y) const;
  void to_section(RodStateVector& y) const;
  void to_effective(RodStateWithTangents& Y) const;
  void to_section(RodStateWithTangents& Y) const;

  /// dy/ds at (s, y).
  void derivative(double s, const RodStateVector& y, RodStateVector& dyds) const;
  /// dY/ds for the state (column 0) and its tangents (columns 1..6).
  void derivative(double s, const RodStateWithTangents& Y, RodStateWithTangents& dYds) const;

 private:
  void intrinsic_at(double s, Vec3& eps0, Vec3& kappa0) const;

  double length_ = 0.0;
  double load_factor_ = 1.0;
  Vec3 compliance_se_, compliance_bt_;  ///< diagonals of K_SE^-1, K_BT^-1
  Vec3 f_, l_;
  Vec3 eps0_, kappa0_;
  DrawnConstants drawn_;                             ///< effective constants (the model's own when not drawn)
  std::shared_ptr<const IntrinsicStrains> varying_;  ///< set only for s-dependent strains
  double force_scale_ = 1.0, moment_scale_ = 1.0, bending_force_scale_ = 1.0;
  RodStateVector state_scale_;
};

}  // namespace pcr
