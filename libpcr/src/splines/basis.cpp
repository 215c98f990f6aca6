#include "pcr/splines/basis.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "pcr/core/error.hpp"
#include "pcr/math/gauss_legendre.hpp"

namespace pcr {

namespace {

// Scratch buffers of A2.3 live on the stack up to this degree; beyond it they are heap-allocated.
constexpr int kStackDegree = 24;
constexpr int kStackSize = kStackDegree + 1;

// The NURBS Book A2.3 (DersBasisFuns). ndu is a (p+1)^2 table: its upper triangle ndu(r, j) holds the
// degree-j basis functions N_{i-j+r, j}(u), its strict lower triangle ndu(j, r) the knot differences
// xi_{i+r+1} - xi_{i+r+1-j}; these are > 0 because xi_i < xi_{i+1} for the span i of u.
// left/right hold u - xi_{i+1-j} and xi_{i+j} - u; a is 2 x (p+1) (two rows of coefficients a_{k,j}).
void ders_basis_funs(const std::vector<double>& xi, int span, double u, int p, int num_derivatives,
                     double* ndu, double* left, double* right, double* a, Eigen::Ref<MatX> ders) {
  const int w = p + 1;  // row stride of ndu and a
  auto N = [&](int row, int col) -> double& { return ndu[row * w + col]; };
  auto A = [&](int row, int col) -> double& { return a[row * w + col]; };
  N(0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - xi[span + 1 - j];
    right[j] = xi[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      N(j, r) = right[r + 1] + left[j - r];
      const double temp = N(r, j - 1) / N(j, r);
      N(r, j) = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N(j, j) = saved;
  }
  for (int j = 0; j <= p; ++j) ders(0, j) = N(j, p);
  // Derivatives (The NURBS Book sec. 2.3): N^(k)_{r} = p!/(p-k)! sum_j a_{k,j} N_{r+j, p-k}, with a_{k,j} by
  // recurrence.
  const int n = std::min(num_derivatives, p);
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    A(0, 0) = 1.0;
    for (int k = 1; k <= n; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        A(s2, 0) = A(s1, 0) / N(pk + 1, rk);
        d = A(s2, 0) * N(rk, pk);
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = r - 1 <= pk ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        A(s2, j) = (A(s1, j) - A(s1, j - 1)) / N(pk + 1, rk + j);
        d += A(s2, j) * N(rk + j, pk);
      }
      if (r <= pk) {
        A(s2, k) = -A(s1, k - 1) / N(pk + 1, r);
        d += A(s2, k) * N(r, pk);
      }
      ders(k, r) = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;  // p! / (p-k)!
  for (int k = 1; k <= n; ++k) {
    for (int j = 0; j <= p; ++j) ders(k, j) *= factor;
    factor *= p - k;
  }
  for (int k = n + 1; k <= num_derivatives; ++k) ders.row(k).setZero();  // beyond the degree
}

}  // namespace

void basis_derivatives(const KnotVector& knots, double u, int max_derivative, int& first,
                       Eigen::Ref<MatX> values) {
  const int p = knots.degree();
  require(max_derivative >= 0, "basis_derivatives: max_derivative = ", max_derivative, " must be >= 0");
  require(values.rows() == max_derivative + 1 && values.cols() == p + 1, "basis_derivatives: values is ",
          values.rows(), " x ", values.cols(), ", expected ", max_derivative + 1, " x ", p + 1);
  const int span = knots.find_span(u);  // throws for u outside [0, 1]
  first = span - p;
  if (p <= kStackDegree) {
    std::array<double, kStackSize * kStackSize> ndu;
    std::array<double, kStackSize> left, right;
    std::array<double, 2 * kStackSize> a;
    ders_basis_funs(knots.knots(), span, u, p, max_derivative, ndu.data(), left.data(), right.data(),
                    a.data(), values);
  } else {
    std::vector<double> ndu((p + 1) * (p + 1)), left(p + 1), right(p + 1), a(2 * (p + 1));
    ders_basis_funs(knots.knots(), span, u, p, max_derivative, ndu.data(), left.data(), right.data(),
                    a.data(), values);
  }
}

BasisDerivatives basis_derivatives(const KnotVector& knots, double u, int max_derivative) {
  require(max_derivative >= 0, "basis_derivatives: max_derivative = ", max_derivative, " must be >= 0");
  BasisDerivatives result;
  result.values.resize(max_derivative + 1, knots.degree() + 1);
  basis_derivatives(knots, u, max_derivative, result.first, result.values);
  return result;
}

namespace {

void check_weights(const KnotVector& knots, const VecX& weights, const char* where) {
  require(weights.size() == knots.num_basis(), where, ": ", weights.size(), " weights given for ",
          knots.num_basis(), " basis functions");
  for (Eigen::Index i = 0; i < weights.size(); ++i)
    require(std::isfinite(weights[i]) && weights[i] > 0.0, where, ": weight[", i, "] = ", weights[i],
            " must be finite and > 0");
}

double binomial(int n, int k) {
  double result = 1.0;
  for (int i = 1; i <= k; ++i) result = result * (n - k + i) / i;
  return result;
}

}  // namespace

BasisDerivatives rational_basis_derivatives(const KnotVector& knots, const VecX& weights, double u,
                                            int max_derivative) {
  check_weights(knots, weights, "rational_basis_derivatives");
  BasisDerivatives result = basis_derivatives(knots, u, max_derivative);
  const int p = knots.degree();
  // A_i^(k) = w_i N_i^(k), W^(k) = sum_i A_i^(k); the Leibniz rule on A_i = R_i W gives (cf. eq. 4.8)
  // R_i^(k) = (A_i^(k) - sum_{l=1..k} C(k,l) W^(l) R_i^(k-l)) / W.
  MatX& values = result.values;
  for (int j = 0; j <= p; ++j) values.col(j) *= weights[result.first + j];
  const VecX W = values.rowwise().sum();
  for (int k = 0; k <= max_derivative; ++k) {
    for (int l = 1; l <= k; ++l) values.row(k) -= binomial(k, l) * W[l] * values.row(k - l);
    values.row(k) /= W[0];
  }
  return result;
}

Eigen::SparseMatrix<double> collocation_matrix(const KnotVector& knots, const std::vector<double>& points,
                                               int derivative, const VecX* weights) {
  require(derivative >= 0, "collocation_matrix: derivative = ", derivative, " must be >= 0");
  if (weights != nullptr) check_weights(knots, *weights, "collocation_matrix");
  const int p = knots.degree();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(points.size() * (p + 1));
  for (std::size_t row = 0; row < points.size(); ++row) {
    const BasisDerivatives basis = weights != nullptr
                                       ? rational_basis_derivatives(knots, *weights, points[row], derivative)
                                       : basis_derivatives(knots, points[row], derivative);
    for (int j = 0; j <= p; ++j)
      entries.emplace_back(static_cast<int>(row), basis.first + j, basis.values(derivative, j));
  }
  Eigen::SparseMatrix<double> matrix(static_cast<Eigen::Index>(points.size()), knots.num_basis());
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

VecX basis_integrals(const KnotVector& knots, double u) {
  require(u >= 0.0 && u <= 1.0, "basis_integrals: u = ", u, " is outside [0, 1]");
  const int p = knots.degree();
  // Gauss-Legendre rule exact for degree <= p + 1, kept per thread for the next call (a rod asks for
  // the integrals at every collocation and sample point).
  thread_local std::vector<double> nodes, weights;
  if (static_cast<int>(nodes.size()) != p / 2 + 1) gauss_legendre(p / 2 + 1, nodes, weights);
  VecX J = VecX::Zero(knots.num_basis());
  MatX values(1, p + 1);
  const std::vector<double>& t = knots.knots();
  for (size_t k = 0; k + 1 < t.size() && t[k] < u; ++k) {
    const double a = t[k], b = std::min(t[k + 1], u);
    if (!(b > a)) continue;
    for (size_t q = 0; q < nodes.size(); ++q) {
      const double x = 0.5 * (a + b) + 0.5 * (b - a) * nodes[q];
      int first = 0;
      basis_derivatives(knots, x, 0, first, values);
      J.segment(first, p + 1) += (0.5 * (b - a) * weights[q]) * values.row(0).transpose();
    }
  }
  return J;
}

void active_basis_integrals(const KnotVector& knots, double u, int& first, Eigen::Ref<VecX> integrals) {
  require(u >= 0.0 && u <= 1.0, "active_basis_integrals: u = ", u, " is outside [0, 1]");
  const int p = knots.degree();
  require(integrals.size() == p + 1, "active_basis_integrals: ", integrals.size(), " values for degree ", p);
  thread_local std::vector<double> nodes, weights;
  if (static_cast<int>(nodes.size()) != p / 2 + 1) gauss_legendre(p / 2 + 1, nodes, weights);
  first = knots.find_span(u) - p;
  integrals.setZero();
  // N_{first+j} is supported on [t_{first+j}, t_{first+j+p+1}]: below u only the spans from t_first on
  // contribute (the same quadrature as basis_integrals, restricted to those spans).
  MatX values(1, p + 1);
  const std::vector<double>& t = knots.knots();
  for (int k = first; k + 1 < static_cast<int>(t.size()) && t[k] < u; ++k) {
    const double a = t[k], b = std::min(t[k + 1], u);
    if (!(b > a)) continue;
    for (size_t q = 0; q < nodes.size(); ++q) {
      const double x = 0.5 * (a + b) + 0.5 * (b - a) * nodes[q];
      int first_x = 0;
      basis_derivatives(knots, x, 0, first_x, values);
      for (int j = 0; j <= p; ++j) {
        const int i = first_x + j - first;  // index among the functions active at u
        if (i >= 0 && i <= p) integrals[i] += 0.5 * (b - a) * weights[q] * values(0, j);
      }
    }
  }
}

}  // namespace pcr
