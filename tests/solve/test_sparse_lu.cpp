// SparseLu: solutions of small systems with known answers (and of a right-hand side without columns),
// the sign of the determinant (computed by hand), refactorisation on a kept pattern, and the failure
// report of a singular matrix.
#define BOOST_TEST_MODULE sparse_lu
#include <boost/test/unit_test.hpp>

#include <vector>

#include "pcr/solve/sparse_lu.hpp"

using namespace pcr;

namespace {

Eigen::SparseMatrix<double> sparse(const MatX& dense) {
  Eigen::SparseMatrix<double> A = dense.sparseView();
  A.makeCompressed();
  return A;
}

}  // namespace

// A = [[2, 1, 0], [1, 3, 1], [0, 1, 4]], det = 2 (12 - 1) - 1 (4 - 0) = 18 > 0; x = (1, -1, 2) gives
// b = A x = (1, 0, 7). The tolerance is round-off of a 3 x 3 solve (entries of order 1).
BOOST_AUTO_TEST_CASE(solves_a_known_system) {
  MatX A(3, 3);
  A << 2, 1, 0, 1, 3, 1, 0, 1, 4;
  SparseLu lu;
  BOOST_REQUIRE(lu.compute(sparse(A)));
  BOOST_TEST(lu.ok());
  const VecX b = (VecX(3) << 1, 0, 7).finished();
  const VecX expected = (VecX(3) << 1, -1, 2).finished();
  BOOST_TEST((lu.solve(b) - expected).norm() < 1e-14);
  VecX x(3);
  lu.solve(b, x);
  BOOST_TEST((x - expected).norm() < 1e-14);
  MatX B(3, 2);
  B.col(0) = b;
  B.col(1) = 2 * b;
  const MatX X = lu.solve(B);
  BOOST_TEST((X.col(1) - 2 * expected).norm() < 1e-14);
  BOOST_TEST(lu.determinant_sign() == 1);
}

// A right-hand side without columns (the input Jacobian of a robot without inputs) has a 3 x 0 solution;
// Eigen's SparseLU itself asserts on it (with assertions on, as in the sanitizer build).
BOOST_AUTO_TEST_CASE(solves_a_right_hand_side_without_columns) {
  MatX A(3, 3);
  A << 2, 1, 0, 1, 3, 1, 0, 1, 4;
  SparseLu lu;
  BOOST_REQUIRE(lu.compute(sparse(A)));
  const MatX X = lu.solve(MatX(3, 0));
  BOOST_TEST(X.rows() == 3);
  BOOST_TEST(X.cols() == 0);
}

// Swapping two rows of A flips the sign of det A; negating one more row flips it back.
BOOST_AUTO_TEST_CASE(determinant_sign_follows_row_swaps) {
  MatX A(3, 3);
  A << 2, 1, 0, 1, 3, 1, 0, 1, 4;
  A.row(0).swap(A.row(2));
  SparseLu lu;
  BOOST_REQUIRE(lu.compute(sparse(A)));
  BOOST_TEST(lu.determinant_sign() == -1);
  A.row(1) *= -1.0;
  BOOST_REQUIRE(lu.compute(sparse(A)));
  BOOST_TEST(lu.determinant_sign() == 1);
}

// The pattern analysed once serves a matrix with other values (the Newton iterations' use).
BOOST_AUTO_TEST_CASE(refactorizes_on_the_kept_pattern) {
  MatX A(2, 2);
  A << 4, 1, 1, 3;
  Eigen::SparseMatrix<double> S = sparse(A);
  SparseLu lu;
  lu.analyze_pattern(S);
  BOOST_REQUIRE(lu.factorize(S));
  S.coeffRef(0, 0) = -4.0;  // det = -12 - 1 = -13
  BOOST_REQUIRE(lu.factorize(S));
  BOOST_TEST(lu.determinant_sign() == -1);
  const VecX x = lu.solve((VecX(2) << -3, 4).finished());  // A x = b for x = (1, 1)
  BOOST_TEST((x - VecX::Ones(2)).norm() < 1e-14);
}

// A singular matrix (rank 1) is reported, not solved.
BOOST_AUTO_TEST_CASE(reports_a_singular_matrix) {
  MatX A(2, 2);
  A << 1, 2, 2, 4;
  SparseLu lu;
  BOOST_TEST(!lu.compute(sparse(A)));
  BOOST_TEST(!lu.ok());
  BOOST_TEST(!lu.error_message().empty());
  BOOST_TEST(lu.determinant_sign() == 0);
}
