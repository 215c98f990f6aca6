#pragma once
// Forward-mode automatic differentiation with a fixed number N of directions: a Dual<N> carries a
// value and its N partial derivatives. Used for the local Jacobians of collocation equations (a few
// tens of local variables per collocation point), so that every block's Jacobian is exact and cheap.
// Works inside fixed-size Eigen matrices (NumTraits below). Only the operations pcr needs exist.
#include <cmath>

#include <Eigen/Core>

namespace pcr {

template <int N>
struct Dual {
  using Grad = Eigen::Matrix<double, N, 1>;
  double a = 0.0;  ///< value
  Grad v;          ///< partial derivatives

  /// Value 0, derivatives not initialised: every default-constructed dual (Eigen's fixed-size matrices
  /// of duals construct all their entries) is assigned before it is read, and zeroing them was half of
  /// the collocation kernels' time.
  Dual() {}  // NOLINT(modernize-use-equals-default): `= default` would value-initialise v in Dual{}
  Dual(double value) : a(value), v(Grad::Zero()) {}  // NOLINT: constants convert implicitly
  Dual(double value, const Grad& grad) : a(value), v(grad) {}
  /// The i-th independent variable with the given value.
  static Dual variable(double value, int i) {
    Dual d(value);
    d.v[i] = 1.0;
    return d;
  }

  Dual& operator+=(const Dual& b) { a += b.a; v += b.v; return *this; }
  Dual& operator-=(const Dual& b) { a -= b.a; v -= b.v; return *this; }
  Dual& operator*=(const Dual& b) { v = v * b.a + b.v * a; a *= b.a; return *this; }
  Dual& operator/=(const Dual& b) { *this = *this / b; return *this; }
  friend Dual operator-(const Dual& x) { return Dual(-x.a, -x.v); }
  friend Dual operator+(const Dual& x, const Dual& y) { return Dual(x.a + y.a, x.v + y.v); }
  friend Dual operator-(const Dual& x, const Dual& y) { return Dual(x.a - y.a, x.v - y.v); }
  friend Dual operator*(const Dual& x, const Dual& y) { return Dual(x.a * y.a, x.v * y.a + y.v * x.a); }
  friend Dual operator/(const Dual& x, const Dual& y) {
    const double inv = 1.0 / y.a;
    return Dual(x.a * inv, (x.v - y.v * (x.a * inv)) * inv);
  }
  friend Dual operator+(const Dual& x, double c) { return Dual(x.a + c, x.v); }
  friend Dual operator+(double c, const Dual& x) { return Dual(x.a + c, x.v); }
  friend Dual operator-(const Dual& x, double c) { return Dual(x.a - c, x.v); }
  friend Dual operator-(double c, const Dual& x) { return Dual(c - x.a, -x.v); }
  friend Dual operator*(const Dual& x, double c) { return Dual(x.a * c, x.v * c); }
  friend Dual operator*(double c, const Dual& x) { return Dual(x.a * c, x.v * c); }
  friend Dual operator/(const Dual& x, double c) { return Dual(x.a / c, x.v / c); }
  friend bool operator<(const Dual& x, const Dual& y) { return x.a < y.a; }
  friend bool operator>(const Dual& x, const Dual& y) { return x.a > y.a; }
  friend bool operator==(const Dual& x, const Dual& y) { return x.a == y.a; }
  friend bool operator!=(const Dual& x, const Dual& y) { return x.a != y.a; }
};

template <int N>
Dual<N> sqrt(const Dual<N>& x) {
  const double r = std::sqrt(x.a);
  return Dual<N>(r, x.v * (0.5 / r));
}

/// Value part of a double or a Dual.
inline double value_of(double x) { return x; }
template <int N>
double value_of(const Dual<N>& x) {
  return x.a;
}

}  // namespace pcr

namespace Eigen {
template <int N>
struct NumTraits<pcr::Dual<N>> : NumTraits<double> {
  using Real = pcr::Dual<N>;
  using NonInteger = pcr::Dual<N>;
  using Nested = pcr::Dual<N>;
  using Literal = pcr::Dual<N>;
  enum { IsComplex = 0, IsInteger = 0, IsSigned = 1, RequireInitialization = 1, ReadCost = 1,
         AddCost = 1 + N, MulCost = 1 + 2 * N };
};
template <int N, typename BinaryOp>
struct ScalarBinaryOpTraits<pcr::Dual<N>, double, BinaryOp> {
  using ReturnType = pcr::Dual<N>;
};
template <int N, typename BinaryOp>
struct ScalarBinaryOpTraits<double, pcr::Dual<N>, BinaryOp> {
  using ReturnType = pcr::Dual<N>;
};
}  // namespace Eigen
