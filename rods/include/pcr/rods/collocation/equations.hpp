#pragma once
// The Cosserat rod equations at one collocation point, written once for double and Dual<N> scalars
// (docs/design.md §1-2). Shared by pcr::rods and the robot couplings in pcr::robots.
//
// Frames: p, n, m, f, l in the world frame; strains eps, kappa and stiffness in the body frame.
// Orientation: R(q) = R_unit(q) / |q|^2 and the body curvature in quaternion form
//   kappa = 2 vec(conj(q) (x) q') / |q|^2          (R' = R hat(kappa); the |q| factor drops out)
//   kappa' = 2 vec(conj(q) (x) q'') / |q|^2 - 4 (q . q') vec(conj(q) (x) q') / |q|^4
// which equals vee(R^T R') = [<d2',d3>, <d3',d1>, <d1',d2>] (docs/design.md §1).
// Every residual is made dimensionless with the rod's reference scales (see PointConstants). Each
// kernel's local vector z is named once by its layout struct (layout.hpp), right above the kernel.
#include <Eigen/Core>

#include "pcr/core/types.hpp"
#include "pcr/rods/collocation/layout.hpp"

namespace pcr::collocation {

template <typename T>
using V3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using V4 = Eigen::Matrix<T, 4, 1>;
template <typename T>
using M3 = Eigen::Matrix<T, 3, 3>;

/// Constants of the equations at one point (material, intrinsic strains and their s-derivatives,
/// distributed loads already multiplied by the load factor) and the row scales. For a drawn rod
/// (drawn_rod.hpp) k_se, k_bt, eps0, kappa0 are the effective constants of (M4) and the unknowns n, m
/// of the equations are the effective N, M; flux_force and flux_moment convert them to the section's.
struct PointConstants {
  Vec3 k_se = Vec3::Ones(), k_bt = Vec3::Ones();
  Vec3 eps0 = Vec3::Zero(), kappa0 = Vec3::Zero();
  double flux_force = 0.0;          ///< drawn rods: rho A c^2 [N]
  Vec3 flux_moment = Vec3::Zero();  ///< drawn rods: diagonal of rho c^2 J_rho [N m^2]
  Vec3 eps0_s = Vec3::Zero(), kappa0_s = Vec3::Zero();
  Vec3 f = Vec3::Zero(), l = Vec3::Zero();  ///< distributed force and moment per length (world)
  double length_scale = 1.0;                ///< L0 [m]
  double force_scale = 1.0;                 ///< F0 = max(K_BT) / L0^2 [N]
  double moment_scale = 1.0;                ///< M0 = max(K_BT) / L0 [N m]
};

template <typename T>
M3<T> rotation(const V4<T>& q) {
  const T w = q[0], x = q[1], y = q[2], z = q[3];
  const T s = q.squaredNorm();
  M3<T> A;
  A << w * w + x * x - y * y - z * z, 2.0 * (x * y - w * z), 2.0 * (x * z + w * y),  //
      2.0 * (x * y + w * z), w * w - x * x + y * y - z * z, 2.0 * (y * z - w * x),   //
      2.0 * (x * z - w * y), 2.0 * (y * z + w * x), w * w - x * x - y * y + z * z;
  return A / s;
}

/// Vector part of conj(a) (x) b = a0 bv - b0 av - av x bv.
template <typename T>
V3<T> conj_product_vec(const V4<T>& a, const V4<T>& b) {
  const V3<T> av = a.template tail<3>(), bv = b.template tail<3>();
  return a[0] * bv - b[0] * av - av.cross(bv);
}

/// Hamilton product a (x) b (scalar first).
template <typename T>
V4<T> quat_product(const V4<T>& a, const V4<T>& b) {
  const V3<T> av = a.template tail<3>(), bv = b.template tail<3>();
  V4<T> r;
  r[0] = a[0] * b[0] - av.dot(bv);
  r.template tail<3>() = a[0] * bv + b[0] * av + av.cross(bv);
  return r;
}

/// Body curvature kappa from q and dq/ds.
template <typename T>
V3<T> body_curvature(const V4<T>& q, const V4<T>& q_s) {
  return conj_product_vec(q, q_s) * (2.0 / q.squaredNorm());
}

/// Primal form, interior point: force balance (3), moment balance (3), |q|^2 - 1 (1); u-derivatives,
/// s = L u.
struct PrimalInteriorZ {
  enum Entry { q, q_u, q_uu, p_u, p_uu, L, kEntries };
  static constexpr LocalLayout<kEntries> layout{{{{kPrimalPoint.q, 4, 0},
                                                  {kPrimalPoint.q, 4, 1},
                                                  {kPrimalPoint.q, 4, 2},
                                                  {kPrimalPoint.p, 3, 1},
                                                  {kPrimalPoint.p, 3, 2},
                                                  {kDirect, 1}}}};
};

template <typename T>
void primal_interior(const Eigen::Matrix<T, PrimalInteriorZ::layout.size(), 1>& z, const PointConstants& c,
                     T* r) {
  using Z = PrimalInteriorZ;
  const V4<T> q = get<Z, Z::q>(z);
  const T L = get<Z, Z::L>(z)[0];
  const V4<T> q_s = get<Z, Z::q_u>(z) / L;
  const V4<T> q_ss = get<Z, Z::q_uu>(z) / (L * L);
  const V3<T> p_s = get<Z, Z::p_u>(z) / L;
  const V3<T> p_ss = get<Z, Z::p_uu>(z) / (L * L);
  const T S = q.squaredNorm();
  const M3<T> R = rotation(q);
  const V3<T> w1 = conj_product_vec(q, q_s);
  const V3<T> kappa = w1 * (2.0 / S);
  const V3<T> kappa_s = conj_product_vec(q, q_ss) * (2.0 / S) - w1 * (4.0 * q.dot(q_s) / (S * S));
  const V3<T> v = R.transpose() * p_s;  // body-frame p'
  const V3<T> v_s = R.transpose() * p_ss - kappa.cross(v);
  V3<T> sigma, sigma_s, chi, chi_s;  // body-frame force and moment and their s-derivatives
  for (int i = 0; i < 3; ++i) {
    sigma[i] = c.k_se[i] * (v[i] - (i == 2 ? 1.0 : 0.0) - c.eps0[i]);
    sigma_s[i] = c.k_se[i] * (v_s[i] - c.eps0_s[i]);
    chi[i] = c.k_bt[i] * (kappa[i] - c.kappa0[i]);
    chi_s[i] = c.k_bt[i] * (kappa_s[i] - c.kappa0_s[i]);
  }
  // n = R sigma, n' = R (kappa x sigma + sigma');  m' likewise; equations n' + f = 0, m' + p' x n + l = 0.
  const V3<T> n = R * sigma;
  const V3<T> e_n = R * (kappa.cross(sigma) + sigma_s) + c.f;
  const V3<T> e_m = R * (kappa.cross(chi) + chi_s) + p_s.cross(n) + c.l;
  // Force rows in strain units (L / max K_SE): n' = R K_SE (...)' carries the round-off of p'' times
  // K_SE, which F0 scaling would magnify by K_SE / F0 (up to 1e8 for slender rods).
  const double fr = c.length_scale / c.k_se.maxCoeff(), mr = c.length_scale / c.moment_scale;
  for (int i = 0; i < 3; ++i) {
    r[i] = e_n[i] * fr;
    r[3 + i] = e_m[i] * mr;
  }
  r[6] = S - 1.0;
}

/// Constitutive equations (6) in compliance form, equivalent to n = R K_SE (eps - eps0) and
/// m = R K_BT (kappa - kappa0) but scaled as strains so that stiff axial/shear directions do not swamp
/// the residual:  K_SE^-1 R^T n - (eps - eps0) = 0,  L0 (K_BT^-1 R^T m - (kappa - kappa0)) = 0, with
/// eps = R^T p' - e3 and kappa from q, q' (s-derivatives).
template <typename T>
void constitutive_rows(const V4<T>& q, const V4<T>& q_s, const V3<T>& p_s, const V3<T>& n, const V3<T>& m,
                       const PointConstants& c, T* r) {
  const M3<T> R = rotation(q);
  const V3<T> sigma = R.transpose() * n;
  const V3<T> chi = R.transpose() * m;
  const V3<T> eps = R.transpose() * p_s;
  const V3<T> kappa = body_curvature(q, q_s);
  for (int i = 0; i < 3; ++i) {
    r[i] = sigma[i] / c.k_se[i] - (eps[i] - (i == 2 ? 1.0 : 0.0) - c.eps0[i]);
    r[3 + i] = (chi[i] / c.k_bt[i] - (kappa[i] - c.kappa0[i])) * c.length_scale;
  }
}

/// The mixed form at a point: the values and u-derivatives of q, p, n, m and the length.
struct MixedZ {
  enum Entry { q, q_u, p_u, n, n_u, m, m_u, L, kEntries };
  static constexpr LocalLayout<kEntries> layout{{{{kMixedPoint.q, 4, 0},
                                                  {kMixedPoint.q, 4, 1},
                                                  {kMixedPoint.p, 3, 1},
                                                  {kMixedPoint.n, 3, 0},
                                                  {kMixedPoint.n, 3, 1},
                                                  {kMixedPoint.m, 3, 0},
                                                  {kMixedPoint.m, 3, 1},
                                                  {kDirect, 1}}}};
};
template <typename T>
using MixedLocal = Eigen::Matrix<T, MixedZ::layout.size(), 1>;

/// Mixed form constitutive equations (constitutive_rows) at a point.
template <typename T>
void mixed_constitutive(const MixedLocal<T>& z, const PointConstants& c, T* r) {
  using Z = MixedZ;
  const T L = get<Z, Z::L>(z)[0];
  constitutive_rows<T>(get<Z, Z::q>(z), get<Z, Z::q_u>(z) / L, get<Z, Z::p_u>(z) / L, get<Z, Z::n>(z),
                       get<Z, Z::m>(z), c, r);
}

/// Mixed form field equations at a point: n' + f (3), m' + p' x n + l (3), then the two constitutive
/// equations (6).
template <typename T>
void mixed_field(const MixedLocal<T>& z, const PointConstants& c, T* r) {
  using Z = MixedZ;
  const T L = get<Z, Z::L>(z)[0];
  const V3<T> p_s = get<Z, Z::p_u>(z) / L;
  const V3<T> n = get<Z, Z::n>(z);
  const V3<T> n_s = get<Z, Z::n_u>(z) / L;
  const V3<T> m_s = get<Z, Z::m_u>(z) / L;
  const V3<T> e_n = n_s + c.f;
  const V3<T> e_m = m_s + p_s.cross(n) + c.l;
  const double fr = c.length_scale / c.force_scale, mr = c.length_scale / c.moment_scale;
  for (int i = 0; i < 3; ++i) {
    r[i] = e_n[i] * fr;
    r[3 + i] = e_m[i] * mr;
  }
  mixed_constitutive(z, c, r + 6);
}

/// Mixed form, interior Greville point of the Greville scheme (MixedPoints::Greville): the 12 field
/// equations, then |q|^2 - 1.
template <typename T>
void mixed_interior(const MixedLocal<T>& z, const PointConstants& c, T* r) {
  mixed_field(z, c, r);
  r[12] = get<MixedZ, MixedZ::q>(z).squaredNorm() - 1.0;
}

/// Condensed form (rods without distributed loads): n' = 0 and (m + (p - c) x n)' = m' + p' x n = 0, so
/// n(s) = n and m(s) = h - (p(s) - c) x n with two constant unknowns, the force n and the moment h
/// about a fixed point c (the wrench block [n, h]). Only the constitutive rows remain.
struct CondensedZ {
  enum Entry { q, q_u, p_u, p, wrench, L, kEntries };
  static constexpr LocalLayout<kEntries> layout{{{{kCondensedPoint.q, 4, 0},
                                                  {kCondensedPoint.q, 4, 1},
                                                  {kCondensedPoint.p, 3, 1},
                                                  {kCondensedPoint.p, 3, 0},
                                                  {kDirect, kWrenchSize},
                                                  {kDirect, 1}}}};
};

template <typename T>
void condensed_field(const Eigen::Matrix<T, CondensedZ::layout.size(), 1>& z, const PointConstants& c,
                     const Vec3& moment_point, T* r) {
  using Z = CondensedZ;
  const T L = get<Z, Z::L>(z)[0];
  const V3<T> n = get<Z, Z::wrench>(z).template head<3>();
  const V3<T> arm = get<Z, Z::p>(z) - moment_point.cast<T>();
  const V3<T> m = get<Z, Z::wrench>(z).template tail<3>() - arm.cross(n);
  constitutive_rows<T>(get<Z, Z::q>(z), get<Z, Z::q_u>(z) / L, get<Z, Z::p_u>(z) / L, n, m, c, r);
}

/// Condensed form with constant distributed loads f, l (world frame; PointConstants): n' = -f and
/// (m + (p - c) x n)' = -l - (p - c) x f integrate to n(s) = n - f s and
/// m(s) = h - (p(s) - c) x n(s) - l s - A(s) x f,  A(s) = integral_0^s (p - c) dt = L (I(u) - c u),
/// with I(u) = integral_0^u p du'. s = u L at the point's u.
template <typename T>
V3<T> condensed_moment(const V3<T>& p, const V3<T>& n_s, const V3<T>& h, const T& L, const V3<T>& I,
                       const PointConstants& c, const Vec3& moment_point, double u) {
  const V3<T> cp = moment_point.cast<T>();
  const V3<T> A = (I - cp * u) * L;
  return h - (p - cp).cross(n_s) - c.l.cast<T>() * (u * L) - A.cross(c.f.cast<T>());
}

/// The condensed form with loads at a point: as CondensedZ, and I(u) = T_k + sum_i J_i(u) P_i in two
/// parts (collocation_rod.hpp): T_k of the first control point k active at u (the integral carried by
/// the basis functions before it) and the integrals J_i(u) = integral_0^u N_i of the active ones.
struct CondensedLoadedZ {
  enum Entry { q, q_u, p_u, p, wrench, L, T_first, I_active, kEntries };
  static constexpr LocalLayout<kEntries> layout{{{{kCondensedLoadedPoint.q, 4, 0},
                                                  {kCondensedLoadedPoint.q, 4, 1},
                                                  {kCondensedLoadedPoint.p, 3, 1},
                                                  {kCondensedLoadedPoint.p, 3, 0},
                                                  {kDirect, kWrenchSize},
                                                  {kDirect, 1},
                                                  {kCondensedLoadedPoint.integral, 3, kSelected},
                                                  {kCondensedLoadedPoint.p, 3, kIntegral}}}};
};

/// n(s) = n - f s and m(s) (condensed_moment) at u from a local vector with the entries p, wrench, L of Z
/// and the integral I(u) (which the condensed forms with loads hold in different ways).
template <typename Z, typename T, typename Local>
void condensed_wrench_from_integral(const Local& z, const V3<T>& I, const PointConstants& c,
                                    const Vec3& moment_point, double u, V3<T>& n, V3<T>& m) {
  const T L = get<Z, Z::L>(z)[0];
  n = get<Z, Z::wrench>(z).template head<3>() - c.f.cast<T>() * (u * L);
  m = condensed_moment<T>(get<Z, Z::p>(z), n, get<Z, Z::wrench>(z).template tail<3>(), L, I, c, moment_point,
                          u);
}

/// n(s), m(s) of the condensed form with loads at u from its local vector (Z: CondensedLoadedZ or the
/// tip's CondensedLoadedTipZ, which name the same quantities): I(u) = T_first + I_active.
template <typename Z, typename T, typename Local>
void condensed_loaded_wrench(const Local& z, const PointConstants& c, const Vec3& moment_point, double u,
                             V3<T>& n, V3<T>& m) {
  const V3<T> I = get<Z, Z::T_first>(z) + get<Z, Z::I_active>(z);
  condensed_wrench_from_integral<Z, T>(z, I, c, moment_point, u, n, m);
}

/// Primal form: internal force and moment at a point from the constitutive law, from q and the
/// u-derivatives q_u, p_u (world frame).
template <typename T>
void primal_wrench(const V4<T>& q, const V4<T>& q_u, const V3<T>& p_u, const T& L, const PointConstants& c,
                   V3<T>& n, V3<T>& m) {
  const V4<T> q_s = q_u / L;
  const V3<T> p_s = p_u / L;
  const M3<T> R = rotation(q);
  const V3<T> v = R.transpose() * p_s;
  const V3<T> kappa = body_curvature(q, q_s);
  V3<T> sigma, chi;
  for (int i = 0; i < 3; ++i) {
    sigma[i] = c.k_se[i] * (v[i] - (i == 2 ? 1.0 : 0.0) - c.eps0[i]);
    chi[i] = c.k_bt[i] * (kappa[i] - c.kappa0[i]);
  }
  n = R * sigma;
  m = R * chi;
}

}  // namespace pcr::collocation
