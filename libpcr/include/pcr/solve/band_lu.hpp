#pragma once
// LU factorisation with partial pivoting of a band matrix (kl sub-, ku superdiagonals), the per-rod
// kernel of BorderedBlockLu. The algorithm and storage are those of LAPACK's dgbtf2 / dgbtrs
// (Golub & Van Loan, Matrix Computations, 4th ed., sec. 4.3.5): column-major band storage with
// 2 kl + ku + 1 rows, A(i, j) at row kl + ku + i - j of column j; row interchanges within the kl rows
// below the diagonal let U fill up to kl + ku superdiagonals (the top kl rows of the storage).
// Cost: factorisation about 2 n kl (kl + ku) flops, solve about 2 n (2 kl + ku); entries that are zero
// in a row of U are skipped in the update, and the solves run only over the rows each column of L and U
// actually fills.
//
// The matrix may be tall (rows >= cols): then P A = [L1; L2] U with L1 square unit lower triangular and
// U square upper triangular (the pivots choose which cols of the rows form L1 U), and
// [L1 0; L2 I]^-1 P b splits into the part U solves and the rows' remainder (solve_in_place).
// BorderedBlockLu uses this when it moves a group's wide columns to the border: the rows left over
// after elimination join the Schur complement.
#include <vector>

#include "pcr/core/types.hpp"

namespace pcr {

class BandLu {
 public:
  /// Sizes the storage for an n x n matrix with kl sub- and ku superdiagonals and zeroes it.
  void resize(int n, int kl, int ku) { resize(n, n, kl, ku); }
  /// The same for a rows x cols matrix, rows >= cols (entries A(i, j) with j - ku <= i <= j + kl).
  void resize(int rows, int cols, int kl, int ku);
  /// The shape of resize without the storage, which the next set_zero() makes (an analysed pattern is
  /// then cheap to copy).
  void reshape(int rows, int cols, int kl, int ku);
  /// Zeroes the matrix (before entries are written for a new factorisation), sizing its storage first
  /// after reshape.
  void set_zero();
  /// Entry A(i, j); |i - j| must lie within the band (not checked: callers map entries once).
  double& at(int i, int j) { return ab_[index(i, j)]; }
  /// Position of A(i, j) in data() (for precomputed scatter maps).
  int index(int i, int j) const { return (kl_ + ku_ + i - j) + j * ld_; }
  double* data() { return ab_.data(); }
  int rows() const { return rows_; }
  int cols() const { return cols_; }

  /// In-place factorisation; false when a pivot column is exactly zero (a square matrix is singular, a
  /// tall one has dependent columns).
  bool factorize();
  /// b (rows() values) := [U^-1 g_1; g_2] with g = [L1 0; L2 I]^-1 P b, after a successful factorize():
  /// for a square matrix b := A^-1 b; for a tall one b[0, cols) solves the pivot rows and b[cols, rows)
  /// is what the other rows leave (zero exactly when b is in the range of A).
  void solve_in_place(double* b) const;
  /// Sign of det A (+1 / -1) of a square matrix after a successful factorize().
  int determinant_sign() const;

  /// Nonzero entries of the factors within their actual extents (L without the unit diagonal).
  long factor_nonzeros() const;

 private:
  int rows_ = 0, cols_ = 0, kl_ = 0, ku_ = 0, ld_ = 1;
  std::vector<double> ab_;
  std::vector<int> pivot_;
  std::vector<int> l_rows_;   // below-diagonal rows of column j of L that can be nonzero
  std::vector<int> u_first_;  // first row of column j of U that is nonzero
};

}  // namespace pcr
