#pragma once
// Rods in steady axial motion ("drawn rods", docs/design.md §1 "Drawn rods"; O. M. O'Reilly, "On steady
// motions of an elastic rod with application to contact problems", 1997, §3-4). The material moves
// along a fixed shape p(s), R(s) at c reference lengths per second, so v = c p' and the body angular
// velocity is c kappa. The balance laws gain the momentum fluxes rho A c^2 p' and rho c^2 R J_rho kappa;
// with the effective force and moment
//   N = n - rho A c^2 p',   M = m - rho c^2 R J_rho kappa                       (M3)
// they are the static ones, N' + f = 0, M' + p' x N + l = 0, and the constitutive law keeps its form
//   R^T N = K_SE,eff (eps - eps0_eff),  R^T M = K_BT,eff (kappa - kappa0_eff)     (M4)
// with K_SE,eff = K_SE - rho A c^2 I, eps0_eff = K_SE,eff^-1 (K_SE eps0 + rho A c^2 e3),
// K_BT,eff = K_BT - rho c^2 J_rho, kappa0_eff = K_BT,eff^-1 K_BT kappa0. J_rho = diag(I1, I2, I1 + I2)
// (second moments of area, not the torsion constant), from the section data of a homogeneous section:
// rho I_i = (rho A) (E I_i) / (E A). The solvers use (N, M) as unknowns and report (n, m).
#include "pcr/core/types.hpp"
#include "pcr/rods/rod_model.hpp"

namespace pcr {

/// The effective constitutive constants of a rod (the model's own when it is not drawn).
struct DrawnConstants {
  double flux_force = 0.0;          ///< rho A c^2 [N]
  Vec3 flux_moment = Vec3::Zero();  ///< diagonal of rho c^2 J_rho [N m^2]
  Vec3 k_se = Vec3::Ones();         ///< diagonal of K_SE,eff [N]
  Vec3 k_bt = Vec3::Ones();         ///< diagonal of K_BT,eff [N m^2]
  Vec3 eps0 = Vec3::Zero();         ///< eps0_eff
  Vec3 kappa0 = Vec3::Zero();       ///< kappa0_eff [1/m]
  bool drawn() const { return flux_force != 0.0 || !flux_moment.isZero(0.0); }
};

/// rho A c^2 and rho c^2 diag(J_rho) of the model (zero when c = 0 or the rod is massless).
void drawn_flux(const RodModel& model, double& flux_force, Vec3& flux_moment);

/// The effective constants (M4) for intrinsic strains eps0, kappa0 (already scaled by any load factor).
DrawnConstants drawn_constants(const RodModel& model, const Vec3& eps0, const Vec3& kappa0);

/// Overwrites k_se, k_bt, eps0, kappa0 with their effective values (M4) for the fluxes given; nothing
/// changes when both fluxes are zero.
void apply_drawn_constants(double flux_force, const Vec3& flux_moment, Vec3& k_se, Vec3& k_bt, Vec3& eps0,
                           Vec3& kappa0);

/// The section force and moment n, m from the effective N, M at a section with frame R (world frame):
/// n = N + rho A c^2 p', m = M + rho c^2 R J_rho kappa, with p' = R (e3 + eps), eps and kappa from the
/// effective constitutive law (M4) with the effective constants given. Scalar type T: double or Dual.
template <typename T, typename Mat, typename Vec>
void section_from_effective(const Mat& R, const Vec& N, const Vec& M, double flux_force,
                            const Vec3& flux_moment, const Vec3& k_se, const Vec3& k_bt, const Vec3& eps0,
                            const Vec3& kappa0, Vec& n, Vec& m) {
  const Vec sigma = R.transpose() * N, chi = R.transpose() * M;
  Vec stretch, flux;  // body frame: e3 + eps, and rho c^2 J_rho kappa
  for (int i = 0; i < 3; ++i) {
    stretch[i] = sigma[i] / k_se[i] + eps0[i] + (i == 2 ? 1.0 : 0.0);
    flux[i] = flux_moment[i] * (chi[i] / k_bt[i] + kappa0[i]);
  }
  n = N + R * (stretch * flux_force);
  m = M + R * flux;
}

/// section_from_effective with the constants of d (double).
void section_wrench(const DrawnConstants& d, const Mat3& R, const Vec3& N, const Vec3& M, Vec3& n, Vec3& m);
/// The inverse: N, M from the section force and moment n, m at a section with frame R.
void effective_wrench(const DrawnConstants& d, const Mat3& R, const Vec3& n, const Vec3& m, Vec3& N, Vec3& M);

}  // namespace pcr
