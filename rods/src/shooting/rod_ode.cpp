#include "pcr/rods/shooting/rod_ode.hpp"

#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"

#include <algorithm>

namespace pcr {
namespace {

// a (x) [0, u] for a quaternion a and a vector u (Hamilton product with a pure quaternion).
Quat multiply_pure(const Quat& a, const Vec3& u) {
  const Vec3 av = a.tail<3>();
  Quat r;
  r[0] = -av.dot(u);
  r.tail<3>() = a[0] * u + av.cross(u);
  return r;
}

// R(q) = R_unit(q) / |q|^2 without the input check (q is never zero along a solution).
Mat3 rotation_of(const Quat& q) {
  return rotation_unit_form(q) / q.squaredNorm();
}

}  // namespace

Mat3 ShootingState::R() const {
  return rotation_matrix(q);
}

RodStateVector ShootingState::to_vector() const {
  RodStateVector y;
  y << p, q, n, m;
  return y;
}

ShootingState ShootingState::from_vector(const RodStateVector& y) {
  ShootingState x;
  x.p = y.segment<3>(RodStateIndex::p);
  x.q = y.segment<4>(RodStateIndex::q);
  x.n = y.segment<3>(RodStateIndex::n);
  x.m = y.segment<3>(RodStateIndex::m);
  return x;
}

RodOde::RodOde(const RodModel& model, double load_factor) {
  model.validate();
  length_ = model.length;
  load_factor_ = load_factor;
  // Drawn rods: the effective constants (M4); the model's own otherwise (drawn_rod.hpp). s-varying
  // intrinsic strains (varying_) only occur at c = 0 (RodModel::validate).
  drawn_ = drawn_constants(model, model.intrinsic.shear_extension, model.intrinsic.curvature);
  compliance_se_ = drawn_.k_se.cwiseInverse();
  compliance_bt_ = drawn_.k_bt.cwiseInverse();
  f_ = load_factor * model.distributed_force();
  l_ = load_factor * model.loads.moment_per_length;
  eps0_ = drawn_.eps0;
  kappa0_ = drawn_.kappa0;
  if (model.intrinsic.varying) varying_ = std::make_shared<IntrinsicStrains>(model.intrinsic);
  // Characteristic force and moment: the bending scale EI/L^2, EI/L, or the applied loads if larger
  // (then round-off in n and m grows with the loads, and tolerances must follow).
  const double bending = model.bending_torsion_stiffness.maxCoeff() / (length_ * length_);
  const double forces = model.base.force.norm() + model.tip.force.norm() + f_.norm() * length_;
  const double moments = model.base.moment.norm() + model.tip.moment.norm() + l_.norm() * length_;
  bending_force_scale_ = bending;
  force_scale_ = std::max(bending, load_factor * forces);
  moment_scale_ = std::max(bending * length_, load_factor * moments + force_scale_ * length_);
  state_scale_ << Vec3::Constant(length_), Quat::Ones(), Vec3::Constant(force_scale_),
      Vec3::Constant(moment_scale_);
}

namespace {

using Block36 = Eigen::Matrix<double, 3, kRodTangentCount>;

// x -> R (A R^T x + b) for a diagonal A and a body-frame vector b, with the tangents
// d = R (omega x (A R^T x + b) + A (R^T dx - omega x R^T x)) for dR = R hat(omega) (columns).
void body_affine(const Mat3& R, const Vec3& A, const Vec3& b, const Block36* omega, Eigen::Ref<Vec3> x,
                 Eigen::Ref<Block36> dx) {
  const Vec3 x_body = R.transpose() * x;
  const Vec3 y_body = A.cwiseProduct(x_body) + b;
  if (omega) dx = R * (-hat(y_body) * *omega + A.asDiagonal() * (R.transpose() * dx + hat(x_body) * *omega));
  x = R * y_body;
}

// The section's n, m from N, M (to_section) or back: n = R (A_n R^T N + b_n), A_n = K_SE / K_SE,eff,
// b_n = rho A c^2 (eps0_eff + e3); m = R (A_m R^T M + b_m), A_m = K_BT / K_BT,eff,
// b_m = rho c^2 J_rho kappa0_eff (drawn_rod.hpp); the inverse has A^-1, -A^-1 b.
void convert(const DrawnConstants& d, bool to_section, RodStateWithTangents& Y, bool tangents) {
  if (!d.drawn()) return;
  Vec3 A_n = Vec3::Ones() + Vec3::Constant(d.flux_force).cwiseQuotient(d.k_se);
  Vec3 b_n = d.flux_force * (d.eps0 + Vec3::UnitZ());
  Vec3 A_m = Vec3::Ones() + d.flux_moment.cwiseQuotient(d.k_bt);
  Vec3 b_m = d.flux_moment.cwiseProduct(d.kappa0);
  if (!to_section) {
    A_n = A_n.cwiseInverse();
    b_n = -A_n.cwiseProduct(b_n);
    A_m = A_m.cwiseInverse();
    b_m = -A_m.cwiseProduct(b_m);
  }
  const Quat q = Y.col(0).segment<4>(RodStateIndex::q);
  const Mat3 R = rotation_of(q);
  Block36 omega = Block36::Zero();
  if (tangents) {
    // omega = 2 vec(conj(q) (x) dq) / |q|^2 per tangent column (as in RodOde::derivative).
    Eigen::Matrix<double, 3, 4> G;
    G.col(0) = -q.tail<3>();
    G.rightCols<3>() = q[0] * Mat3::Identity() - hat(Vec3(q.tail<3>()));
    omega = (2.0 / q.squaredNorm()) * G * Y.block<4, kRodTangentCount>(RodStateIndex::q, 1);
  }
  body_affine(R, A_n, b_n, tangents ? &omega : nullptr, Y.col(0).segment<3>(RodStateIndex::n),
              Y.block<3, kRodTangentCount>(RodStateIndex::n, 1));
  body_affine(R, A_m, b_m, tangents ? &omega : nullptr, Y.col(0).segment<3>(RodStateIndex::m),
              Y.block<3, kRodTangentCount>(RodStateIndex::m, 1));
}

}  // namespace

void RodOde::to_effective(RodStateWithTangents& Y) const {
  convert(drawn_, false, Y, true);
}
void RodOde::to_section(RodStateWithTangents& Y) const {
  convert(drawn_, true, Y, true);
}

void RodOde::to_effective(RodStateVector& y) const {
  if (!drawn()) return;
  RodStateWithTangents Y = RodStateWithTangents::Zero();
  Y.col(0) = y;
  convert(drawn_, false, Y, false);
  y = Y.col(0);
}

void RodOde::to_section(RodStateVector& y) const {
  if (!drawn()) return;
  RodStateWithTangents Y = RodStateWithTangents::Zero();
  Y.col(0) = y;
  convert(drawn_, true, Y, false);
  y = Y.col(0);
}

void RodOde::intrinsic_at(double s, Vec3& eps0, Vec3& kappa0) const {
  if (varying_) {
    varying_->at(s, eps0, kappa0);
  } else {
    eps0 = eps0_;
    kappa0 = kappa0_;
  }
}

void RodOde::derivative(double s, const RodStateVector& y, RodStateVector& dyds) const {
  const Quat q = y.segment<4>(RodStateIndex::q);
  const Vec3 n = y.segment<3>(RodStateIndex::n), m = y.segment<3>(RodStateIndex::m);
  const Mat3 R = rotation_of(q);
  Vec3 eps0, kappa0;
  intrinsic_at(s, eps0, kappa0);
  const Vec3 v = compliance_se_.cwiseProduct(R.transpose() * n) + eps0 + Vec3::UnitZ();
  const Vec3 u = compliance_bt_.cwiseProduct(R.transpose() * m) + kappa0;
  const Vec3 dp = R * v;
  dyds.segment<3>(RodStateIndex::p) = dp;
  dyds.segment<4>(RodStateIndex::q) = 0.5 * multiply_pure(q, u);
  dyds.segment<3>(RodStateIndex::n) = -f_;
  dyds.segment<3>(RodStateIndex::m) = -dp.cross(n) - l_;
}

void RodOde::derivative(double s, const RodStateWithTangents& Y, RodStateWithTangents& dYds) const {
  const Quat q = Y.col(0).segment<4>(RodStateIndex::q);
  const Vec3 n = Y.col(0).segment<3>(RodStateIndex::n), m = Y.col(0).segment<3>(RodStateIndex::m);
  const double q2 = q.squaredNorm();
  const Mat3 R = rotation_of(q);
  Vec3 eps0, kappa0;
  intrinsic_at(s, eps0, kappa0);
  const Vec3 n_body = R.transpose() * n, m_body = R.transpose() * m;
  const Vec3 v = compliance_se_.cwiseProduct(n_body) + eps0 + Vec3::UnitZ();
  const Vec3 u = compliance_bt_.cwiseProduct(m_body) + kappa0;
  const Vec3 dp = R * v;
  dYds.col(0).segment<3>(RodStateIndex::p) = dp;
  dYds.col(0).segment<4>(RodStateIndex::q) = 0.5 * multiply_pure(q, u);
  dYds.col(0).segment<3>(RodStateIndex::n) = -f_;
  dYds.col(0).segment<3>(RodStateIndex::m) = -dp.cross(n) - l_;

  // All six tangents at once (3x6 blocks): omega = (2/|q|^2) G(q) dq with
  // G(q) dq = vec(conj(q) (x) dq) = q_w dq_v - dq_w q_v - q_v x dq_v.
  using Block36 = Eigen::Matrix<double, 3, kRodTangentCount>;
  using Block46 = Eigen::Matrix<double, 4, kRodTangentCount>;
  const Vec3 qv = q.tail<3>();
  Eigen::Matrix<double, 3, 4> G;
  G.col(0) = -qv;
  G.rightCols<3>() = q[0] * Mat3::Identity() - hat(qv);
  const auto dQ = Y.block<4, kRodTangentCount>(RodStateIndex::q, 1);
  const auto dN = Y.block<3, kRodTangentCount>(RodStateIndex::n, 1);
  const auto dM = Y.block<3, kRodTangentCount>(RodStateIndex::m, 1);
  const Block36 omega = (2.0 / q2) * G * dQ;
  const Mat3 Rt = R.transpose();
  // n_body x omega = hat(n_body) omega; omega x v = -hat(v) omega.
  const Block36 dv = compliance_se_.asDiagonal() * (hat(n_body) * omega + Rt * dN);
  const Block36 du = compliance_bt_.asDiagonal() * (hat(m_body) * omega + Rt * dM);
  const Block36 ddp = R * (dv - hat(v) * omega);
  // dq (x) [0, u] = P(u) dq (right multiplication), q (x) [0, du] = Lq du (left multiplication).
  Eigen::Matrix4d P;
  P << 0, -u[0], -u[1], -u[2],  //
      u[0], 0, u[2], -u[1],     //
      u[1], -u[2], 0, u[0],     //
      u[2], u[1], -u[0], 0;
  Eigen::Matrix<double, 4, 3> Lq;
  Lq.row(0) = -qv.transpose();
  Lq.bottomRows<3>() = q[0] * Mat3::Identity() + hat(qv);
  const Block46 ddq = 0.5 * (P * dQ + Lq * du);
  dYds.block<3, kRodTangentCount>(RodStateIndex::p, 1) = ddp;
  dYds.block<4, kRodTangentCount>(RodStateIndex::q, 1) = ddq;
  dYds.block<3, kRodTangentCount>(RodStateIndex::n, 1).setZero();
  // dm' = -(dp' x n + p' x dn) = hat(n) dp' - hat(p') dn.
  dYds.block<3, kRodTangentCount>(RodStateIndex::m, 1) = hat(n) * ddp - hat(dp) * dN;
}

}  // namespace pcr
