#pragma once
// Direct solver for square sparse systems with bordered block-diagonal structure: the unknowns fall
// into groups (one rod's control points, say) whose rows touch no other group, plus a small border
// (platform poses, inputs) whose rows and columns couple the groups:
//
//   [ A_1          B_1 ] [x_1]   [b_1]
//   [      ...     ... ] [...] = [...]
//   [          A_G B_G ] [x_G]   [b_G]
//   [ C_1  ... C_G  D  ] [ y ]   [b_y]
//
// Static condensation (Schur complement): each A_g is factored by a band LU (BandLu; rows ordered by
// their first and last column, so a rod's collocation rows form a band of about (p + 1) x 13 columns),
// W_g = A_g^-1 B_g, S = D - sum_g C_g W_g (dense, border x border), then per solve
//   z_g = A_g^-1 b_g,  S y = b_y - sum_g C_g z_g,  x_g = z_g - W_g y.
// Against a general sparse LU this keeps every inner loop a contiguous column operation and costs
// work linear in the number of groups.
//
// Groups come from the caller (Problem variable groups); a row belongs to group g when all its
// nonzero columns are in g or the border, else to the border. A group with more columns than rows
// (a rod whose length is an unknown) gives its densest surplus columns to the border, one with more
// rows than columns its densest surplus rows. A group's columns keep the Problem's order unless a
// barycentric order makes the band LU cheaper (variables added after a rod's control points but coupled
// to a few of them, e.g. contact forces; src/solve/band_ordering.hpp).
//
// Wide columns: a group column that more than half of the group's rows touch (the constant wrench
// [n, h] of a condensed rod, read by every field row) would widen the band to the whole group, at a
// cost growing with the square of its size. Such columns (at most a quarter of the group's) go to the
// border; the group keeps all its rows, so A_g is tall (k more rows than columns), factored by the
// band LU with partial pivoting as P A_g = [L1; L2] U, and the k rows that the pivoting leaves over
// join the Schur complement: with G = [L1 0; L2 I]^-1 P B_g and g = [L1 0; L2 I]^-1 P b_g split into
// their first n_g - k and last k rows, W_g = U^-1 G_1, z_g = U^-1 g_1, and the leftover rows add
// G_2 y = g_2 to the border system. The pivoting picks them numerically (for a condensed rod clamped
// at its base: typically 6 of its tip's rows, the structure of a shooting method), so no row has to
// be named in advance.
//
// The solve fails (factorize() returns false) when a block A_g or S is singular even if the whole
// matrix is not (e.g. a rod that buckles with both ends held): callers fall back to a general sparse
// LU then.
//
// Not thread-safe: solve() uses scratch buffers of the object.
#include <Eigen/SparseCore>
#include <array>
#include <string>
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/solve/band_lu.hpp"

namespace pcr {

class BorderedBlockLu {
 public:
  /// Analyses A's pattern with column_groups[c] = group of column c (>= 0) or -1 (border).
  /// Returns false (and the solver is unusable) when the pattern has no such structure: no group,
  /// or a border larger than max_border.
  bool analyze_pattern(const Eigen::SparseMatrix<double>& A, const std::vector<int>& column_groups,
                       int max_border = 200);
  /// Numeric factorisation of a matrix with the analysed pattern (the same nonzero positions in the
  /// same order); false when a block or the Schur complement is singular (error_message() says which).
  bool factorize(const Eigen::SparseMatrix<double>& A);
  /// x = A^-1 b after a successful factorize().
  void solve(const VecX& b, VecX& x) const;
  const std::string& error_message() const { return error_; }

  bool analyzed() const { return analyzed_; }
  int num_groups() const { return static_cast<int>(groups_.size()); }
  /// Border columns, the wide columns moved out of the groups included.
  int border_size() const { return static_cast<int>(border_columns_.size()); }
  /// Wide columns moved from the groups to the border (see the file comment).
  int wide_columns() const;
  /// Nonzeros of the band factors (all groups) plus the dense border parts W_g, C_g and S.
  long factor_nonzeros() const;

 private:
  struct Group {
    std::vector<int> rows, columns;  // global indices, in local order (columns: the band's, not the wide)
    BandLu band;                     // rows.size() x columns.size(), tall when wide columns left
    int leftover_row = 0;            // first Schur complement row of the rows left over by the band
    MatX B, Ct, W;                   // B, W: n_rows x nb; Ct = C_g^T: n_columns x nb (border row k: column k)
    std::vector<int> coupled_border;  // border columns with a nonzero in B
    // Border rows k with a nonzero in C_g and the span [begin, end) of their nonzero group columns.
    struct RowSpan {
      int row, begin, end;
    };
    std::vector<RowSpan> coupled_rows;
    mutable VecX z;
    bool has_storage = false;  // B, Ct, W, z sized (by the first factorize)
    int leftover() const { return static_cast<int>(rows.size() - columns.size()); }
  };
  enum Target { kBand, kB, kC, kD, kTargets };
  struct Slot {
    int value;  // position of the nonzero in A's values (CSC order)
    int group;
    int index;  // position in the target's storage
  };
  // The pattern's rows and columns per group while analyze_pattern builds groups_ (global indices).
  struct Partition {
    int n = 0;
    std::vector<std::vector<int>> rows, columns;
    std::vector<int> row_count, column_count;  // nonzeros per row and column of A
  };

  bool partition(const Eigen::SparseMatrix<double>& A, const std::vector<int>& column_groups,
                 Partition& part);
  void square_groups(Partition& part);
  void move_wide_columns(const Eigen::SparseMatrix<double>& A, Partition& part);
  void build_groups(const Eigen::SparseMatrix<double>& A, const Partition& part);
  bool build_slots(const Eigen::SparseMatrix<double>& A);

  std::vector<Group> groups_;
  std::vector<int> border_rows_, border_columns_;  // border_rows_: the rows of A in the border
  // Scatter maps of analyze_pattern: local index of each row and column of A in its group or border.
  std::vector<int> local_row_, local_column_, group_of_row_, group_of_column_;
  MatX S_;  // the border block D, then D - sum_g C_g W_g; rows: border_rows_, then the leftover rows
  Eigen::PartialPivLU<MatX> schur_;
  // Where each nonzero of A goes, listed per target (one loop each in factorize, no branch per entry).
  std::array<std::vector<Slot>, kTargets> slots_;
  long nonzeros_ = 0;
  bool analyzed_ = false;
  std::string error_;
  mutable VecX border_rhs_, border_solution_;
};

}  // namespace pcr
