#include "pcr/rods/shooting/rod_ode.hpp"

#include "pcr/math/quaternion.hpp"

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

Mat3 RodState::R() const {
  return rotation_matrix(q);
}

RodStateVector RodState::to_vector() const {
  RodStateVector y;
  y << p, q, n, m;
  return y;
}

RodState RodState::from_vector(const RodStateVector& y) {
  RodState x;
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
  compliance_se_ = model.shear_extension_stiffness.cwiseInverse();
  compliance_bt_ = model.bending_torsion_stiffness.cwiseInverse();
  f_ = load_factor * model.distributed_force();
  l_ = load_factor * model.loads.moment_per_length;
  eps0_ = model.intrinsic.shear_extension;
  kappa0_ = model.intrinsic.curvature;
  if (model.intrinsic.varying) varying_ = std::make_shared<IntrinsicStrains>(model.intrinsic);
  force_scale_ = model.bending_torsion_stiffness.maxCoeff() / (length_ * length_);
  state_scale_ << Vec3::Constant(length_), Quat::Ones(), Vec3::Constant(force_scale_),
      Vec3::Constant(force_scale_ * length_);
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

  const Quat q_conj(q[0], -q[1], -q[2], -q[3]);
  for (int j = 1; j <= kRodTangentCount; ++j) {
    const Quat dq = Y.col(j).segment<4>(RodStateIndex::q);
    const Vec3 dn = Y.col(j).segment<3>(RodStateIndex::n), dm = Y.col(j).segment<3>(RodStateIndex::m);
    // dR = R hat(omega), omega = 2 vec(conj(q) (x) dq) / |q|^2 (the radial part of dq drops out).
    const Vec3 omega =
        (2.0 / q2) * (q[0] * dq.tail<3>() - dq[0] * q.tail<3>() - q.tail<3>().cross(dq.tail<3>()));
    const Vec3 dv = compliance_se_.cwiseProduct(n_body.cross(omega) + R.transpose() * dn);
    const Vec3 du = compliance_bt_.cwiseProduct(m_body.cross(omega) + R.transpose() * dm);
    const Vec3 ddp = R * (omega.cross(v) + dv);
    dYds.col(j).segment<3>(RodStateIndex::p) = ddp;
    dYds.col(j).segment<4>(RodStateIndex::q) = 0.5 * (multiply_pure(dq, u) + multiply_pure(q, du));
    dYds.col(j).segment<3>(RodStateIndex::n).setZero();
    dYds.col(j).segment<3>(RodStateIndex::m) = -(ddp.cross(n) + dp.cross(dn));
  }
}

}  // namespace pcr
