#pragma once
// Sparse LU of a square matrix (Eigen's SparseLU, natural column order), the one linear solver of the Newton
// iterations, the implicit-function-theorem derivatives and the spline interpolations. Behind this
// class so that Eigen's SparseLU templates are compiled once (sparse_lu.cpp) instead of in every file
// that solves a system: about 20 s of compile time per such file in the sanitizer build, 11 s in Release.
#include <Eigen/SparseCore>
#include <memory>
#include <string>

#include "pcr/core/types.hpp"

namespace pcr {

class SparseLu {
 public:
  SparseLu();
  ~SparseLu();
  SparseLu(SparseLu&&) noexcept;
  SparseLu& operator=(SparseLu&&) noexcept;

  /// Ordering and symbolic analysis of A's pattern (kept for factorize() of matrices with this pattern).
  void analyze_pattern(const Eigen::SparseMatrix<double>& A);
  /// Numeric factorisation on the last analysed pattern; false when A is (numerically) singular.
  bool factorize(const Eigen::SparseMatrix<double>& A);
  /// analyze_pattern and factorize.
  bool compute(const Eigen::SparseMatrix<double>& A);
  /// Whether the last factorize() succeeded, and if not, why.
  bool ok() const;
  std::string error_message() const;

  /// x = A^-1 b into a vector of the right size (no allocation when x already has it).
  void solve(const VecX& b, VecX& x) const;
  VecX solve(const VecX& b) const;
  /// X = A^-1 B, one column per column of B (n x 0 for a B without columns).
  MatX solve(const MatX& B) const;
  /// Sign of det A: +1, -1 (0 before a successful factorisation).
  int determinant_sign() const;
  /// Nonzeros of the factors L and U.
  long nonzeros_l() const;
  long nonzeros_u() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pcr
