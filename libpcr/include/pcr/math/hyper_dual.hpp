#pragma once
// Second-order forward-mode automatic differentiation: a HyperDual<N> carries a value, its gradient and
// its Hessian with respect to N local variables (dual.hpp carries the first derivatives only). Used where
// exact second derivatives of a few local quantities matter: the energy's Hessian in the stability
// verdict with contact, whose eigenvalues are compared with zero (energy_rod_term.cpp). Works inside
// fixed-size Eigen matrices (NumTraits below). Only the operations pcr needs exist.
#include <cmath>

#include <Eigen/Core>

namespace pcr {

template <int N>
struct HyperDual {
  using Grad = Eigen::Matrix<double, N, 1>;
  using Hess = Eigen::Matrix<double, N, N>;
  double a = 0.0;         ///< value
  Grad g = Grad::Zero();  ///< gradient
  Hess H = Hess::Zero();  ///< Hessian

  HyperDual() = default;
  HyperDual(double value) : a(value) {}  // NOLINT: constants convert implicitly
  HyperDual(double value, const Grad& grad, const Hess& hess) : a(value), g(grad), H(hess) {}
  /// The i-th independent variable with the given value.
  static HyperDual variable(double value, int i) {
    HyperDual d(value);
    d.g[i] = 1.0;
    return d;
  }

  friend HyperDual operator+(const HyperDual& x, const HyperDual& y) {
    return HyperDual(x.a + y.a, x.g + y.g, x.H + y.H);
  }
  friend HyperDual operator-(const HyperDual& x, const HyperDual& y) {
    return HyperDual(x.a - y.a, x.g - y.g, x.H - y.H);
  }
  friend HyperDual operator-(const HyperDual& x) { return HyperDual(-x.a, -x.g, -x.H); }
  /// (x y)'' = x'' y + x y'' + x' y'^T + y' x'^T
  friend HyperDual operator*(const HyperDual& x, const HyperDual& y) {
    const Hess cross = x.g * y.g.transpose();
    return HyperDual(x.a * y.a, x.g * y.a + y.g * x.a, x.H * y.a + y.H * x.a + cross + cross.transpose());
  }
  /// x / y = x (1 / y)
  friend HyperDual operator/(const HyperDual& x, const HyperDual& y) { return x * inverse(y); }
  /// 1 / x: (1/x)' = -x' / x^2, (1/x)'' = -x'' / x^2 + 2 x' x'^T / x^3.
  friend HyperDual inverse(const HyperDual& x) {
    const double i = 1.0 / x.a;
    return HyperDual(i, -x.g * (i * i), -x.H * (i * i) + (2.0 * i * i * i) * x.g * x.g.transpose());
  }
  /// sqrt(x): g / (2 s), H / (2 s) - g g^T / (4 s^3).
  friend HyperDual sqrt(const HyperDual& x) {
    const double s = std::sqrt(x.a);
    return HyperDual(s, x.g / (2.0 * s), x.H / (2.0 * s) - x.g * x.g.transpose() / (4.0 * s * s * s));
  }
  friend HyperDual operator+(const HyperDual& x, double c) { return HyperDual(x.a + c, x.g, x.H); }
  friend HyperDual operator+(double c, const HyperDual& x) { return x + c; }
  friend HyperDual operator-(const HyperDual& x, double c) { return HyperDual(x.a - c, x.g, x.H); }
  friend HyperDual operator-(double c, const HyperDual& x) { return HyperDual(c - x.a, -x.g, -x.H); }
  friend HyperDual operator*(const HyperDual& x, double c) { return HyperDual(x.a * c, x.g * c, x.H * c); }
  friend HyperDual operator*(double c, const HyperDual& x) { return x * c; }
  friend HyperDual operator/(const HyperDual& x, double c) { return x * (1.0 / c); }
  HyperDual& operator+=(const HyperDual& y) { return *this = *this + y; }
  HyperDual& operator-=(const HyperDual& y) { return *this = *this - y; }
  HyperDual& operator*=(const HyperDual& y) { return *this = *this * y; }
  HyperDual& operator/=(const HyperDual& y) { return *this = *this / y; }
};

}  // namespace pcr

namespace Eigen {
template <int N>
struct NumTraits<pcr::HyperDual<N>> : NumTraits<double> {
  using Real = pcr::HyperDual<N>;
  using NonInteger = pcr::HyperDual<N>;
  using Nested = pcr::HyperDual<N>;
  using Literal = pcr::HyperDual<N>;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = 1 + N + N * N,
    MulCost = 1 + 3 * N + 3 * N * N
  };
};
template <int N, typename BinaryOp>
struct ScalarBinaryOpTraits<pcr::HyperDual<N>, double, BinaryOp> {
  using ReturnType = pcr::HyperDual<N>;
};
template <int N, typename BinaryOp>
struct ScalarBinaryOpTraits<double, pcr::HyperDual<N>, BinaryOp> {
  using ReturnType = pcr::HyperDual<N>;
};
}  // namespace Eigen
