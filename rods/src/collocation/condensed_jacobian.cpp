// The condensed field rows (equations.hpp: constitutive_rows with n, m = h - (p - c) x n) and their
// derivatives in closed form. With S = |q|^2, q = [w, v], R = R_unit(q) / S and
//   R_unit^T u = (w^2 - |v|^2) u + 2 v (v . u) - 2 w v x u,
//   kappa = 2 vec(conj(q) (x) q_s) / S,   vec(conj(a) (x) b) = a0 bv - b0 av - av x bv,
// the rows are  r_f = K_SE^-1 R^T n - (R^T p_s - e3 - eps0),  r_m = L0 (K_BT^-1 R^T m - (kappa - kappa0)),
// with p_s = p_u / L, q_s = q_u / L.
#include "condensed_jacobian.hpp"

#include "pcr/math/so3.hpp"

namespace pcr::collocation {
namespace {

using Mat34 = Eigen::Matrix<double, 3, 4>;
using Vec4 = Eigen::Vector4d;

// R^T u and its derivative with respect to q (3 x 4): d(g / S) = dg / S - (g / S) 2 q^T / S.
void rotate_back(const Vec4& q, double S, const Vec3& u, Vec3& out, Mat34& d) {
  const double w = q[0];
  const Vec3 v = q.tail<3>();
  const Vec3 g = (w * w - v.squaredNorm()) * u + 2.0 * v * v.dot(u) - 2.0 * w * v.cross(u);
  Mat34 dg;
  dg.col(0) = 2.0 * w * u - 2.0 * v.cross(u);
  dg.rightCols<3>() =
      2.0 * (v * u.transpose() - u * v.transpose() + v.dot(u) * Mat3::Identity()) + 2.0 * w * hat(u);
  out = g / S;
  d = dg / S - out * (2.0 / S) * q.transpose();
}

}  // namespace

void condensed_field_jacobian(const Eigen::Matrix<double, kCondensedLocal, 1>& z, const PointConstants& c,
                              const Vec3& moment_point, double* r, double* J) {
  using Z = CondensedZ;
  constexpr int nq = Z::layout.offset(Z::q), nq_u = Z::layout.offset(Z::q_u), np_u = Z::layout.offset(Z::p_u),
                np = Z::layout.offset(Z::p), nw = Z::layout.offset(Z::wrench), nL = Z::layout.offset(Z::L);
  Eigen::Map<Eigen::Matrix<double, 6, kCondensedLocal, Eigen::RowMajor>> D(J);
  D.setZero();
  const Eigen::Vector4d q = get<Z, Z::q>(z);
  const double L = get<Z, Z::L>(z)[0], S = q.squaredNorm();
  const Eigen::Vector4d q_s = get<Z, Z::q_u>(z) / L;
  const Vec3 p_s = get<Z, Z::p_u>(z) / L;
  const Vec3 n = get<Z, Z::wrench>(z).head<3>();
  const Vec3 arm = get<Z, Z::p>(z) - moment_point;
  const Vec3 m = get<Z, Z::wrench>(z).tail<3>() - arm.cross(n);
  const Mat3 Rt = rotation<double>(q).transpose();
  Vec3 sigma, chi, eps;
  Mat34 dsigma, dchi, deps;
  rotate_back(q, S, n, sigma, dsigma);
  rotate_back(q, S, m, chi, dchi);
  rotate_back(q, S, p_s, eps, deps);
  // kappa = 2 cv / S with cv = vec(conj(q) (x) q_s): dcv/dq = [q_s,v  -q_s,0 I + hat(q_s,v)],
  // dcv/dq_s = [-v  q0 I - hat(v)].
  const Vec3 v = q.tail<3>(), vs = q_s.tail<3>();
  const Vec3 kappa = conj_product_vec<double>(q, q_s) * (2.0 / S);
  Mat34 dcv_dq, dcv_dqs;
  dcv_dq.col(0) = vs;
  dcv_dq.rightCols<3>() = -q_s[0] * Mat3::Identity() + hat(vs);
  dcv_dqs.col(0) = -v;
  dcv_dqs.rightCols<3>() = q[0] * Mat3::Identity() - hat(v);
  const Mat34 dkappa_dq = dcv_dq * (2.0 / S) - kappa * (2.0 / S) * q.transpose();
  const Mat34 dkappa_dqu = dcv_dqs * (2.0 / (S * L));
  const Vec3 ise = c.k_se.cwiseInverse(), ibt = c.k_bt.cwiseInverse();
  const double L0 = c.length_scale;
  for (int i = 0; i < 3; ++i) {
    r[i] = sigma[i] * ise[i] - (eps[i] - (i == 2 ? 1.0 : 0.0) - c.eps0[i]);
    r[3 + i] = (chi[i] * ibt[i] - (kappa[i] - c.kappa0[i])) * L0;
  }
  // Force rows: sigma / K_SE - eps.
  D.block<3, 4>(0, nq) = ise.asDiagonal() * dsigma - deps;
  D.block<3, 3>(0, np_u) = -Rt / L;
  D.block<3, 3>(0, nw) = ise.asDiagonal() * Rt;
  D.block<3, 1>(0, nL) = eps / L;
  // Moment rows: L0 (chi / K_BT - kappa), chi = R^T m, dm/dh = I, dm/dn = -hat(arm), dm/dp = hat(n).
  const Mat3 C = L0 * (ibt.asDiagonal() * Rt);
  D.block<3, 4>(3, nq) = L0 * (ibt.asDiagonal() * dchi - dkappa_dq);
  D.block<3, 4>(3, nq_u) = -L0 * dkappa_dqu;
  D.block<3, 3>(3, np) = C * hat(n);
  D.block<3, 3>(3, nw) = -C * hat(arm);
  D.block<3, 3>(3, nw + 3) = C;
  D.block<3, 1>(3, nL) = L0 * kappa / L;
}

}  // namespace pcr::collocation
