// Segment stiffness of the rod's second variation from the transfer matrix of its Jacobi equations
// (held_rod.hpp, docs/design.md §4). Linearising the equilibrium n' + f = 0, m' + p' x n = 0 with the
// constitutive law about the state (R, n, m, p'), for dead loads (df = 0, no distributed couple), in the
// variables z = (dp, dth, dn, dm) (world; dR = hat(dth) R):
//   dp'  = -[p']x dth + C_se (dn + [n]x dth),   C_se = R K_SE^-1 R^T
//   dth' =  C_bt (dm + [m]x dth),               C_bt = R K_BT^-1 R^T
//   dn'  =  0
//   dm'  =  [n]x dp' - [p']x dn
// (the variational equations of the shooting ODE, rod_ode.hpp, with the body rotation omega = R^T dth).
// These are the Euler-Lagrange equations of the second variation
//   Q = a^T K_s a + dth'^T K_b dth' - 2 n . (dth x dp') + n . (dth x (dth x p')) - m . (dth x dth'),
//   a = dp' - dth x p',  K_s = R K_SE R^T,  K_b = R K_BT R^T,
// whose momenta are pi_p = dn and pi_th = dm + 1/2 [m]x dth: in (x, pi) = ((dp, dth), pi) the system is
// Hamiltonian and its transfer matrix Phi symplectic (Phi^T J Phi = J), which makes the stiffness below
// symmetric; in the raw variables it is not (the 1/2 [m]x dth term is essential wherever m != 0).
#include <cmath>

#include "pcr/math/so3.hpp"
#include "pcr/rods/stability/held_rod.hpp"

namespace pcr::stability {

namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;

/// The dimensionless coefficients: z~ = (dp / L, dth, dn / F, dm / M) over t = s / L, M = max(K_BT) / L,
/// F = M / L. Then A~ = L S^-1 A S has the form of A with n / F, m / M, F K_SE^-1 and L M K_BT^-1.
struct Scaled {
  explicit Scaled(const HeldRod& rod)
      : length(rod.length),
        moment(rod.bending_torsion_stiffness.maxCoeff() / rod.length),
        force(moment / rod.length),
        shear_compliance(force * rod.shear_extension_stiffness.cwiseInverse()),
        bending_compliance(length * moment * rod.bending_torsion_stiffness.cwiseInverse()) {}
  double length, moment, force;
  Vec3 shear_compliance, bending_compliance;
};

/// A~(s) of z~' = A~ z~ (rows and columns dp, dth, dn, dm) by its six non-zero 3 x 3 blocks:
///   A = [0 A_pth Cse 0; 0 Cbt [m]x 0 Cbt; 0 0 0 0; 0 [n]x A_pth [n]x Cse - [p']x 0].
struct JacobiMatrix {
  Mat3 p_th, p_n, th_th, th_m, m_th, m_n;
  /// A~ Z for a 12 x 12 Z whose dn rows are [0 0 I 0] (those of the transfer matrix Phi and of its RK4
  /// stages: dn' = 0), using that and the zero blocks (a quarter of the dense product's multiplications).
  Mat12 times_transfer(const Mat12& Z) const {
    Mat12 out;
    out.middleRows<3>(0).noalias() = p_th * Z.middleRows<3>(3);
    out.block<3, 3>(0, 6) += p_n;
    out.middleRows<3>(3).noalias() = th_th * Z.middleRows<3>(3) + th_m * Z.middleRows<3>(9);
    out.middleRows<3>(6).setZero();
    out.middleRows<3>(9).noalias() = m_th * Z.middleRows<3>(3);
    out.block<3, 3>(9, 6) += m_n;
    return out;
  }
};

JacobiMatrix jacobi_matrix(const JacobiState& y, const Scaled& c) {
  const Mat3& R = y.rotation;
  const Mat3 Cse = R * c.shear_compliance.asDiagonal() * R.transpose();
  const Mat3 Cbt = R * c.bending_compliance.asDiagonal() * R.transpose();
  const Mat3 n = hat(y.force / c.force), m = hat(y.moment / c.moment), t = hat(y.tangent);
  JacobiMatrix A;
  A.p_th = -t + Cse * n;
  A.p_n = Cse;
  A.th_th = Cbt * m;
  A.th_m = Cbt;
  A.m_th = n * A.p_th;
  A.m_n = n * Cse - t;
  return A;
}

/// T(s) = [[I6, 0], [Mm, I6]], Mm = 1/2 [m~]x in the (pi_th, dth) block: z_canonical = T z. This returns
/// the block 1/2 [m~]x (T^-1 has -1/2 [m~]x there).
Mat3 canonical_block(const JacobiState& y, const Scaled& c) {
  return 0.5 * hat(y.moment / c.moment);
}

/// Relative asymmetry of K in its diagonal scaling: max |K~_ij - K~_ji| with K~ = D K D,
/// D = diag(|K_ii|)^-1/2 (the entries of K span many decades: axial against bending).
double scaled_asymmetry(const Mat12& K) {
  Eigen::Matrix<double, 12, 1> d;
  for (int i = 0; i < 12; ++i) d[i] = std::abs(K(i, i)) > 0.0 ? 1.0 / std::sqrt(std::abs(K(i, i))) : 1.0;
  const Mat12 Ks = d.asDiagonal() * K * d.asDiagonal();
  return (Ks - Ks.transpose()).cwiseAbs().maxCoeff();
}

}  // namespace

bool segment_stiffness(const HeldRod& rod, const JacobiStateAt& state, double s_a, double s_b, int substeps,
                       Mat12& stiffness, double& asymmetry) {
  const Scaled c(rod);
  const double h = (s_b - s_a) / substeps, dt = h / c.length;
  const JacobiState y_a = state(s_a);
  Mat12 Phi = Mat12::Identity();
  JacobiMatrix A0 = jacobi_matrix(y_a, c);
  JacobiState y_b = y_a;
  for (int k = 0; k < substeps; ++k) {  // classical RK4 on Phi' = A Phi
    const double s = s_a + k * h;
    const JacobiMatrix A1 = jacobi_matrix(state(s + 0.5 * h), c);
    y_b = state(k + 1 == substeps ? s_b : s + h);
    const JacobiMatrix A2 = jacobi_matrix(y_b, c);
    const Mat12 k1 = A0.times_transfer(Phi);
    const Mat12 k2 = A1.times_transfer(Phi + 0.5 * dt * k1);
    const Mat12 k3 = A1.times_transfer(Phi + 0.5 * dt * k2);
    const Mat12 k4 = A2.times_transfer(Phi + dt * k3);
    Phi += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    A0 = A2;
    // X(s) = dx(s) / dpi(s_a) starts as (s - s_a) diag(C_se, C_bt) (det > 0) and is singular exactly at
    // a conjugate point of s_a: the segment must not reach one.
    if (!(Phi.block<6, 6>(0, 6).determinant() > 0.0)) return false;
  }
  // Canonical transfer matrix P = T(s_b) Phi T(s_a)^-1 by its two non-identity blocks (canonical_block);
  // its dx/dpi block is Phi's.
  Mat12 P = Phi;
  P.middleRows<3>(9).noalias() += canonical_block(y_b, c) * Phi.middleRows<3>(3);
  P.middleCols<3>(3).noalias() -= P.middleCols<3>(9) * canonical_block(y_a, c);
  const Mat6 Xi = P.block<6, 6>(0, 6).inverse();  // by partial-pivoting LU (fixed size 6)
  const Mat6 Xi_xx = Xi * P.block<6, 6>(0, 0);    // X^-1 P_xx
  // (-pi_a, pi_b) = K (x_a, x_b): pi_a = X^-1 (x_b - P_xx x_a), pi_b = P_pix x_a + P_pipi pi_a.
  Mat12 K;
  K.block<6, 6>(0, 0) = Xi_xx;
  K.block<6, 6>(0, 6) = -Xi;
  K.block<6, 6>(6, 0) = P.block<6, 6>(6, 0) - P.block<6, 6>(6, 6) * Xi_xx;
  K.block<6, 6>(6, 6) = P.block<6, 6>(6, 6) * Xi;
  if (!K.allFinite()) return false;
  asymmetry = scaled_asymmetry(K);
  stiffness = 0.5 * (K + K.transpose());
  return true;
}

}  // namespace pcr::stability
