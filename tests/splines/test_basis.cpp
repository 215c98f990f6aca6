// B-spline and NURBS bases: partition of unity, non-negativity, compact support, derivatives against an
// independent Cox-de Boor recursion and against central finite differences, collocation matrices.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "pcr/splines/basis.hpp"
#include "splines/reference_basis.hpp"

using namespace pcr;
using pcr_test::cox_de_boor;
using pcr_test::throws_input_error_naming;

namespace {

// Non-uniform knots with a double knot (0.25, for p >= 2) and a knot of multiplicity p (0.5, C^0).
KnotVector nonuniform_knots(int p) {
  std::vector<double> xi(p + 1, 0.0);
  xi.push_back(0.1);
  xi.insert(xi.end(), std::min(2, p), 0.25);
  xi.insert(xi.end(), p, 0.5);
  xi.push_back(0.7);
  xi.push_back(0.85);
  xi.insert(xi.end(), p + 1, 1.0);
  return KnotVector(p, xi);
}
constexpr double kNonuniformMinSpan = 0.1;  // shortest element of nonuniform_knots
constexpr int kUniformElements = 5;

struct Case {
  KnotVector knots;
  double min_span;
};

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (int p = 1; p <= 8; ++p) {
    cases.push_back({KnotVector::open_uniform(p, kUniformElements), 1.0 / kUniformElements});
    cases.push_back({nonuniform_knots(p), kNonuniformMinSpan});
  }
  return cases;
}

// 201 equally spaced points (they hit every knot above exactly) plus random points.
std::vector<double> sample_points() {
  std::vector<double> u;
  for (int k = 0; k <= 200; ++k) u.push_back(k / 200.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int k = 0; k < 100; ++k) u.push_back(uniform(rng));
  return u;
}

// Size of the d-th derivatives at u from the independent reference: max(1, max_i |N_i^(d)(u)|).
// Tolerances below are relative to it, since the d-th derivative grows like (p / element)^d.
double reference_scale(const KnotVector& knots, double u, int d) {
  double scale = 1.0;
  for (int i = 0; i < knots.num_basis(); ++i)
    scale = std::max(scale, std::abs(cox_de_boor(knots.knots(), i, knots.degree(), u, d)));
  return scale;
}

}  // namespace

BOOST_AUTO_TEST_CASE(basis_matches_cox_de_boor_with_partition_of_unity_and_compact_support) {
  for (const Case& c : all_cases()) {
    const KnotVector& knots = c.knots;
    const int p = knots.degree(), n = knots.num_basis();
    for (double u : sample_points()) {
      const BasisDerivatives basis = basis_derivatives(knots, u, p);
      BOOST_TEST(basis.first == knots.find_span(u) - p);
      BOOST_TEST(basis.values.rows() == p + 1);
      BOOST_TEST(basis.values.cols() == p + 1);
      // Sum of p+1 values in [0, 1], each with a relative error of O(p eps): 1e-14 > 8 * 3 * 2.2e-16.
      BOOST_TEST(std::abs(basis.values.row(0).sum() - 1.0) < 1e-14);
      BOOST_TEST(basis.values.row(0).minCoeff() >= 0.0);
      for (int d = 0; d <= p; ++d) {
        const double scale = reference_scale(knots, u, d);
        // Derivatives of a partition of unity sum to zero; p+1 terms with O(p eps) relative error each
        // (measured <= 1.5e-15 relative for p <= 8), so 1e-14 relative.
        if (d > 0) BOOST_TEST(std::abs(basis.values.row(d).sum()) < 1e-14 * scale);
        for (int i = 0; i < n; ++i) {
          const double reference = cox_de_boor(knots.knots(), i, p, u, d);
          const bool active = i >= basis.first && i <= basis.first + p;
          const double value = active ? basis.values(d, i - basis.first) : 0.0;
          // Both sides are sums of O(p) rounded products: relative error a few p eps (measured <= 1.5e-15,
          // i.e. 7 eps, for p <= 8); 1e-14 relative = 45 eps.
          BOOST_TEST(std::abs(value - reference) < 1e-14 * scale,
                     "p = " << p << ", u = " << u << ", i = " << i << ", d = " << d << ": " << value << " vs "
                            << reference);
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(derivatives_match_central_differences) {
  const double h = 1e-6;
  for (const Case& c : all_cases()) {
    const KnotVector& knots = c.knots;
    const int p = knots.degree();
    const int max_d = std::min(p, 3);
    for (double u : sample_points()) {
      // Stay 1e-3 away from every knot: the basis is a polynomial on [u-h, u+h].
      bool near_knot = false;
      for (double x : knots.knots()) near_knot = near_knot || std::abs(u - x) < 1e-3;
      if (near_knot) continue;
      const BasisDerivatives at = basis_derivatives(knots, u, max_d);
      const BasisDerivatives plus = basis_derivatives(knots, u + h, max_d);
      const BasisDerivatives minus = basis_derivatives(knots, u - h, max_d);
      BOOST_TEST(plus.first == at.first);
      BOOST_TEST(minus.first == at.first);
      for (int d = 1; d <= max_d; ++d) {
        // Central difference of the (d-1)-th derivative. Truncation h^2/6 |N^(d+2)|: each derivative gains
        // a factor <= 2p / min_span (eq. 2.7), so h^2/6 (2p/min_span)^2 scale_d (4e-9 scale_d for p = 8).
        // Round-off: a few eps |N^(d-1)| / h, with |N^(d-1)| <= scale_d (scale >= 1 and grows with d).
        // Tolerance: 5 times their sum.
        const double growth = 2.0 * p / c.min_span, eps = std::numeric_limits<double>::epsilon();
        const double truncation = h * h / 6 * growth * growth, rounding = 4 * eps / h;
        const double tol = 5 * (truncation + rounding) * reference_scale(knots, u, d);
        for (int j = 0; j <= p; ++j) {
          const double fd = (plus.values(d - 1, j) - minus.values(d - 1, j)) / (2 * h);
          BOOST_TEST(std::abs(at.values(d, j) - fd) < tol, "p = " << p << ", u = " << u << ", d = " << d);
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(allocation_free_variant_matches_and_checks_sizes) {
  const KnotVector knots = nonuniform_knots(4);
  MatX values(3, 5);
  int first = -1;
  for (double u : sample_points()) {
    basis_derivatives(knots, u, 2, first, values);
    const BasisDerivatives reference = basis_derivatives(knots, u, 2);
    BOOST_TEST(first == reference.first);
    BOOST_TEST((values - reference.values).cwiseAbs().maxCoeff() == 0.0);  // same arithmetic, bitwise
  }
  MatX wrong(2, 5);
  BOOST_TEST(
      throws_input_error_naming([&] { basis_derivatives(knots, 0.5, 2, first, wrong); }, {"2 x 5", "3 x 5"}));
  BOOST_TEST(throws_input_error_naming([&] { basis_derivatives(knots, 1.25, 1); }, {"u = 1.25"}));
  BOOST_TEST(throws_input_error_naming([&] { basis_derivatives(knots, 0.5, -1); }, {"max_derivative = -1"}));
  // Derivatives beyond the degree are exactly zero.
  const BasisDerivatives high = basis_derivatives(knots, 0.3, 6);
  BOOST_TEST(high.values.bottomRows(2).cwiseAbs().maxCoeff() == 0.0);
}

BOOST_AUTO_TEST_CASE(rational_basis_matches_the_quotient_rule_on_cox_de_boor) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> weight(0.3, 3.0);
  for (int p = 1; p <= 6; ++p) {
    const KnotVector knots = nonuniform_knots(p);
    const int n = knots.num_basis();
    VecX w(n);
    for (int i = 0; i < n; ++i) w[i] = weight(rng);
    for (double u : sample_points()) {
      const BasisDerivatives R = rational_basis_derivatives(knots, w, u, 2);
      // Independent: W = sum w_i N_i, R_i = w_i N_i / W, R_i' and R_i'' by the quotient rule.
      double W[3] = {0, 0, 0};
      for (int i = 0; i < n; ++i)
        for (int d = 0; d < 3; ++d) W[d] += w[i] * cox_de_boor(knots.knots(), i, p, u, d);
      // Partition of unity of the rational basis: sum of p+1 terms, O(p eps) as for the B-splines.
      BOOST_TEST(std::abs(R.values.row(0).sum() - 1.0) < 1e-14);
      for (int j = 0; j <= p; ++j) {
        const int i = R.first + j;
        const double A0 = w[i] * cox_de_boor(knots.knots(), i, p, u, 0);
        const double A1 = w[i] * cox_de_boor(knots.knots(), i, p, u, 1);
        const double A2 = w[i] * cox_de_boor(knots.knots(), i, p, u, 2);
        const double R0 = A0 / W[0];
        const double R1 = (A1 - W[1] * R0) / W[0];
        const double R2 = (A2 - 2 * W[1] * R1 - W[2] * R0) / W[0];
        // Weights within a factor 10 of each other: the quotient-rule terms stay within ~10^d times the
        // B-spline scale; rounding a few eps per term, so 1e-14 relative to that (as for B-splines).
        BOOST_TEST(std::abs(R.values(0, j) - R0) < 1e-14);
        BOOST_TEST(std::abs(R.values(1, j) - R1) < 1e-14 * 10 * reference_scale(knots, u, 1));
        BOOST_TEST(std::abs(R.values(2, j) - R2) < 1e-14 * 100 * reference_scale(knots, u, 2));
      }
    }
  }
  // Equal weights give back the B-spline basis (W = const).
  const KnotVector knots = KnotVector::open_uniform(3, 4);
  const BasisDerivatives R = rational_basis_derivatives(knots, VecX::Constant(7, 2.5), 0.4, 2);
  const BasisDerivatives N = basis_derivatives(knots, 0.4, 2);
  // Multiplying and dividing by 2.5 plus subtracting W' = sum of zero-sum terms: a few eps of the
  // second-derivative scale (p^2 / h^2 ~ 150), so 1e-12 absolute.
  BOOST_TEST((R.values - N.values).cwiseAbs().maxCoeff() < 1e-12);
  // Bad weights are named.
  BOOST_TEST(throws_input_error_naming([&] { rational_basis_derivatives(knots, VecX::Ones(6), 0.4, 1); },
                                       {"6 weights", "7 basis"}));
  VecX bad = VecX::Ones(7);
  bad[2] = -1.0;
  BOOST_TEST(
      throws_input_error_naming([&] { rational_basis_derivatives(knots, bad, 0.4, 1); }, {"weight[2] = -1"}));
}

BOOST_AUTO_TEST_CASE(collocation_matrix_holds_the_basis_values) {
  const KnotVector knots = nonuniform_knots(3);
  const std::vector<double> tau = knots.greville();
  const int n = knots.num_basis();
  for (int derivative = 0; derivative <= 2; ++derivative) {
    const Eigen::SparseMatrix<double> A = collocation_matrix(knots, tau, derivative);
    BOOST_TEST(A.rows() == static_cast<Eigen::Index>(tau.size()));
    BOOST_TEST(A.cols() == n);
    const MatX dense = MatX(A);
    for (std::size_t r = 0; r < tau.size(); ++r) {
      const BasisDerivatives basis = basis_derivatives(knots, tau[r], derivative);
      for (int i = 0; i < n; ++i) {
        const bool active = i >= basis.first && i <= basis.first + 3;
        BOOST_TEST(dense(r, i) == (active ? basis.values(derivative, i - basis.first) : 0.0));
        // Independent reference; tolerance as in the Cox-de Boor comparison above.
        const double scale = reference_scale(knots, tau[r], derivative);
        BOOST_TEST(std::abs(dense(r, i) - cox_de_boor(knots.knots(), i, 3, tau[r], derivative)) <
                   1e-14 * scale);
      }
      // Rows of the value matrix sum to 1 (partition of unity, O(p eps)).
      if (derivative == 0) BOOST_TEST(std::abs(dense.row(r).sum() - 1.0) < 1e-14);
    }
  }
  // NURBS variant: rows of R sum to 1 as well.
  const VecX w = VecX::LinSpaced(n, 0.5, 2.0);
  const MatX R = MatX(collocation_matrix(knots, tau, 0, &w));
  for (Eigen::Index r = 0; r < R.rows(); ++r) BOOST_TEST(std::abs(R.row(r).sum() - 1.0) < 1e-14);
  BOOST_TEST(throws_input_error_naming([&] { collocation_matrix(knots, tau, -1); }, {"derivative = -1"}));
}

BOOST_AUTO_TEST_CASE(single_element_basis_is_bernstein_also_beyond_the_stack_buffers) {
  // On one element with open knots the B-splines are the Bernstein polynomials
  // B_i(u) = C(p,i) u^i (1-u)^(p-i), B_i' = p (B_{i-1,p-1} - B_{i,p-1}) (The NURBS Book ch. 1, eq. 2.7).
  // Degree 30 exercises the heap scratch path (degree > 24).
  auto bernstein = [](int p, int i, double u) {
    if (i < 0 || i > p) return 0.0;
    double binomial = 1.0;
    for (int k = 1; k <= i; ++k) binomial = binomial * (p - i + k) / k;
    return binomial * std::pow(u, i) * std::pow(1.0 - u, p - i);
  };
  for (int p : {3, 24, 25, 30}) {
    const KnotVector knots = KnotVector::open_uniform(p, 1);
    for (double u : sample_points()) {
      const BasisDerivatives basis = basis_derivatives(knots, u, 1);
      BOOST_TEST(basis.first == 0);
      std::vector<double> derivative(p + 1);
      double scale = 1.0;  // size of the reference derivatives, for a relative tolerance
      for (int i = 0; i <= p; ++i) {
        derivative[i] = p * (bernstein(p - 1, i - 1, u) - bernstein(p - 1, i, u));
        scale = std::max(scale, std::abs(derivative[i]));
      }
      for (int i = 0; i <= p; ++i) {
        // Each side is a product/sum of O(p) rounded factors: relative error ~ p eps <= 30 * 2.2e-16.
        // 1e-13 (absolute, values <= 1; relative to the derivative scale) is ~15 times that.
        BOOST_TEST(std::abs(basis.values(0, i) - bernstein(p, i, u)) < 1e-13);
        BOOST_TEST(std::abs(basis.values(1, i) - derivative[i]) < 1e-13 * scale,
                   "p = " << p << ", u = " << u);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(basis_integrals_match_their_closed_forms_and_derivatives) {
  // J_j(u) = integral_0^u N_j, checked against facts independent of the quadrature:
  //  - J_j(1) = (t_{j+p+1} - t_j) / (p + 1) (the integral of a B-spline);
  //  - sum_j J_j(u) = u (the integral of the partition of unity);
  //  - dJ_j/du = N_j(u) by central differences away from knots (J_j is a polynomial of degree p + 1
  //    there: truncation h^2 / 6 |N_j''| <= 1e-12 (2 p / min_span)^2 with h = 1e-6; round-off 1e-16 / h).
  // Tolerance 1e-13 for the sums (quadrature exact, round-off of ~n (p + 1) terms of size <= 1), 1e-8 for
  // the differences (truncation <= 2.6e-9 for p = 8 and min span 0.1, plus round-off 1e-10).
  for (const Case& c : all_cases()) {
    const KnotVector& knots = c.knots;
    const int p = knots.degree();
    const std::vector<double>& t = knots.knots();
    const VecX full = basis_integrals(knots, 1.0);
    for (int j = 0; j < knots.num_basis(); ++j)
      BOOST_TEST(std::abs(full[j] - (t[j + p + 1] - t[j]) / (p + 1)) < 1e-13, "p = " << p << ", j = " << j);
    BOOST_TEST(basis_integrals(knots, 0.0).cwiseAbs().maxCoeff() == 0.0);
    for (double u : sample_points()) {
      BOOST_TEST(std::abs(basis_integrals(knots, u).sum() - u) < 1e-13, "p = " << p << ", u = " << u);
      bool near_knot = false;
      for (double x : t) near_knot = near_knot || std::abs(u - x) < 1e-3;
      if (near_knot) continue;
      const double h = 1e-6;
      const VecX slope = (basis_integrals(knots, u + h) - basis_integrals(knots, u - h)) / (2 * h);
      const BasisDerivatives at = basis_derivatives(knots, u, 0);
      for (int j = 0; j < knots.num_basis(); ++j) {
        const bool active = j >= at.first && j <= at.first + p;
        const double expected = active ? at.values(0, j - at.first) : 0.0;
        BOOST_TEST(std::abs(slope[j] - expected) < 1e-8, "p = " << p << ", u = " << u << ", j = " << j);
      }
    }
  }
  BOOST_CHECK_THROW(basis_integrals(KnotVector::open_uniform(3, 4), 1.5), InputError);
}

BOOST_AUTO_TEST_CASE(active_basis_integrals_are_those_of_the_functions_active_at_u) {
  // The integrals of the p + 1 functions active at u (first as basis_derivatives gives it) against the
  // entries of basis_integrals, which are checked against closed forms above: the same quadrature on the
  // same spans in the same order, so equal up to the round-off of a different summation (1e-15).
  for (const Case& c : all_cases()) {
    const KnotVector& knots = c.knots;
    const int p = knots.degree();
    for (double u : sample_points()) {
      VecX active(p + 1);
      int first = -1;
      active_basis_integrals(knots, u, first, active);
      BOOST_TEST(first == basis_derivatives(knots, u, 0).first, "p = " << p << ", u = " << u);
      const VecX all = basis_integrals(knots, u);
      for (int j = 0; j <= p; ++j)
        BOOST_TEST(std::abs(active[j] - all[first + j]) < 1e-15,
                   "p = " << p << ", u = " << u << ", j = " << j);
    }
  }
  VecX wrong_size(2);
  int first = 0;
  BOOST_CHECK_THROW(active_basis_integrals(KnotVector::open_uniform(3, 4), 0.5, first, wrong_size),
                    InputError);
  VecX four(4);
  BOOST_CHECK_THROW(active_basis_integrals(KnotVector::open_uniform(3, 4), -0.1, first, four), InputError);
}
