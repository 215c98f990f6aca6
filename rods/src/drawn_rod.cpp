#include "pcr/rods/drawn_rod.hpp"

namespace pcr {

void drawn_flux(const RodModel& model, double& flux_force, Vec3& flux_moment) {
  const double c2 = model.drawing_speed * model.drawing_speed;
  flux_force = model.mass_per_length * c2;
  // rho I_i = (rho A) (E I_i) / (E A) for a homogeneous section; J_rho = diag(I1, I2, I1 + I2).
  const Vec3& k_bt = model.bending_torsion_stiffness;
  const double EA = model.shear_extension_stiffness[2];
  const double rho_c2_over_E = EA > 0.0 ? flux_force / EA : 0.0;
  flux_moment = rho_c2_over_E * Vec3(k_bt[0], k_bt[1], k_bt[0] + k_bt[1]);
}

void apply_drawn_constants(double flux_force, const Vec3& flux_moment, Vec3& k_se, Vec3& k_bt, Vec3& eps0,
                           Vec3& kappa0) {
  if (flux_force == 0.0 && flux_moment.isZero(0.0)) return;
  const Vec3 k_se_eff = k_se - Vec3::Constant(flux_force);
  const Vec3 k_bt_eff = k_bt - flux_moment;
  eps0 = (k_se.cwiseProduct(eps0) + flux_force * Vec3::UnitZ()).cwiseQuotient(k_se_eff);
  kappa0 = k_bt.cwiseProduct(kappa0).cwiseQuotient(k_bt_eff);
  k_se = k_se_eff;
  k_bt = k_bt_eff;
}

DrawnConstants drawn_constants(const RodModel& model, const Vec3& eps0, const Vec3& kappa0) {
  DrawnConstants d;
  drawn_flux(model, d.flux_force, d.flux_moment);
  d.k_se = model.shear_extension_stiffness;
  d.k_bt = model.bending_torsion_stiffness;
  d.eps0 = eps0;
  d.kappa0 = kappa0;
  apply_drawn_constants(d.flux_force, d.flux_moment, d.k_se, d.k_bt, d.eps0, d.kappa0);
  return d;
}

void section_wrench(const DrawnConstants& d, const Mat3& R, const Vec3& N, const Vec3& M, Vec3& n, Vec3& m) {
  section_from_effective<double>(R, N, M, d.flux_force, d.flux_moment, d.k_se, d.k_bt, d.eps0, d.kappa0, n,
                                 m);
}

void effective_wrench(const DrawnConstants& d, const Mat3& R, const Vec3& n, const Vec3& m, Vec3& N,
                      Vec3& M) {
  // Body frame: R^T n = sigma + a (K_eff^-1 sigma + eps0_eff + e3), a = rho A c^2, so
  // sigma_i = ((R^T n)_i - a (eps0_eff + e3)_i) k_i / (k_i + a); likewise chi from R^T m.
  const Vec3 n_body = R.transpose() * n, m_body = R.transpose() * m;
  const double a = d.flux_force;
  Vec3 sigma, chi;
  for (int i = 0; i < 3; ++i) {
    sigma[i] = (n_body[i] - a * (d.eps0[i] + (i == 2 ? 1.0 : 0.0))) * d.k_se[i] / (d.k_se[i] + a);
    chi[i] = (m_body[i] - d.flux_moment[i] * d.kappa0[i]) * d.k_bt[i] / (d.k_bt[i] + d.flux_moment[i]);
  }
  N = R * sigma;
  M = R * chi;
}

}  // namespace pcr
