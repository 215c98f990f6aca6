#include "pcr/rods/rod_end.hpp"

#include "pcr/math/dual.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/rods/collocation/equations.hpp"
#include "pcr/rods/drawn_rod.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr {
using namespace collocation;

// y = [p (3), q (4), n (3), m (3)] is the mixed form's control point itself.
static_assert(kMixedPoint.size == 13 && kMixedPoint.p == 0 && kMixedPoint.q == 3 && kMixedPoint.n == 7 &&
                  kMixedPoint.m == 10,
              "RodEndEvaluator: the mixed control point is y");

RodEndEvaluator::RodEndEvaluator(const CollocationRod& rod, const RodVariables& variables, bool at_tip)
    : at_tip_(at_tip),
      mixed_(rod.discretization().formulation == RodFormulation::Mixed),
      condensed_(rod.discretization().formulation == RodFormulation::Condensed),
      cp_size_(rod.control_point_size()) {
  const int n = rod.num_control_points(), p = rod.discretization().degree;
  const double u = at_tip ? 1.0 : 0.0;
  if (mixed_ || condensed_) {
    count_ = 1;
    variables_ = {variables.control_points[at_tip ? n - 1 : 0]};
    value_basis_ = {1.0};
    if (condensed_) {
      moment_point_ = rod.moment_point();
      if (at_tip && rod.condensed_with_loads()) {
        // The tip's m reads I(1) = sum_j w_j P_j, w_j = integral_0^1 N_j, and L: with running integrals
        // T (collocation_rod.hpp) I(1) = T_{n-1} + w_{n-1} P_{n-1}, the end control point's; else every
        // control point.
        loads_ = true;
        integral_ = rod.point_layout().integral;
        const VecX w = basis_integrals(rod.knots(), 1.0);
        const int first = integral_ >= 0 ? n - 1 : 0;
        count_ = n - first;
        variables_.assign(variables.control_points.begin() + first, variables.control_points.end());
        integral_weights_.assign(w.data() + first, w.data() + n);
        f_ = rod.model().distributed_force();
        l_ = rod.model().loads.moment_per_length;
        variables_.push_back(variables.wrench);
        variables_.push_back(variables.length);
        return;
      }
      variables_.push_back(variables.wrench);
    }
    return;
  }
  const BasisDerivatives d = basis_derivatives(rod.knots(), u, 1);
  count_ = p + 1;
  for (int i = 0; i <= p; ++i) {
    variables_.push_back(variables.control_points[d.first + i]);
    value_basis_.push_back(d.values(0, i));
    derivative_basis_.push_back(d.values(1, i));
  }
  variables_.push_back(variables.length);
  // The constitutive law of the unknowns: for a drawn rod the effective one (M4, drawn_rod.hpp), so that
  // y holds N, M as in the other formulations.
  const RodModel& m = rod.model();
  Vec3 eps0, kappa0;
  m.intrinsic.at(u * m.length, eps0, kappa0);
  const DrawnConstants drawn = drawn_constants(m, eps0, kappa0);
  k_se_ = drawn.k_se;
  k_bt_ = drawn.k_bt;
  eps0_ = drawn.eps0;
  kappa0_ = drawn.kappa0;
}

void RodEndEvaluator::evaluate(const double* const* values, RodEndVector& y,
                               std::vector<MatX>* jacobians) const {
  if (mixed_)
    evaluate_mixed(values, y, jacobians);
  else if (condensed_ && loads_)
    evaluate_condensed_with_loads(values, y, jacobians);
  else if (condensed_)
    evaluate_condensed(values, y, jacobians);
  else
    evaluate_primal(values, y, jacobians);
}

// Mixed: y is the end control point itself.
void RodEndEvaluator::evaluate_mixed(const double* const* values, RodEndVector& y,
                                     std::vector<MatX>* jacobians) const {
  y = Eigen::Map<const RodEndVector>(values[0]);
  if (jacobians) {
    jacobians->resize(1);
    (*jacobians)[0] = MatX::Identity(13, 13);
  }
}

void RodEndEvaluator::evaluate_condensed_with_loads(const double* const* values, RodEndVector& y,
                                                    std::vector<MatX>* jacobians) const {
  // At s = L: n = n0 - f L, m = h - a x n - l L - L (I - c) x f with a = P - c (P of the end control
  // point), I = sum_j w_j P_j over the control points read (+ T of the end one with running integrals).
  // dm/dP_j = L w_j hat(f) (+ hat(n) for the end), dm/dT = L hat(f), dm/dn0 = -hat(a), dm/dh = 1,
  // dn/dL = -f, dm/dL = a x f - l - (I - c) x f.
  const int end = count_ - 1;
  const Eigen::Map<const Eigen::Matrix<double, 7, 1>> point(values[end]);  // [P, Q] first in both layouts
  const Eigen::Map<const Eigen::Matrix<double, 6, 1>> wrench(values[count_]);
  const double L = values[count_ + 1][0];
  Vec3 I = integral_ >= 0 ? Vec3(Eigen::Map<const Vec3>(values[end] + integral_)) : Vec3::Zero();
  for (int j = 0; j < count_; ++j) I += integral_weights_[j] * Eigen::Map<const Vec3>(values[j]);
  const Vec3 a = point.head<3>() - moment_point_, n = wrench.head<3>() - f_ * L;
  y.head<7>() = point;
  y.segment<3>(7) = n;
  PointConstants loads;
  loads.f = f_;
  loads.l = l_;
  y.segment<3>(10) =
      condensed_moment<double>(point.head<3>(), n, wrench.tail<3>(), L, I, loads, moment_point_, 1.0);
  if (jacobians) {
    jacobians->assign(count_ + 2, MatX());
    const Mat3 hat_f = hat(f_);
    for (int j = 0; j < count_; ++j) {
      MatX& J = (*jacobians)[j];
      J = MatX::Zero(13, cp_size_);
      J.block<3, 3>(10, 0) = (L * integral_weights_[j]) * hat_f;
    }
    MatX& Jp = (*jacobians)[end];
    Jp.topLeftCorner<7, 7>().setIdentity();
    Jp.block<3, 3>(10, 0) += hat(n);
    if (integral_ >= 0) Jp.block<3, 3>(10, integral_) = L * hat_f;
    MatX& Jw = (*jacobians)[count_];
    Jw = MatX::Zero(13, 6);
    Jw.block<3, 3>(7, 0).setIdentity();
    Jw.block<3, 3>(10, 0) = -hat(a);
    Jw.block<3, 3>(10, 3).setIdentity();
    MatX& JL = (*jacobians)[count_ + 1];
    JL = MatX::Zero(13, 1);
    JL.block<3, 1>(7, 0) = -f_;
    JL.block<3, 1>(10, 0) = a.cross(f_) - l_ - (I - moment_point_).cross(f_);
  }
}

void RodEndEvaluator::evaluate_condensed(const double* const* values, RodEndVector& y,
                                         std::vector<MatX>* jacobians) const {
  // y = [P, Q, n, h - (P - c) x n]: dm/dP = hat(n), dm/dn = -hat(P - c), dm/dh = I (also the base
  // of the form with loads, where s = 0: its T does not enter).
  static_assert(kCondensedPoint.p == 0 && kCondensedPoint.q == 3 && kCondensedLoadedPoint.p == 0 &&
                    kCondensedLoadedPoint.q == 3,
                "the condensed control points start with y's [p, q]");
  const Eigen::Map<const Eigen::Matrix<double, 7, 1>> point(values[0]);
  const Eigen::Map<const Eigen::Matrix<double, 6, 1>> wrench(values[1]);
  const Vec3 n = wrench.head<3>(), arm = point.head<3>() - moment_point_;
  y.head<7>() = point;
  y.segment<3>(7) = n;
  y.segment<3>(10) = wrench.tail<3>() - arm.cross(n);
  if (jacobians) {
    jacobians->assign(2, MatX());
    MatX& Jp = (*jacobians)[0];
    Jp = MatX::Zero(13, cp_size_);
    Jp.topLeftCorner<7, 7>().setIdentity();
    Jp.block<3, 3>(10, 0) = hat(n);
    MatX& Jw = (*jacobians)[1];
    Jw = MatX::Zero(13, 6);
    Jw.block<3, 3>(7, 0).setIdentity();
    Jw.block<3, 3>(10, 0) = -hat(arm);
    Jw.block<3, 3>(10, 3).setIdentity();
  }
}

void RodEndEvaluator::evaluate_primal(const double* const* values, RodEndVector& y,
                                      std::vector<MatX>* jacobians) const {
  // Primal: local z = [q (4), q_u (4), p_u (3), L (1)] for the wrench; p, q are the end values.
  static_assert(kPrimalPoint.size == 7 && kPrimalPoint.p == 0 && kPrimalPoint.q == 3,
                "the primal control point is [P, Q]");
  using D = Dual<12>;
  Eigen::Matrix<double, 12, 1> zv = Eigen::Matrix<double, 12, 1>::Zero();
  Vec3 p = Vec3::Zero();
  for (int i = 0; i < count_; ++i) {
    const Eigen::Map<const Eigen::Matrix<double, 7, 1>> c(values[i]);
    p += value_basis_[i] * c.head<3>();
    zv.segment<4>(0) += value_basis_[i] * c.segment<4>(3);
    zv.segment<4>(4) += derivative_basis_[i] * c.segment<4>(3);
    zv.segment<3>(8) += derivative_basis_[i] * c.head<3>();
  }
  zv[11] = values[count_][0];
  PointConstants c;
  c.k_se = k_se_;
  c.k_bt = k_bt_;
  c.eps0 = eps0_;
  c.kappa0 = kappa0_;
  Eigen::Matrix<D, 12, 1> z;
  for (int k = 0; k < 12; ++k) z[k] = D::variable(zv[k], k);
  V3<D> n, m;
  primal_wrench<D>(z.segment<4>(0), z.segment<4>(4), z.segment<3>(8), z[11], c, n, m);
  y.segment<3>(0) = p;
  y.segment<4>(3) = zv.segment<4>(0);
  for (int i = 0; i < 3; ++i) {
    y[7 + i] = n[i].a;
    y[10 + i] = m[i].a;
  }
  if (!jacobians) return;
  jacobians->assign(count_ + 1, MatX());
  for (int i = 0; i < count_; ++i) {
    MatX& J = (*jacobians)[i];
    J = MatX::Zero(13, 7);
    J.block<3, 3>(0, 0) = value_basis_[i] * Mat3::Identity();
    J.block<4, 4>(3, 3) = value_basis_[i] * Eigen::Matrix4d::Identity();
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 4; ++k) {
        J(7 + r, 3 + k) = n[r].v[k] * value_basis_[i] + n[r].v[4 + k] * derivative_basis_[i];
        J(10 + r, 3 + k) = m[r].v[k] * value_basis_[i] + m[r].v[4 + k] * derivative_basis_[i];
      }
      for (int k = 0; k < 3; ++k) {
        J(7 + r, k) = n[r].v[8 + k] * derivative_basis_[i];
        J(10 + r, k) = m[r].v[8 + k] * derivative_basis_[i];
      }
    }
  }
  MatX& JL = (*jacobians)[count_];
  JL = MatX::Zero(13, 1);
  for (int r = 0; r < 3; ++r) {
    JL(7 + r, 0) = n[r].v[11];
    JL(10 + r, 0) = m[r].v[11];
  }
}

}  // namespace pcr
