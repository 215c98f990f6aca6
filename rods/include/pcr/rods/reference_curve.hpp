#pragma once
// A stress-free reference centerline given as a B-spline or NURBS curve in R^3 (the "isogeometric"
// geometry input): its arc length, its body frame and the intrinsic strains it implies.
//
// Frame (Frenet): d3 = tangent t, d1 = principal normal N, d2 = binormal B. With t' = k N,
// N' = -k t + tau B, B' = -tau N, the body curvature vee(R^T R') = (<d2',d3>, <d3',d1>, <d1',d2>)
// is kappa0 = (0, k, tau), eps0 = 0 (the reference is unstretched and unsheared):
//   k = |p_u x p_uu| / |p_u|^3,   tau = (p_u x p_uu) . p_uuu / |p_u x p_uu|^2.
// The Frenet frame needs k > 0: curves with straight parts or inflections are rejected.
// The curve may have any parametrisation u in [0, 1]; arc length s(u) = integral |p_u| du.
#include <vector>

#include "pcr/rods/rod_model.hpp"
#include "pcr/splines/spline_curve.hpp"

namespace pcr {

class ReferenceCurve {
 public:
  /// Throws InputError unless the curve is 3-D, regular (|p_u| > 0) and curved (k > 0) everywhere
  /// (checked at 64 points per element).
  explicit ReferenceCurve(SplineCurve curve);

  double length() const { return length_; }
  /// Curve parameter u of arc length s in [0, length()].
  double parameter_at(double s) const;
  Vec3 position_at(double s) const;
  /// [d1 d2 d3] = [N B t] at arc length s.
  Mat3 frame_at(double s) const;
  /// kappa0 = (0, k, tau) and eps0 = 0 at arc length s.
  void strains_at(double s, Vec3& eps0, Vec3& kappa0) const;

  /// Makes `model` stress-free in this shape: length, intrinsic strains (s-dependent), and the base
  /// end's position and orientation at the curve's start (the base kind is left as it is).
  void apply_to(RodModel& model) const;

 private:
  void derivatives_at(double u, Vec3& p1, Vec3& p2, Vec3& p3) const;
  double speed_integral(double a, double b) const;
  SplineCurve curve_;
  std::vector<double> breakpoints_, s_at_breakpoint_;
  double length_ = 0.0;
};

}  // namespace pcr
