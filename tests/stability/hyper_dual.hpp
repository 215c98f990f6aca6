#pragma once
// Second-order forward automatic differentiation for the tests' independent energy model
// (discrete_rods.hpp): a HyperDual<N> carries a value, its gradient and its Hessian with respect to N
// local variables. Only the operations the discrete energy needs.
#include <cmath>

#include <Eigen/Core>

namespace pcr::test {

template <int N>
struct HyperDual {
  using Grad = Eigen::Matrix<double, N, 1>;
  using Hess = Eigen::Matrix<double, N, N>;
  double a = 0.0;
  Grad g = Grad::Zero();
  Hess H = Hess::Zero();

  HyperDual() = default;
  HyperDual(double value) : a(value) {}  // NOLINT: constants convert implicitly
  static HyperDual variable(double value, int i) {
    HyperDual d(value);
    d.g[i] = 1.0;
    return d;
  }

  friend HyperDual operator+(const HyperDual& x, const HyperDual& y) {
    HyperDual r;
    r.a = x.a + y.a;
    r.g = x.g + y.g;
    r.H = x.H + y.H;
    return r;
  }
  friend HyperDual operator-(const HyperDual& x, const HyperDual& y) {
    HyperDual r;
    r.a = x.a - y.a;
    r.g = x.g - y.g;
    r.H = x.H - y.H;
    return r;
  }
  friend HyperDual operator-(const HyperDual& x) {
    HyperDual r;
    r.a = -x.a;
    r.g = -x.g;
    r.H = -x.H;
    return r;
  }
  // (x y)'' = x'' y + x y'' + x' y'^T + y' x'^T
  friend HyperDual operator*(const HyperDual& x, const HyperDual& y) {
    HyperDual r;
    r.a = x.a * y.a;
    r.g = x.g * y.a + y.g * x.a;
    r.H = x.H * y.a + y.H * x.a + x.g * y.g.transpose() + y.g * x.g.transpose();
    return r;
  }
  friend HyperDual operator*(const HyperDual& x, double c) {
    HyperDual r;
    r.a = x.a * c;
    r.g = x.g * c;
    r.H = x.H * c;
    return r;
  }
  friend HyperDual operator*(double c, const HyperDual& x) { return x * c; }
  HyperDual& operator+=(const HyperDual& y) { return *this = *this + y; }
  /// 1 / x: (1/x)' = -x' / x^2, (1/x)'' = -x'' / x^2 + 2 x' x'^T / x^3.
  friend HyperDual inverse(const HyperDual& x) {
    HyperDual r;
    r.a = 1.0 / x.a;
    r.g = -x.g / (x.a * x.a);
    r.H = -x.H / (x.a * x.a) + 2.0 * x.g * x.g.transpose() / (x.a * x.a * x.a);
    return r;
  }
  /// sqrt(x): g / (2 s), H / (2 s) - g g^T / (4 s^3).
  friend HyperDual sqrt(const HyperDual& x) {
    const double s = std::sqrt(x.a);
    HyperDual r;
    r.a = s;
    r.g = x.g / (2.0 * s);
    r.H = x.H / (2.0 * s) - x.g * x.g.transpose() / (4.0 * s * s * s);
    return r;
  }
};

}  // namespace pcr::test
