#pragma once
// Column order of BorderedBlockLu's groups for a narrow band (internal header of pcr's solvers).
//
// A group's columns come in the order of the Problem's variables. For a rod that is one control point
// after the other - a band of about (p + 1) x 13 columns - except for variables added after all control
// points but coupled to a few of them only: the contact forces and complementarity multipliers at each
// midpoint of a rod in contact (rods/src/contact/contact_block.cpp). In that order a midpoint's rows touch
// its control points and columns at the group's end, and the band spans most of the rod (a 506-column rod
// with 24 elements in contact: kl = 230, ku = 267; the band LU costs about 2 n kl (kl + ku) flops).
//
// The barycentric order puts each column where its rows are: a row's centre is the median of its
// columns' positions, a column's key the median of its rows' centres, columns sorted by (key, position).
// A contact force at a midpoint then sits among that midpoint's control points (the rod above: kl = 87,
// ku = 99; a cold FK of models/planar_post.urdf that takes 1,130 Newton iterations: 2.5 -> 1.66 s CPU).
// Kept only where it at least halves the estimate kl (kl + ku) of the band LU's cost, the rows ordered
// as BorderedBlockLu orders them: the estimate ignores the structural zeros the factorisation skips. On a
// short condensed rod (14 control points; its constant wrench, read by every field row, stays in the
// group) the order moves the wrench from the group's end to its middle, kl, ku = 67, 94 -> 63, 48, yet
// the warm R5b path takes 1.6 % more instructions (callgrind, bench_time_split r5b_path): there the
// Problem's order stays, and so the factorisation to the bit.
#include <Eigen/SparseCore>
#include <vector>

namespace pcr {

struct BandWidths {
  int kl = 0, ku = 0;
};

/// The band LU's flops over 2 n: kl (kl + ku) (band_lu.hpp), the estimate the order is chosen by.
inline long factorization_cost(const BandWidths& w) {
  return static_cast<long>(w.kl) * (w.kl + w.ku);
}

/// kl and ku of the group with these rows and columns (global indices; local columns in the given
/// order) when its rows are ordered by the sum of their first and last local column, then the first
/// (stable: ties keep the order of `rows`), rows without a column of the group last: BorderedBlockLu's
/// row order, written to *ordered_rows when given.
BandWidths group_band_widths(const Eigen::SparseMatrix<double>& A, const std::vector<int>& rows,
                             const std::vector<int>& columns, std::vector<int>* ordered_rows = nullptr);

/// Reorders each group's columns (columns[g], global indices; rows[g] the group's rows) by the
/// barycentric order where it at least halves the band LU's cost estimate (file comment).
void order_columns_for_narrow_band(const Eigen::SparseMatrix<double>& A,
                                   const std::vector<std::vector<int>>& rows,
                                   std::vector<std::vector<int>>& columns);

}  // namespace pcr
