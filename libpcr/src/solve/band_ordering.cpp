// Column order of BorderedBlockLu's groups for a narrow band (band_ordering.hpp).
#include "band_ordering.hpp"

#include <algorithm>
#include <numeric>

namespace pcr {

namespace {

/// Median of a non-empty list (the lower one of an even count), reordering it.
int median(std::vector<int>& values) {
  const size_t middle = (values.size() - 1) / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<long>(middle), values.end());
  return values[middle];
}

/// The barycentric order of one group (file comment of the header): row_centre[r] is the median
/// position of row r's columns in `columns`.
std::vector<int> barycentric_order(const Eigen::SparseMatrix<double>& A, const std::vector<int>& columns,
                                   const std::vector<int>& group_of_row, int group,
                                   const std::vector<int>& row_centre) {
  const int count = static_cast<int>(columns.size());
  std::vector<int> key(count, 0);
  std::vector<int> centres;
  for (int k = 0; k < count; ++k) {
    centres.clear();
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, columns[k]); it; ++it)
      if (group_of_row[it.row()] == group) centres.push_back(row_centre[it.row()]);
    key[k] = centres.empty() ? k : median(centres);
  }
  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  std::vector<int> reordered(count);
  for (int k = 0; k < count; ++k) reordered[k] = columns[order[k]];
  return reordered;
}

}  // namespace

BandWidths group_band_widths(const Eigen::SparseMatrix<double>& A, const std::vector<int>& rows,
                             const std::vector<int>& columns, std::vector<int>* ordered_rows) {
  const int n = static_cast<int>(A.rows()), none = n;
  std::vector<int> local(n, -1), first(n, none), last(n, none), in_group(n, 0);
  for (size_t k = 0; k < columns.size(); ++k) local[columns[k]] = static_cast<int>(k);
  for (int r : rows) in_group[r] = 1;
  for (int c : columns) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      const int r = static_cast<int>(it.row());
      if (!in_group[r]) continue;
      first[r] = std::min(first[r], local[c]);
      last[r] = last[r] == none ? local[c] : std::max(last[r], local[c]);
    }
  }
  std::vector<int> ordered = rows;
  std::stable_sort(ordered.begin(), ordered.end(), [&](int a, int b) {
    return first[a] + last[a] != first[b] + last[b] ? first[a] + last[a] < first[b] + last[b]
                                                    : first[a] < first[b];
  });
  BandWidths w;
  for (size_t k = 0; k < ordered.size(); ++k) {
    const int r = ordered[k];
    if (first[r] == none) continue;
    w.kl = std::max(w.kl, static_cast<int>(k) - first[r]);
    w.ku = std::max(w.ku, last[r] - static_cast<int>(k));
  }
  if (ordered_rows) ordered_rows->swap(ordered);
  return w;
}

void order_columns_for_narrow_band(const Eigen::SparseMatrix<double>& A,
                                   const std::vector<std::vector<int>>& rows,
                                   std::vector<std::vector<int>>& columns) {
  const int n = static_cast<int>(A.rows());
  std::vector<int> group_of_row(n, -1), position(n, -1);
  for (size_t g = 0; g < rows.size(); ++g)
    for (int r : rows[g]) group_of_row[r] = static_cast<int>(g);
  std::vector<std::vector<int>> row_positions(n);  // positions of each group row's group columns
  for (size_t g = 0; g < columns.size(); ++g) {
    for (size_t k = 0; k < columns[g].size(); ++k) {
      const int c = columns[g][k];
      position[c] = static_cast<int>(k);
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it)
        if (group_of_row[it.row()] == static_cast<int>(g)) row_positions[it.row()].push_back(position[c]);
    }
  }
  std::vector<int> row_centre(n, 0);
  for (int r = 0; r < n; ++r)
    if (!row_positions[r].empty()) row_centre[r] = median(row_positions[r]);
  for (size_t g = 0; g < columns.size(); ++g) {
    if (columns[g].size() < 2) continue;
    std::vector<int> reordered =
        barycentric_order(A, columns[g], group_of_row, static_cast<int>(g), row_centre);
    const BandWidths before = group_band_widths(A, rows[g], columns[g]);
    const BandWidths after = group_band_widths(A, rows[g], reordered);
    if (2 * factorization_cost(after) < factorization_cost(before)) columns[g].swap(reordered);
  }
}

}  // namespace pcr
