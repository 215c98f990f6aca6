// The condensed field rows (equations.hpp: constitutive_rows with n, m = h - (p - c) x n) and their
// derivatives in closed form. With S = |q|^2, q = [w, v], R = R_unit(q) / S and
//   R_unit^T u = (w^2 - |v|^2) u + 2 v (v . u) - 2 w v x u,
//   kappa = 2 vec(conj(q) (x) q_s) / S,   vec(conj(a) (x) b) = a0 bv - b0 av - av x bv,
// the rows are  r_f = K_SE^-1 R^T n - (R^T p_s - e3 - eps0),  r_m = L0 (K_BT^-1 R^T m - (kappa - kappa0)),
// with p_s = p_u / L, q_s = q_u / L. With distributed loads (condensed_forms.cpp) n and m are those at
// s = u L: n(s) = n - f s, m(s) = h - (p - c) x n(s) - l s - L (I - c u) x f, so besides the rows'
// own dependence on q, q_u, p_u, L (at fixed n, m) they read
//   dn(s)/dn = I, dn(s)/dL = -f u,
//   dm(s)/dh = I, dm(s)/dn = -hat(p - c), dm(s)/dp = hat(n(s)), dm(s)/dI = L hat(f),
//   dm(s)/dL = u hat(p - c) f - l u + hat(f) (I - c u).
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

// The rows at q, q_u, p_u, L with the internal force n and moment m given, and their derivatives: the
// columns of q, q_u, p_u and L of D (at fixed n, m; offsets of Z, whose first entries are those of
// CondensedZ); dr/dn = [K_SE^-1 R^T; 0] and dr/dm = [0; C] with C = L0 K_BT^-1 R^T are returned as Rt
// (R^T) and C for the caller's chain rule.
template <typename Z, int NL>
void constitutive_jacobian(const Eigen::Matrix<double, NL, 1>& z, const Vec3& n, const Vec3& m,
                           const PointConstants& c, double* r,
                           Eigen::Map<Eigen::Matrix<double, 6, NL, Eigen::RowMajor>>& D, Mat3& Rt, Mat3& C) {
  constexpr int nq = Z::layout.offset(Z::q), nq_u = Z::layout.offset(Z::q_u), np_u = Z::layout.offset(Z::p_u),
                nL = Z::layout.offset(Z::L);
  const Eigen::Vector4d q = get<Z, Z::q>(z);
  const double L = get<Z, Z::L>(z)[0], S = q.squaredNorm();
  const Eigen::Vector4d q_s = get<Z, Z::q_u>(z) / L;
  const Vec3 p_s = get<Z, Z::p_u>(z) / L;
  Rt = rotation<double>(q).transpose();
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
  D.template block<3, 4>(0, nq) = ise.asDiagonal() * dsigma - deps;
  D.template block<3, 3>(0, np_u) = -Rt / L;
  D.template block<3, 1>(0, nL) = eps / L;
  // Moment rows: L0 (chi / K_BT - kappa), chi = R^T m.
  C = L0 * (ibt.asDiagonal() * Rt);
  D.template block<3, 4>(3, nq) = L0 * (ibt.asDiagonal() * dchi - dkappa_dq);
  D.template block<3, 4>(3, nq_u) = -L0 * dkappa_dqu;
  D.template block<3, 1>(3, nL) = L0 * kappa / L;
  D.template block<3, 3>(0, Z::layout.offset(Z::wrench)) = ise.asDiagonal() * Rt;
}

}  // namespace

void condensed_field_jacobian(const Eigen::Matrix<double, kCondensedLocal, 1>& z, const PointConstants& c,
                              const Vec3& moment_point, double* r, double* J) {
  using Z = CondensedZ;
  constexpr int np = Z::layout.offset(Z::p), nw = Z::layout.offset(Z::wrench);
  Eigen::Map<Eigen::Matrix<double, 6, kCondensedLocal, Eigen::RowMajor>> D(J);
  D.setZero();
  const Vec3 n = get<Z, Z::wrench>(z).head<3>();
  const Vec3 arm = get<Z, Z::p>(z) - moment_point;
  const Vec3 m = get<Z, Z::wrench>(z).tail<3>() - arm.cross(n);
  Mat3 Rt, C;
  constitutive_jacobian<Z>(z, n, m, c, r, D, Rt, C);
  // dm/dh = I, dm/dn = -hat(arm), dm/dp = hat(n).
  D.block<3, 3>(3, np) = C * hat(n);
  D.block<3, 3>(3, nw) = -C * hat(arm);
  D.block<3, 3>(3, nw + 3) = C;
}

void condensed_loaded_field_jacobian(const Eigen::Matrix<double, kCondensedSummedLocal, 1>& z,
                                     const PointConstants& c, const Vec3& moment_point, double u, double* r,
                                     double* J) {
  using Z = CondensedSummedZ;
  constexpr int np = Z::layout.offset(Z::p), nw = Z::layout.offset(Z::wrench), nL = Z::layout.offset(Z::L),
                nI = Z::layout.offset(Z::I);
  Eigen::Map<Eigen::Matrix<double, 6, kCondensedSummedLocal, Eigen::RowMajor>> D(J);
  D.setZero();
  const double L = get<Z, Z::L>(z)[0];
  const Vec3 I = get<Z, Z::I>(z);
  Vec3 n, m;
  condensed_wrench_from_integral<Z, double>(z, I, c, moment_point, u, n, m);
  const Vec3 arm = get<Z, Z::p>(z) - moment_point;
  Mat3 Rt, C;
  constitutive_jacobian<Z>(z, n, m, c, r, D, Rt, C);
  D.block<3, 3>(3, np) = C * hat(n);
  D.block<3, 3>(3, nw) = -C * hat(arm);
  D.block<3, 3>(3, nw + 3) = C;
  D.block<3, 3>(3, nI) = L * (C * hat(c.f));
  const Vec3 dn_dL = -c.f * u;
  const Vec3 dm_dL = u * arm.cross(c.f) - c.l * u + c.f.cross(I - moment_point * u);
  D.block<3, 1>(0, nL) += c.k_se.cwiseInverse().asDiagonal() * (Rt * dn_dL);
  D.block<3, 1>(3, nL) += C * dm_dL;
}

}  // namespace pcr::collocation
