#include "robot_blocks.hpp"

#include <algorithm>

#include "pcr/math/dual.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/rods/collocation/end_equations.hpp"
#include "pcr/rods/end_axes.hpp"

namespace pcr::assembly {
using namespace collocation;

namespace {

std::vector<VariableId> concat(std::vector<VariableId> a, const std::vector<VariableId>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

using RowMap = Eigen::Map<RowMajorMatX>;
// The chain rules below multiply 7 x 13 (or 7 x 7) by 13 x k (k <= 7) matrices: lazyProduct (a loop
// over the coefficients) rather than operator*, which takes Eigen's blocked matrix product for dynamic
// sizes and spends most of its time packing (8 % of a universal_pair cold solve's instructions).

}  // namespace

// ---------------------------------------------------------------------------------------------------
CouplingBlock::CouplingBlock(const std::string& name, RodEndEvaluator end, LinkFrame frame, RodEndKind kind,
                             const Vec3& axis, const PointConstants& scales)
    : ResidualBlock(std::string("coupling.") + to_string(kind), name, 7,
                    concat(end.variables(), frame.variables)),
      end_(std::move(end)),
      frame_(std::move(frame)),
      kind_(kind),
      axes_(joint_axes(axis)),
      scales_(scales),
      end_blocks_(static_cast<int>(end_.variables().size())) {}

namespace {

// The 7 coupling equations from z = [y (13): p, q, n, m of the rod end; x (3), Q (4): link frame].
template <typename T>
void coupling_residual(const Eigen::Matrix<T, 20, 1>& z, const Pose& offset, RodEndKind kind,
                       const Mat3& axes, const PointConstants& scales, T* r) {
  const V3<T> x = z.template segment<3>(13);
  const V4<T> Q = z.template segment<4>(16);
  const M3<T> RQ = rotation(Q);
  EndTarget<T> t;
  t.position = x + RQ * offset.position.cast<T>();
  t.orientation = quat_product<T>(Q, offset.orientation.cast<T>());
  t.frame = RQ * offset.rotation().cast<T>();
  t.axes = axes;
  end_conditions<T>(kind, t, EndLoads{}, scales, z.template segment<3>(0), z.template segment<4>(3),
                    z.template segment<3>(7), z.template segment<3>(10), r);
}

}  // namespace

void CouplingBlock::evaluate(const double* const* values, double* residual, double* const* jacobians) const {
  RodEndVector y;
  std::vector<MatX> dy;
  end_.evaluate(values, y, jacobians ? &dy : nullptr);
  Vec7 zl;
  MatX dz;
  frame_.evaluate(values + end_blocks_, zl, jacobians ? &dz : nullptr);
  if (!jacobians) {
    Eigen::Matrix<double, 20, 1> z;
    z << y, zl;
    coupling_residual<double>(z, frame_.offset, kind_, axes_, scales_, residual);
    return;
  }
  using D = Dual<20>;
  Eigen::Matrix<D, 20, 1> z;
  for (int k = 0; k < 13; ++k) z[k] = D::variable(y[k], k);
  for (int k = 0; k < 7; ++k) z[13 + k] = D::variable(zl[k], 13 + k);
  D r[7];
  coupling_residual<D>(z, frame_.offset, kind_, axes_, scales_, r);
  for (int i = 0; i < 7; ++i) residual[i] = r[i].a;
  Eigen::Matrix<double, 7, 20> dr;
  for (int i = 0; i < 7; ++i) dr.row(i) = r[i].v.transpose();
  for (int k = 0; k < end_blocks_; ++k)
    if (jacobians[k]) RowMap(jacobians[k], 7, dy[k].cols()) = dr.leftCols<13>().lazyProduct(dy[k]);
  int column = 0;
  for (size_t k = 0; k < frame_.variables.size(); ++k) {
    const int size = frame_.kind == LinkFrame::Kind::Platform ? 7 : 1;
    if (jacobians[end_blocks_ + k])
      RowMap(jacobians[end_blocks_ + k], 7, size) =
          dr.rightCols<7>().lazyProduct(dz.middleCols(column, size));
    column += size;
  }
}

// ---------------------------------------------------------------------------------------------------
namespace {
std::vector<VariableId> balance_variables(VariableId platform, const std::vector<PlatformRodEnd>& ends,
                                          const std::vector<PlatformContact>& contacts) {
  std::vector<VariableId> v{platform};
  for (const PlatformRodEnd& e : ends) v = concat(v, e.end.variables());
  const PlatformContactReaction appended(contacts, v);  // appends the contact variables
  (void)appended;
  return v;
}
}  // namespace

PlatformBalanceBlock::PlatformBalanceBlock(const std::string& name, VariableId platform,
                                           std::vector<PlatformRodEnd> ends, std::vector<PlatformLoad> loads,
                                           double mass, const Vec3& center_of_mass, const Vec3& gravity,
                                           double force_scale, double moment_scale,
                                           std::vector<PlatformContact> contacts)
    : ResidualBlock("platform.balance", name, 7, balance_variables(platform, ends, contacts)),
      ends_(std::move(ends)),
      loads_(std::move(loads)),
      mass_(mass),
      com_(center_of_mass),
      gravity_(gravity),
      force_scale_(force_scale),
      moment_scale_(moment_scale) {
  std::vector<VariableId> v = balance_variables(platform, ends_, {});
  contact_ = PlatformContactReaction(std::move(contacts), v);  // the same indices as variables()
}

void PlatformBalanceBlock::evaluate(const double* const* values, double* residual,
                                    double* const* jacobians) const {
  const Eigen::Map<const Vec7> pose(values[0]);
  const Vec3 x = pose.head<3>();
  const Quat Q = pose.tail<4>();
  Mat3 R;
  QuatRotationJacobian dR;
  rotation_matrix_derivatives(Q, R, dR);
  const Vec3 weight = mass_ * gravity_;
  Vec3 force = weight, moment = (R * com_).cross(weight);
  Eigen::Matrix<double, 3, 4> dmoment_dQ;
  for (int k = 0; k < 4; ++k) dmoment_dQ.col(k) = (dR[k] * com_).cross(weight);
  for (const PlatformLoad& l : loads_) {
    force += l.force;
    moment += l.torque + (R * l.point).cross(l.force);
    for (int k = 0; k < 4; ++k) dmoment_dQ.col(k) += (dR[k] * l.point).cross(l.force);
  }
  Mat3 dmoment_dx = Mat3::Zero();
  int block = 1;
  std::vector<MatX> dy;
  if (jacobians) contact_.zero_appended(jacobians, 7);
  for (const PlatformRodEnd& e : ends_) {
    RodEndVector y;
    e.end.evaluate(values + block, y, jacobians ? &dy : nullptr);
    const Vec3 p = y.segment<3>(0), n = y.segment<3>(7), m = y.segment<3>(10);
    force -= e.sigma * n;
    moment -= e.sigma * (m + (p - x).cross(n));
    if (jacobians) {
      // d/dp = sigma hat(n), d/dn = -sigma hat(p - x), d/dm = -sigma I;  d/dx = -sigma hat(n).
      Eigen::Matrix<double, 7, 13> dr_dy = Eigen::Matrix<double, 7, 13>::Zero();
      dr_dy.block<3, 3>(0, 7) = -e.sigma * Mat3::Identity() / force_scale_;
      dr_dy.block<3, 3>(3, 0) = e.sigma * hat(n) / moment_scale_;
      dr_dy.block<3, 3>(3, 7) = -e.sigma * hat(p - x) / moment_scale_;
      dr_dy.block<3, 3>(3, 10) = -e.sigma * Mat3::Identity() / moment_scale_;
      dmoment_dx -= e.sigma * hat(n);
      for (size_t k = 0; k < dy.size(); ++k)
        if (jacobians[block + k]) RowMap(jacobians[block + k], 7, dy[k].cols()) = dr_dy.lazyProduct(dy[k]);
    }
    block += static_cast<int>(e.end.variables().size());
  }
  contact_.add(values, x, force, moment, dmoment_dx, jacobians, 7, force_scale_, moment_scale_);
  Eigen::Map<Eigen::Matrix<double, 7, 1>> r(residual);
  r.head<3>() = force / force_scale_;
  r.segment<3>(3) = moment / moment_scale_;
  r[6] = Q.squaredNorm() - 1.0;
  if (jacobians && jacobians[0]) {
    RowMap J(jacobians[0], 7, 7);
    J.setZero();
    J.block<3, 3>(3, 0) = dmoment_dx / moment_scale_;
    J.block<3, 4>(3, 3) = dmoment_dQ / moment_scale_;
    J.block<1, 4>(6, 3) = 2.0 * Q.transpose();
  }
}

// ---------------------------------------------------------------------------------------------------
namespace {
int target_rows(const PoseComponents& c) {
  return static_cast<int>(std::count(c.begin(), c.end(), true));
}
}  // namespace

PoseTargetBlock::PoseTargetBlock(const std::string& name, VariableId platform, VariableId target,
                                 const Pose& offset, const PoseComponents& components, double length_scale)
    : ResidualBlock("target.pose", name, target_rows(components), {platform, target}),
      offset_(offset),
      components_(components),
      length_scale_(length_scale) {}

namespace {

// All six target rows from z = [x (3), Q (4): platform pose; xt (3), Qt (4): target pose].
template <typename T>
void pose_target_residual(const Eigen::Matrix<T, 14, 1>& z, const Pose& offset, double length_scale, T* all) {
  const V3<T> x = z.template segment<3>(0), xt = z.template segment<3>(7);
  const V4<T> Q = z.template segment<4>(3), Qt = z.template segment<4>(10);
  const V3<T> xf = x + rotation(Q) * offset.position.cast<T>();
  const V4<T> Qf = quat_product<T>(Q, offset.orientation.cast<T>());
  const V3<T> e = conj_product_vec<T>(Qt, Qf) * 2.0;
  for (int i = 0; i < 3; ++i) {
    all[i] = (xf[i] - xt[i]) / length_scale;
    all[3 + i] = e[i];
  }
}

}  // namespace

void PoseTargetBlock::evaluate(const double* const* values, double* residual,
                               double* const* jacobians) const {
  if (!jacobians) {
    Eigen::Matrix<double, 14, 1> z;
    z << Eigen::Map<const Vec7>(values[0]), Eigen::Map<const Vec7>(values[1]);
    double all[6];
    pose_target_residual<double>(z, offset_, length_scale_, all);
    int row = 0;
    for (int i = 0; i < 6; ++i)
      if (components_[i]) residual[row++] = all[i];
    return;
  }
  using D = Dual<14>;
  Eigen::Matrix<D, 14, 1> z;
  for (int k = 0; k < 7; ++k) {
    z[k] = D::variable(values[0][k], k);
    z[7 + k] = D::variable(values[1][k], 7 + k);
  }
  D all[6];
  pose_target_residual<D>(z, offset_, length_scale_, all);
  int row = 0;
  for (int i = 0; i < 6; ++i) {
    if (!components_[i]) continue;
    residual[row] = all[i].a;
    for (int b = 0; b < 2; ++b)
      if (jacobians[b])
        for (int k = 0; k < 7; ++k) jacobians[b][row * 7 + k] = all[i].v[7 * b + k];
    ++row;
  }
}

}  // namespace pcr::assembly
