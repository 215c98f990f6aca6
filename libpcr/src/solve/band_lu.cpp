#include "pcr/solve/band_lu.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "avx2_clones.hpp"

// The factorisation's and the solves' inner loops (axpy over a column of the band) are compiled for AVX2
// as well (avx2_clones.hpp).

namespace pcr {

void BandLu::resize(int rows, int cols, int kl, int ku) {
  reshape(rows, cols, kl, ku);
  set_zero();
}

void BandLu::reshape(int rows, int cols, int kl, int ku) {
  rows_ = rows;
  cols_ = cols;
  kl_ = kl;
  ku_ = ku;
  ld_ = 2 * kl + ku + 1;
  ab_.clear();
  pivot_.assign(cols, 0);
  l_rows_.assign(cols, 0);
  u_first_.assign(cols, 0);
}

void BandLu::set_zero() {
  const size_t size = static_cast<size_t>(ld_) * cols_;
  if (ab_.size() != size)
    ab_.assign(size, 0.0);
  else
    std::fill(ab_.begin(), ab_.end(), 0.0);
}

// dgbtf2: column j picks the largest of its kl entries below the diagonal as pivot, swaps that row
// into place over the columns the pivot row reaches, scales the multipliers and updates the trailing
// columns j + 1 .. ju with a rank-one update (skipped where U(j, c) = 0: much of the band is
// structurally zero for collocation matrices). A tall matrix: the same over its cols columns, the pivot
// candidates running down to its last row.
PCR_AVX2_CLONES bool BandLu::factorize() {
  const int kv = kl_ + ku_;
  double* a = ab_.data();
  int ju = 0;  // last column touched by the pivot rows so far
  for (int j = 0; j < cols_; ++j) {
    const int km = std::min(kl_, rows_ - 1 - j);
    double* col = a + j * ld_ + kv;  // col[k] = A(j + k, j)
    int jp = 0;
    double best = std::abs(col[0]);
    for (int k = 1; k <= km; ++k) {
      if (std::abs(col[k]) > best) {
        best = std::abs(col[k]);
        jp = k;
      }
    }
    pivot_[j] = j + jp;
    if (!(best > 0.0) || !std::isfinite(best)) return false;
    ju = std::max(ju, std::min(j + ku_ + jp, cols_ - 1));
    if (jp != 0) {
      for (int c = j; c <= ju; ++c) std::swap(a[c * ld_ + kv + j - c], a[c * ld_ + kv + j + jp - c]);
    }
    const double inverse = 1.0 / col[0];
    for (int k = 1; k <= km; ++k) col[k] *= inverse;
    int rows = km;  // the multipliers' extent: the band below the diagonal is often not full
    while (rows > 0 && col[rows] == 0.0) --rows;
    for (int c = j + 1; c <= ju; ++c) {
      double* target = a + c * ld_ + kv + j - c;  // target[0] = A(j, c), target[k] = A(j + k, c)
      const double u = target[0];
      if (u == 0.0) continue;
      for (int k = 1; k <= rows; ++k) target[k] -= u * col[k];
    }
  }
  // Actual extents of the factors' columns, for the solves.
  for (int j = 0; j < cols_; ++j) {
    const double* col = a + j * ld_ + kv;
    int rows = std::min(kl_, rows_ - 1 - j);
    while (rows > 0 && col[rows] == 0.0) --rows;
    l_rows_[j] = rows;
    int first = std::max(0, j - kv);
    while (first < j && a[j * ld_ + kv + first - j] == 0.0) ++first;
    u_first_[j] = first;
  }
  return true;
}

PCR_AVX2_CLONES void BandLu::solve_in_place(double* b) const {
  const int kv = kl_ + ku_;
  const double* a = ab_.data();
  for (int j = 0; j < cols_; ++j) {  // [L1 0; L2 I] g = P b
    const int p = pivot_[j];
    if (p != j) std::swap(b[j], b[p]);
    const double bj = b[j];
    if (bj == 0.0) continue;
    const double* col = a + j * ld_ + kv;
    const int rows = l_rows_[j];
#pragma GCC unroll 4
    for (int k = 1; k <= rows; ++k) b[j + k] -= bj * col[k];
  }
  // U x = g_1, two columns j and k = j - 1 at a time: x_j, then x_k (after column j's entry in row k),
  // then rows above both in one pass over b. Each b[i] takes the same operations in the same order as
  // column by column (b[i] - x_j U(i, j) - x_k U(i, k)), so the result is the same to the bit.
  int j = cols_ - 1;
  for (; j >= 1; j -= 2) {
    const int k = j - 1;
    const double* cj = a + j * ld_ + kv - j;  // cj[i] = U(i, j)
    const double* ck = a + k * ld_ + kv - k;  // ck[i] = U(i, k)
    b[j] /= cj[j];
    const double xj = b[j];
    const int fj = u_first_[j], fk = u_first_[k];
    if (xj != 0.0 && fj <= k) b[k] -= xj * cj[k];
    b[k] /= ck[k];
    const double xk = b[k];
    const bool use_j = xj != 0.0 && fj < k, use_k = xk != 0.0 && fk < k;
    if (use_j && use_k) {
      const int both = std::max(fj, fk);
      for (int i = fj; i < both; ++i) b[i] -= xj * cj[i];  // rows only column j reaches
      for (int i = fk; i < both; ++i) b[i] -= xk * ck[i];  // rows only column k reaches
#pragma GCC unroll 4
      for (int i = both; i < k; ++i) b[i] = b[i] - xj * cj[i] - xk * ck[i];
    } else if (use_j) {
      for (int i = fj; i < k; ++i) b[i] -= xj * cj[i];
    } else if (use_k) {
      for (int i = fk; i < k; ++i) b[i] -= xk * ck[i];
    }
  }
  if (j == 0) b[0] /= a[kv];  // the first column left over (an odd count)
}

int BandLu::determinant_sign() const {
  const int kv = kl_ + ku_;
  int sign = 1;
  for (int j = 0; j < cols_; ++j) {
    if (pivot_[j] != j) sign = -sign;
    if (ab_[j * ld_ + kv] < 0.0) sign = -sign;
  }
  return sign;
}

long BandLu::factor_nonzeros() const {
  long count = 0;
  for (int j = 0; j < cols_; ++j) count += l_rows_[j] + (j - u_first_[j] + 1);
  return count;
}

}  // namespace pcr
