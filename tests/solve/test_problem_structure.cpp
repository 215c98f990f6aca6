// Problem's derived structure: the Hessian against finite differences of the Lagrangian's gradient, its
// pattern built by appending or from scratch (blocks added out of order), and evaluation scratch that
// survives a block evaluating another Problem (part of the test_problem module).
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "pcr/solve/jacobian_check.hpp"
#include "pcr/solve/problem.hpp"
#include "solve/test_problems.hpp"

using namespace pcr;
using pcr::test::BroydenRow;
using pcr::test::CircleBlock;
using pcr::test::LineBlock;
using SparseRowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

namespace {

// Broyden rows added last to first: every block after the first adds Hessian entries before the existing
// ones (the structure is rebuilt), where broyden_problem adds them after (appended).
Problem broyden_problem_reversed(int n) {
  Problem p;
  std::vector<VariableId> x;
  for (int i = 0; i < n; ++i)
    x.push_back(p.add_variable_block("x" + std::to_string(i), VecX::Constant(1, -1.0)));
  for (int i = n - 1; i >= 0; --i) p.add_residual_block(std::make_shared<BroydenRow>(i, x));
  return p;
}

/// c = (sum of the entries of its variable blocks)^2: Hessian 2 w 1 1^T over them.
class SquaredSum : public ResidualBlock {
 public:
  explicit SquaredSum(std::vector<VariableId> ids)
      : ResidualBlock("test.squared_sum", "squared_sum", 1, ids) {}
  void evaluate(const double* const* v, double* c, double* const* J) const override {
    double sum = 0.0;
    for (std::size_t k = 0; k < variables().size(); ++k) sum += v[k][0] + v[k][1];
    c[0] = sum * sum;
    for (std::size_t k = 0; J && k < variables().size(); ++k)
      if (J[k]) J[k][0] = J[k][1] = 2.0 * sum;
  }
  bool provides_hessian() const override { return true; }
  void evaluate_hessian(const double* const*, const double* w, double* H) const override {
    const int n = 2 * static_cast<int>(variables().size());
    std::fill(H, H + n * n, 2.0 * w[0]);
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(hessian_is_the_same_built_in_either_block_order_and_after_deactivation) {
  const int n = 12;
  Problem appended = pcr::test::broyden_problem(n), rebuilt = broyden_problem_reversed(n);
  const VecX x = VecX::LinSpaced(n, -1.0, 0.5), lambda = VecX::LinSpaced(n, 0.5, 2.0);
  SparseRowMajor Ha, Hr;
  appended.evaluate_hessian(x, 1.0, lambda, Ha);
  rebuilt.evaluate_hessian(x, 1.0, lambda, Hr);
  // Lower triangle of the union of the rows' squares over {x_{i-1}, x_i, x_{i+1}}: n diagonal entries,
  // n - 1 first and n - 2 second subdiagonal ones.
  BOOST_TEST(Ha.nonZeros() == 3 * n - 3);
  BOOST_TEST(Hr.nonZeros() == Ha.nonZeros());
  BOOST_TEST(std::equal(Ha.outerIndexPtr(), Ha.outerIndexPtr() + n + 1, Hr.outerIndexPtr()));
  BOOST_TEST(std::equal(Ha.innerIndexPtr(), Ha.innerIndexPtr() + Ha.nonZeros(), Hr.innerIndexPtr()));
  // Row i of the reversed problem has multiplier lambda[n - 1 - i]. The only second derivative of row i is
  // d2 c_i / dx_i^2 = -4 (one product each: exact).
  for (int i = 0; i < n; ++i) {
    BOOST_TEST(Ha.coeff(i, i) == -4.0 * lambda[i]);
    BOOST_TEST(Hr.coeff(i, i) == -4.0 * lambda[n - 1 - i]);
    if (i > 0) BOOST_TEST(Ha.coeff(i, i - 1) == 0.0);
  }
  // Switching row 5 off removes the entry (6, 4) that only its square holds, and its diagonal term.
  appended.set_residual_active(5, false);
  VecX lambda_active(n - 1);
  lambda_active << lambda.head(5), lambda.tail(n - 6);
  appended.evaluate_hessian(x, 1.0, lambda_active, Ha);
  BOOST_TEST(Ha.nonZeros() == 3 * n - 4);
  BOOST_TEST(Ha.coeff(5, 5) == 0.0);
  BOOST_TEST(Ha.coeff(6, 6) == -4.0 * lambda[6]);
}

BOOST_AUTO_TEST_CASE(hessian_matches_finite_differences_of_the_lagrangian_gradient) {
  Problem p = pcr::test::hs071_problem();
  BOOST_TEST(p.provides_hessian());
  const VecX x = (VecX(4) << 1.2, 4.1, 3.3, 1.7).finished();
  const VecX lambda = (VecX(2) << -0.7, 0.4).finished();
  const double sigma = 1.3;
  SparseRowMajor H, J;
  p.evaluate_hessian(x, sigma, lambda, H);
  // Independent reference: central differences of grad L = sigma grad f + J^T lambda.
  auto grad_lagrangian = [&](const VecX& y) {
    VecX g, c;
    p.evaluate_objective(y, &g);
    p.evaluate_residuals_and_jacobian(y, c, J);
    return VecX(sigma * g + J.transpose() * lambda);
  };
  const double h = 1e-6;
  for (int j = 0; j < 4; ++j) {
    VecX xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    const VecX column = (grad_lagrangian(xp) - grad_lagrangian(xm)) / (2 * h);
    for (int i = j; i < 4; ++i) {
      // The Lagrangian gradient is polynomial of degree <= 3: O(h^2) truncation ~1e-11, round-off
      // ~eps |grad L| / h ~ 1e-9; 1e-7 bounds both.
      BOOST_TEST(std::abs(H.coeff(i, j) - column[i]) <= 1e-7, "H(" << i << "," << j << ")");
    }
    for (int i = 0; i < j; ++i) BOOST_TEST(H.coeff(i, j) == 0.0);  // lower triangle only
  }
}

// Blocks whose Hessian entries come before existing ones in row-major order (a block over v, then one
// over u and v, then one over u: u's rows come first) mark the pattern stale; it is rebuilt when the
// Hessian is first evaluated. Every lower entry against the closed form: H_ij = 2 sum of the weights of
// the blocks touching both i and j.
BOOST_AUTO_TEST_CASE(hessian_pattern_after_blocks_added_out_of_order) {
  Problem p;
  const VariableId u = p.add_variable_block("u", VecX::Zero(2)), v = p.add_variable_block("v", VecX::Zero(2));
  p.add_residual_block(std::make_shared<SquaredSum>(std::vector<VariableId>{v}));
  p.add_residual_block(std::make_shared<SquaredSum>(std::vector<VariableId>{u, v}));
  p.add_residual_block(std::make_shared<SquaredSum>(std::vector<VariableId>{u}));
  const VecX w = (VecX(3) << 1.0, 2.0, 3.0).finished();
  SparseRowMajor H;
  p.evaluate_hessian(VecX::Zero(4), 1.0, w, H);
  BOOST_TEST(H.nonZeros() == 10);  // the whole lower triangle of 4 x 4
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j <= i; ++j) {
      const bool both_u = i < 2 && j < 2, both_v = i >= 2 && j >= 2;
      const double expected = 2.0 * (w[1] + (both_u ? w[2] : 0.0) + (both_v ? w[0] : 0.0));
      BOOST_TEST(H.coeff(i, j) == expected, "H(" << i << "," << j << ")");
    }
}

namespace {

// c = sum of the residuals of an inner problem (Broyden, n = 3) at (a0, a1, 0.5): a block that evaluates
// another Problem inside its own evaluation, as the reduced-space IK does. It writes its Jacobian only
// after the inner evaluation, so the outer evaluation's pointers must survive it.
class NestedBlock : public ResidualBlock {
 public:
  explicit NestedBlock(VariableId a) : ResidualBlock("test.nested", "nested", 1, {a}) {}
  void evaluate(const double* const* v, double* c, double* const* J) const override {
    VecX x(3), inner_c;
    x << v[0][0], v[0][1], 0.5;
    SparseRowMajor inner_J;
    inner_.evaluate_residuals_and_jacobian(x, inner_c, inner_J);
    c[0] = inner_c.sum();
    if (!J || !J[0]) return;
    const Eigen::RowVectorXd column_sums = Eigen::RowVectorXd::Ones(3) * inner_J;
    J[0][0] = column_sums[0];
    J[0][1] = column_sums[1];
  }

 private:
  Problem inner_ = pcr::test::broyden_problem(3);
};

}  // namespace

BOOST_AUTO_TEST_CASE(a_block_may_evaluate_another_problem) {
  Problem p;
  const VariableId s = p.add_variable_block("s", VecX::Constant(1, 1.5));
  const VariableId t = p.add_variable_block("t", VecX::Constant(1, -0.25));
  const VariableId a = p.add_variable_block("a", (VecX(2) << 0.3, -0.7).finished());
  p.add_residual_block(std::make_shared<CircleBlock>(t, s, 2.0));
  p.add_residual_block(std::make_shared<NestedBlock>(a));
  p.add_residual_block(std::make_shared<LineBlock>(t, s, 1.0, -1.0, 0.0));
  VecX c;
  SparseRowMajor J;
  p.evaluate_residuals_and_jacobian(p.initial_values(), c, J);
  // Written out from the Broyden rows c_i = (3 - 2 x_i) x_i - x_{i-1} - 2 x_{i+1} + 1 at (0.3, -0.7, 0.5):
  // their sum and its derivatives d/dx0 = 3 - 4 x0 - 1, d/dx1 = -2 + 3 - 4 x1 - 1. Same operations up to
  // reassociation: 1e-14.
  const double x0 = 0.3, x1 = -0.7, x2 = 0.5;
  const double sum =
      ((3 - 2 * x0) * x0 - 2 * x1 + 1) + ((3 - 2 * x1) * x1 - x0 - 2 * x2 + 1) + ((3 - 2 * x2) * x2 - x1 + 1);
  BOOST_TEST(std::abs(c[1] - sum) <= 1e-14);
  BOOST_TEST(std::abs(J.coeff(1, 2) - (2 - 4 * x0)) <= 1e-14);
  BOOST_TEST(std::abs(J.coeff(1, 3) - (-4 * x1)) <= 1e-14);
  // The blocks around it are unaffected (values as in offsets_rows_and_pattern_match_the_blocks).
  BOOST_TEST(c[0] == -0.25 * -0.25 + 1.5 * 1.5 - 4.0);
  BOOST_TEST(c[2] == -0.25 - 1.5);
  BOOST_TEST(J.coeff(0, 0) == 2 * 1.5);
  BOOST_TEST(J.coeff(2, 1) == 1.0);
  const JacobianCheckResult r = check_problem_jacobian(p, p.initial_values());
  BOOST_TEST(r.passed, r.to_string());
}
