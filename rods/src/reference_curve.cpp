#include "pcr/rods/reference_curve.hpp"

#include <algorithm>
#include <cmath>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"

namespace pcr {
namespace {

// 5-point Gauss-Legendre on [0, 1]: nodes and weights.
constexpr double kNodes[5] = {0.04691007703066800, 0.23076534494715845, 0.5, 0.76923465505284155,
                              0.95308992296933200};
constexpr double kWeights[5] = {0.11846344252809454, 0.23931433524968324, 0.28444444444444444,
                                0.23931433524968324, 0.11846344252809454};

}  // namespace

ReferenceCurve::ReferenceCurve(SplineCurve curve) : curve_(std::move(curve)) {
  require(curve_.dimension() == 3, "reference curve: must be a curve in R^3, got dimension ", curve_.dimension());
  breakpoints_ = curve_.knots().breakpoints();
  s_at_breakpoint_.assign(1, 0.0);
  for (size_t e = 0; e + 1 < breakpoints_.size(); ++e)
    s_at_breakpoint_.push_back(s_at_breakpoint_.back() + speed_integral(breakpoints_[e], breakpoints_[e + 1]));
  length_ = s_at_breakpoint_.back();
  require(std::isfinite(length_) && length_ > 0.0, "reference curve: length must be positive, got ", length_);
  for (size_t e = 0; e + 1 < breakpoints_.size(); ++e)
    for (int k = 0; k <= 64; ++k) {
      const double u = breakpoints_[e] + (breakpoints_[e + 1] - breakpoints_[e]) * k / 64.0;
      Vec3 p1, p2, p3;
      derivatives_at(u, p1, p2, p3);
      require(p1.norm() > 1e-12 * length_, "reference curve: not regular (|dp/du| = ", p1.norm(), ") at u = ", u);
      const double curvature = p1.cross(p2).norm() / std::pow(p1.norm(), 3);
      require(curvature > 1e-9 / length_, "reference curve: curvature ", curvature, " at u = ", u,
              " (straight part or inflection: the Frenet frame is undefined)");
    }
}

double ReferenceCurve::speed_integral(double a, double b) const {
  // integral_a^b |p_u| du by 5-point Gauss-Legendre on 8 sub-intervals (a and b within one element,
  // where |p_u| is smooth: relative error near round-off).
  double length = 0.0;
  const double h = (b - a) / 8;
  for (int sub = 0; sub < 8; ++sub)
    for (int k = 0; k < 5; ++k) length += h * kWeights[k] * curve_.derivatives(a + h * (sub + kNodes[k]), 1).col(1).norm();
  return length;
}

void ReferenceCurve::derivatives_at(double u, Vec3& p1, Vec3& p2, Vec3& p3) const {
  const MatX d = curve_.derivatives(u, 3);
  p1 = d.col(1);
  p2 = d.col(2);
  p3 = d.col(3);
}

double ReferenceCurve::parameter_at(double s) const {
  require(std::isfinite(s) && s >= -1e-12 * length_ && s <= length_ * (1 + 1e-12), "reference curve: arc length ", s,
          " outside [0, ", length_, "]");
  s = std::clamp(s, 0.0, length_);
  const size_t e = std::min<size_t>(
      std::upper_bound(s_at_breakpoint_.begin(), s_at_breakpoint_.end(), s) - s_at_breakpoint_.begin() - 1,
      breakpoints_.size() - 2);
  double a = breakpoints_[e], b = breakpoints_[e + 1];
  // Newton on s(u) = s within the element, ds/du = |p_u|, safeguarded by bisection; s(u) by Gauss.
  auto arc = [&](double u) { return s_at_breakpoint_[e] + speed_integral(breakpoints_[e], u); };
  double u = a + (b - a) * (s - s_at_breakpoint_[e]) / (s_at_breakpoint_[e + 1] - s_at_breakpoint_[e]);
  for (int it = 0; it < 60; ++it) {
    const double f = arc(u) - s;
    if (std::abs(f) < 1e-15 * length_) break;
    (f > 0 ? b : a) = u;
    double next = u - f / curve_.derivatives(u, 1).col(1).norm();
    if (!(next > a && next < b)) next = 0.5 * (a + b);
    u = next;
  }
  return u;
}

Vec3 ReferenceCurve::position_at(double s) const { return curve_.evaluate(parameter_at(s)); }

Mat3 ReferenceCurve::frame_at(double s) const {
  Vec3 p1, p2, p3;
  derivatives_at(parameter_at(s), p1, p2, p3);
  const Vec3 t = p1.normalized();
  const Vec3 B = p1.cross(p2).normalized();
  Mat3 R;
  R << B.cross(t), B, t;  // N = B x t
  return R;
}

void ReferenceCurve::strains_at(double s, Vec3& eps0, Vec3& kappa0) const {
  Vec3 p1, p2, p3;
  derivatives_at(parameter_at(s), p1, p2, p3);
  const Vec3 c = p1.cross(p2);
  eps0.setZero();
  kappa0 = Vec3(0.0, c.norm() / std::pow(p1.norm(), 3), c.dot(p3) / c.squaredNorm());
}

void ReferenceCurve::apply_to(RodModel& model) const {
  model.length = length_;
  const ReferenceCurve copy = *this;
  model.intrinsic.varying = [copy](double s, Vec3& eps0, Vec3& kappa0) { copy.strains_at(s, eps0, kappa0); };
  model.base.position = position_at(0.0);
  model.base.orientation = quat_from_rotation(frame_at(0.0));
}

}  // namespace pcr
