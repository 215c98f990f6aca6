// BandLu and BorderedBlockLu against dense LU (Eigen's PartialPivLU, an independent implementation) on
// random matrices of their structure, their failure reports, and the Newton solver's use of them
// (NewtonLinearSolver): same roots as with the sparse LU, fallback when a block is singular.
//
// Tolerances: a backward-stable LU solve has a relative error below about cond(A) * n * eps (Golub &
// Van Loan, sec. 3.3); the tests assert cond(A) * n * 1e-14 (eps = 2.2e-16, with a factor 50 for the
// growth of partial pivoting restricted to a band), with cond(A) from the singular values.
#define BOOST_TEST_MODULE structured_lu
#include <boost/test/unit_test.hpp>

#include <array>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "pcr/math/dense_decompositions.hpp"
#include "pcr/solve/band_lu.hpp"
#include "pcr/solve/bordered_block_lu.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "solve/test_problems.hpp"

using namespace pcr;

namespace {

double condition_number(const MatX& A) {
  const VecX s = singular_values(A);
  return s[0] / s[s.size() - 1];
}

double error_bound(const MatX& A) {
  return condition_number(A) * static_cast<double>(A.rows()) * 1e-14;
}

// Random n x n band matrix (entries uniform in [-1, 1]) with zero_diagonal_every-th diagonal entry
// zero, so that the factorisation must pivot.
MatX random_band(int n, int kl, int ku, std::mt19937& rng, int zero_diagonal_every) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatX A = MatX::Zero(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = std::max(0, j - ku); i <= std::min(n - 1, j + kl); ++i) A(i, j) = u(rng);
  for (int j = 0; j < n; j += zero_diagonal_every) A(j, j) = 0.0;
  return A;
}

BandLu band_of(const MatX& A, int kl, int ku) {
  BandLu lu;
  lu.resize(static_cast<int>(A.rows()), kl, ku);
  for (int j = 0; j < A.cols(); ++j)
    for (int i = std::max(0, j - ku); i <= std::min<int>(A.rows() - 1, j + kl); ++i) lu.at(i, j) = A(i, j);
  return lu;
}

Eigen::SparseMatrix<double> sparse(const MatX& A) {
  Eigen::SparseMatrix<double> S = A.sparseView();
  S.makeCompressed();
  return S;
}

// Solves p from its initial values by Newton with NewtonLinearSolver::BorderedBlocks and with Sparse;
// checks that both converge in as many iterations to the same root and returns the factorisation kind
// the structured solver ended with. Both residuals are <= 1e-10 and the Jacobians of the test problems
// well conditioned (diagonally dominant Broyden chains, test_newton): the roots agree to 1e-9.
std::string structured_and_sparse_newton_agree(const Problem& p) {
  NewtonOptions structured, general;
  structured.linear_solver = NewtonLinearSolver::BorderedBlocks;
  general.linear_solver = NewtonLinearSolver::Sparse;
  NewtonSolver a(p, structured), b(p, general);
  VecX xa = p.initial_values(), xb = xa;
  const SolveSummary sa = a.solve(xa), sb = b.solve(xb);
  BOOST_TEST_REQUIRE(sa.converged(), sa.brief_report());
  BOOST_TEST_REQUIRE(sb.converged(), sb.brief_report());
  BOOST_TEST(sa.iterations == sb.iterations);
  BOOST_TEST(std::string(b.factorization_kind()) == "sparse");
  BOOST_TEST((xa - xb).lpNorm<Eigen::Infinity>() <= 1e-9);
  return a.factorization_kind();
}

}  // namespace

BOOST_AUTO_TEST_CASE(band_lu_solves_like_dense_lu_and_pivots) {
  std::mt19937 rng(7);
  for (const auto& [n, kl, ku] :
       {std::array<int, 3>{1, 0, 0}, {12, 1, 1}, {40, 3, 5}, {41, 4, 6}, {60, 7, 2}, {90, 20, 30}}) {
    MatX A = random_band(n, kl, ku, rng, 3);
    if (n == 1) A(0, 0) = 2.0;  // its only entry was zeroed as a "diagonal every 3rd"
    BandLu lu = band_of(A, kl, ku);
    BOOST_REQUIRE(lu.factorize());
    const VecX b = VecX::Random(n);
    VecX x = b;
    lu.solve_in_place(x.data());
    const VecX expected = A.partialPivLu().solve(b);
    BOOST_TEST((x - expected).norm() <= error_bound(A) * expected.norm(), "n = " << n);
    BOOST_TEST((A * x - b).norm() <= 1e-12 * A.norm() * x.norm(), "n = " << n);
    // Sign of det from the dense LU: its diagonal and the parity of its permutation.
    const Eigen::PartialPivLU<MatX> dense(A);
    const int dense_sign = (dense.determinant() > 0) ? 1 : -1;
    BOOST_TEST(lu.determinant_sign() == dense_sign, "n = " << n);
    BOOST_TEST(lu.factor_nonzeros() <= static_cast<long>(n) * (2 * kl + ku + 1));
  }
}

BOOST_AUTO_TEST_CASE(band_lu_reports_a_singular_matrix) {
  MatX A = MatX::Identity(5, 5);
  A(2, 2) = 0.0;  // column 2 is zero within the band: no pivot
  BandLu lu = band_of(A, 1, 1);
  BOOST_TEST(!lu.factorize());
  A(2, 2) = std::numeric_limits<double>::quiet_NaN();
  lu = band_of(A, 1, 1);
  BOOST_TEST(!lu.factorize());
}

// Three banded groups (one with a surplus column that must go to the border), a border of 3 columns
// coupled to every group, border rows touching two groups each.
BOOST_AUTO_TEST_CASE(bordered_block_lu_solves_like_dense_lu) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::vector<int> sizes = {10, 14, 8};
  const int nb = 3;
  int n = nb;
  for (int s : sizes) n += s;
  MatX A = MatX::Zero(n, n);
  std::vector<int> groups(n, -1);
  int offset = 0;
  for (size_t g = 0; g < sizes.size(); ++g) {
    const int s = sizes[g];
    A.block(offset, offset, s, s) = random_band(s, 2, 3, rng, 4);
    for (int k = 0; k < s; ++k) groups[offset + k] = static_cast<int>(g);
    for (int k = 0; k < s; k += 3) A(offset + k, n - nb + static_cast<int>(g)) = u(rng);  // B_g
    offset += s;
  }
  // Group 1 lends its last row to the border (a row touching groups 1 and 2): group 1 then has one
  // column more than rows, and the analysis must move a column to the border.
  const int lent = sizes[0] + sizes[1] - 1;
  A.row(lent).setZero();
  A(lent, lent) = 1.0;
  A(lent, sizes[0] + sizes[1]) = 0.5;
  // Border rows: each couples two groups and the border columns.
  for (int k = 0; k < nb; ++k) {
    const int row = n - nb + k;
    A(row, k) = u(rng);
    A(row, sizes[0] + 2 * k) = u(rng);
    for (int c = 0; c < nb; ++c) A(row, n - nb + c) = u(rng) + (c == k ? 3.0 : 0.0);
  }
  BOOST_REQUIRE(std::abs(A.partialPivLu().determinant()) > 0.0);
  const Eigen::SparseMatrix<double> S = sparse(A);
  BorderedBlockLu lu;
  BOOST_REQUIRE_MESSAGE(lu.analyze_pattern(S, groups), lu.error_message());
  BOOST_TEST(lu.num_groups() == 3);
  BOOST_TEST(lu.border_size() == nb + 1);  // the lent row's group gave a column
  BOOST_REQUIRE_MESSAGE(lu.factorize(S), lu.error_message());
  const VecX b = VecX::Random(n);
  VecX x;
  lu.solve(b, x);
  const VecX expected = A.partialPivLu().solve(b);
  BOOST_TEST((x - expected).norm() <= error_bound(A) * expected.norm());

  // New values on the kept pattern (the Newton iterations' use).
  Eigen::SparseMatrix<double> S2 = S;
  for (int k = 0; k < S2.nonZeros(); ++k) S2.valuePtr()[k] *= 1.0 + 0.1 * std::sin(k);
  BOOST_REQUIRE(lu.factorize(S2));
  lu.solve(b, x);
  const MatX A2 = MatX(S2);
  BOOST_TEST((x - A2.partialPivLu().solve(b)).norm() <= error_bound(A2) * x.norm());
}

BOOST_AUTO_TEST_CASE(bordered_block_lu_refuses_unsuitable_patterns) {
  const Eigen::SparseMatrix<double> S = sparse(MatX::Identity(4, 4));
  BorderedBlockLu lu;
  BOOST_TEST(!lu.analyze_pattern(S, {-1, -1, -1, -1}));  // no group
  BOOST_TEST(!lu.error_message().empty());
  BOOST_TEST(!lu.analyze_pattern(S, {0, 0, -1}));  // wrong size
  BOOST_TEST(lu.analyze_pattern(S, {0, 0, 1, -1}));
  BOOST_TEST(!lu.factorize(sparse(MatX::Identity(3, 3))));  // another pattern
}

// Group {a, b} with rows a + b + c = 3 and a + b = 2: its block [[1, 1], [1, 1]] is singular while the
// whole system (with c + d = 2 in group {d} and the border row a - b + d = 1) is not (det = -2 by row
// reduction). Root (1, 1, 1, 1).
BOOST_AUTO_TEST_CASE(newton_falls_back_to_the_sparse_lu_when_a_block_is_singular) {
  Problem p;
  const VariableId a = p.add_variable_block("a", VecX::Zero(1)), b = p.add_variable_block("b", VecX::Zero(1)),
                   c = p.add_variable_block("c", VecX::Zero(1)), d = p.add_variable_block("d", VecX::Zero(1));
  p.set_variable_group(a, 0);
  p.set_variable_group(b, 0);
  p.set_variable_group(d, 1);
  p.add_residual_block(
      std::make_shared<test::SumBlock>(std::vector<VariableId>{a, b, c}, std::vector<double>{1, 1, 1}, 3.0));
  p.add_residual_block(
      std::make_shared<test::SumBlock>(std::vector<VariableId>{a, b}, std::vector<double>{1, 1}, 2.0));
  p.add_residual_block(
      std::make_shared<test::SumBlock>(std::vector<VariableId>{c, d}, std::vector<double>{1, 1}, 2.0));
  p.add_residual_block(
      std::make_shared<test::SumBlock>(std::vector<VariableId>{a, b, d}, std::vector<double>{1, -1, 1}, 1.0));
  for (NewtonLinearSolver solver :
       {NewtonLinearSolver::Auto, NewtonLinearSolver::BorderedBlocks, NewtonLinearSolver::Sparse}) {
    NewtonOptions o;
    o.linear_solver = solver;
    NewtonSolver newton(p, o);
    VecX x = p.initial_values();
    const SolveSummary s = newton.solve(x);
    BOOST_TEST_REQUIRE(s.converged(), s.brief_report());
    BOOST_TEST((x - VecX::Ones(4)).lpNorm<Eigen::Infinity>() <= 1e-12);  // one exact Newton step
    BOOST_TEST(std::string(newton.factorization_kind()) == "sparse");
  }
}

// G Broyden tridiagonal chains of 50 unknowns (test_problems.hpp), each a group; row 0 of chain g is
// replaced by x_{g,0} + y_g / 2 = 0.1 (coupling it to the border unknown y_g), and border rows
// y_g - x_{g,25} - x_{g+1,25} = 0 couple neighbouring chains. Newton with the structured LU reaches
// the root that it reaches with the sparse LU, in as many iterations.
BOOST_AUTO_TEST_CASE(newton_with_grouped_variables_matches_the_sparse_lu) {
  const int chains = 6, n = 50;
  Problem p;
  std::vector<std::vector<VariableId>> x(chains);
  std::vector<VariableId> y;
  for (int g = 0; g < chains; ++g) {
    for (int i = 0; i < n; ++i) {
      x[g].push_back(
          p.add_variable_block("x" + std::to_string(g) + "_" + std::to_string(i), VecX::Constant(1, -1.0)));
      p.set_variable_group(x[g].back(), g);
    }
    y.push_back(p.add_variable_block("y" + std::to_string(g), VecX::Zero(1)));
  }
  for (int g = 0; g < chains; ++g) {
    p.add_residual_block(std::make_shared<test::SumBlock>(std::vector<VariableId>{x[g][0], y[g]},
                                                          std::vector<double>{1.0, 0.5}, 0.1));
    for (int i = 1; i < n; ++i) p.add_residual_block(std::make_shared<test::BroydenRow>(i, x[g]));
    p.add_residual_block(
        std::make_shared<test::SumBlock>(std::vector<VariableId>{y[g], x[g][25], x[(g + 1) % chains][25]},
                                         std::vector<double>{1.0, -1.0, -1.0}, 0.0));
  }
  BOOST_TEST(structured_and_sparse_newton_agree(p) == "bordered blocks");
}

// One Broyden chain cut into groups of 50 columns: the rows across a cut touch two groups (border
// rows), so each group gives two surplus columns to the border, and the densest-column rule picks
// columns whose removal leaves a block with an inverse of norm ~(7/2)^48. The structured solve is
// then inaccurate; Newton's linear residual check notices it and redoes the step with the sparse LU.
BOOST_AUTO_TEST_CASE(an_ill_conditioned_split_falls_back_to_the_sparse_lu) {
  const int n = 400;
  Problem grouped = test::broyden_problem(n);
  for (int i = 0; i < n; ++i) grouped.set_variable_group(i, i / 50);
  BOOST_TEST(structured_and_sparse_newton_agree(grouped) == "sparse");
}

// A tall band matrix (rows = cols + k, full column rank): the pivot rows are solved exactly and the
// other k rows keep what they leave over, zero for a right-hand side in the range of A.
BOOST_AUTO_TEST_CASE(band_lu_of_a_tall_matrix_solves_its_pivot_rows) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const auto& [cols, extra, kl, ku] : {std::array<int, 4>{10, 1, 3, 2}, {30, 6, 10, 4}, {50, 3, 8, 8}}) {
    const int rows = cols + extra;
    MatX A = MatX::Zero(rows, cols);
    for (int j = 0; j < cols; ++j)
      for (int i = std::max(0, j - ku); i <= std::min(rows - 1, j + kl); ++i) A(i, j) = u(rng);
    for (int j = 0; j < cols; j += 3) A(j, j) = 0.0;  // pivoting needed
    BandLu lu;
    lu.resize(rows, cols, kl, ku);
    for (int j = 0; j < cols; ++j)
      for (int i = std::max(0, j - ku); i <= std::min(rows - 1, j + kl); ++i) lu.at(i, j) = A(i, j);
    BOOST_REQUIRE(lu.factorize());
    // b in the range: x recovered (bound as for the square solve, with cond from A's singular values)
    // and nothing left over but the round-off of the elimination, about rows * eps * ||A|| ||x|| (<= 1.3e-14
    // ||A|| ||x|| here; 1e-13 leaves a factor 8 for the growth of pivoting).
    const VecX x0 = VecX::Random(cols);
    VecX b = A * x0;
    lu.solve_in_place(b.data());
    BOOST_TEST((b.head(cols) - x0).norm() <= error_bound(A) * x0.norm(), "cols = " << cols);
    BOOST_TEST(b.tail(extra).norm() <= 1e-13 * A.norm() * x0.norm(), "cols = " << cols);
    // A general b: the pivot rows (cols of them) are met to round-off (entries <= 1, so a row's misfit is
    // about rows * eps * ||y|| <= 1.3e-14 ||y||; 1e-12 leaves a factor 80 for pivot growth), so at most
    // `extra` rows of A x - b are off; the leftover is nonzero.
    const VecX c = VecX::Random(rows);
    VecX y = c;
    lu.solve_in_place(y.data());
    const VecX misfit = A * y.head(cols) - c;
    int met = 0;
    for (int i = 0; i < rows; ++i) met += std::abs(misfit[i]) <= 1e-12 * (1.0 + y.norm()) ? 1 : 0;
    BOOST_TEST(met >= cols, "cols = " << cols << ": " << met << " rows met");
    // A random c is not in the range of A (probability 1): what is left over is of the order of c, far
    // above round-off.
    BOOST_TEST(y.tail(extra).norm() > 1e-6);
  }
}

// Groups shaped like condensed rods: a band (a chain of points) plus wide columns that every row of
// the group reads (the constant wrench), some rows reading only the wide columns (a free end's force
// condition), border columns (platform pose) read by the last rows of each group, border rows reading
// every group's wide columns (a platform balance). The wide columns go to the border, each group keeps
// its rows; the solve matches dense LU.
BOOST_AUTO_TEST_CASE(bordered_block_lu_moves_wide_columns_to_the_border) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int groups = 3, chain = 40, wide = 3, nb = 3;  // per group: 40 band columns, 3 wide columns
  const int size = chain + wide, n = groups * size + nb;
  MatX A = MatX::Zero(n, n);
  std::vector<int> column_groups(n, -1);
  for (int g = 0; g < groups; ++g) {
    const int o = g * size;
    for (int k = 0; k < size; ++k) column_groups[o + k] = g;
    // Rows 0 .. chain - 1: a band over the chain (kl = 2, ku = 2) and all wide columns.
    A.block(o, o, chain, chain) = random_band(chain, 2, 2, rng, 5);
    for (int i = 0; i < chain; ++i)
      for (int w = 0; w < wide; ++w) A(o + i, o + chain + w) = u(rng);
    // Rows chain .. size - 1: the wide columns and the last chain column only (a tip condition), the
    // first of them also a border column.
    for (int w = 0; w < wide; ++w) {
      const int row = o + chain + w;
      for (int v = 0; v < wide; ++v) A(row, o + chain + v) = u(rng) + (v == w ? 2.0 : 0.0);
      if (w > 0) A(row, o + chain - 1) = u(rng);
    }
    A(o + chain, groups * size + g) = 1.0;
  }
  for (int k = 0; k < nb; ++k) {  // border rows: every group's first wide column and the border
    const int row = groups * size + k;
    for (int g = 0; g < groups; ++g) A(row, g * size + chain + (k % wide)) = u(rng);
    for (int c = 0; c < nb; ++c) A(row, groups * size + c) = u(rng) + (c == k ? 3.0 : 0.0);
  }
  BOOST_REQUIRE(std::abs(A.partialPivLu().determinant()) > 0.0);
  const Eigen::SparseMatrix<double> S = sparse(A);
  BorderedBlockLu lu;
  BOOST_REQUIRE_MESSAGE(lu.analyze_pattern(S, column_groups), lu.error_message());
  BOOST_TEST(lu.num_groups() == groups);
  BOOST_TEST(lu.wide_columns() == groups * wide);
  BOOST_TEST(lu.border_size() == nb + groups * wide);
  BOOST_REQUIRE_MESSAGE(lu.factorize(S), lu.error_message());
  const VecX b = VecX::Random(n);
  VecX x;
  lu.solve(b, x);
  const VecX expected = A.partialPivLu().solve(b);
  BOOST_TEST((x - expected).norm() <= error_bound(A) * expected.norm());
  // New values on the kept pattern: the pivoting may leave other rows over.
  Eigen::SparseMatrix<double> S2 = S;
  for (int k = 0; k < S2.nonZeros(); ++k) S2.valuePtr()[k] *= 1.0 + 0.3 * std::sin(3.0 * k);
  BOOST_REQUIRE_MESSAGE(lu.factorize(S2), lu.error_message());
  lu.solve(b, x);
  const MatX A2 = MatX(S2);
  BOOST_TEST((x - A2.partialPivLu().solve(b)).norm() <= error_bound(A2) * x.norm());
  // A group whose columns are mostly wide (here: a dense 6 x 6 group) keeps them.
  MatX D = MatX::Random(6, 6) + 4.0 * MatX::Identity(6, 6);
  BorderedBlockLu small;
  BOOST_REQUIRE(small.analyze_pattern(sparse(D), std::vector<int>(6, 0)));
  BOOST_TEST(small.wide_columns() == 0);
  BOOST_TEST(small.border_size() == 0);
}
