#include "pcr/solve/bordered_block_lu.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "avx2_clones.hpp"
#include "band_ordering.hpp"

namespace pcr {

namespace {

/// z[i] -= W(i, k) s[k] for i < n and k over `coupled` in order (W column-major, leading dimension ld):
/// four entries of z at a time through all the columns, each entry with the operations of one column
/// after the other (z - W(:, k) s_k per column), so the same bits as column by column.
PCR_AVX2_CLONES void subtract_border_columns(const double* W, int ld, const std::vector<int>& coupled,
                                             const double* s, int n, double* z) {
  const int columns = static_cast<int>(coupled.size());
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    double acc[4] = {z[i], z[i + 1], z[i + 2], z[i + 3]};
    for (int m = 0; m < columns; ++m) {
      const double* w = W + static_cast<std::ptrdiff_t>(coupled[m]) * ld + i;
      const double sk = s[coupled[m]];
      for (int l = 0; l < 4; ++l) acc[l] -= w[l] * sk;
    }
    for (int l = 0; l < 4; ++l) z[i + l] = acc[l];
  }
  for (; i < n; ++i)
    for (int m = 0; m < columns; ++m)
      z[i] -= W[static_cast<std::ptrdiff_t>(coupled[m]) * ld + i] * s[coupled[m]];
}

// Moves the `surplus` entries of `members` with the most nonzeros (count[]) out, into `border`.
void move_densest(std::vector<int>& members, const std::vector<int>& count, int surplus,
                  std::vector<int>& border) {
  std::vector<int> by_count = members;
  std::stable_sort(by_count.begin(), by_count.end(), [&](int a, int b) { return count[a] > count[b]; });
  by_count.resize(surplus);
  for (int k : by_count) border.push_back(k);
  std::sort(by_count.begin(), by_count.end());
  std::vector<int> kept;
  std::set_difference(members.begin(), members.end(), by_count.begin(), by_count.end(),
                      std::back_inserter(kept));
  members.swap(kept);
}

// Wide columns: spanning more than half of the group's rows. They leave only when each spans more than
// twice the median column (in a short rod of high degree every basis function spans most collocation
// points, and the band is the whole rod whatever leaves it), and the group only while they are
// at most this fraction of its rows (in a small group most columns are touched by most rows, and a
// group that kept few columns would be mostly border).
constexpr int kMaxWideFraction = 4;  // wide columns <= rows / 4

}  // namespace

bool BorderedBlockLu::analyze_pattern(const Eigen::SparseMatrix<double>& A,
                                      const std::vector<int>& column_groups, int max_border) {
  analyzed_ = false;
  groups_.clear();
  for (std::vector<Slot>& slots : slots_) slots.clear();
  error_.clear();
  border_rows_.clear();
  border_columns_.clear();
  Partition part;
  if (!partition(A, column_groups, part)) return false;
  square_groups(part);
  move_wide_columns(A, part);
  order_columns_for_narrow_band(A, part.rows, part.columns);
  std::sort(border_rows_.begin(), border_rows_.end());
  std::sort(border_columns_.begin(), border_columns_.end());
  size_t leftover = 0;
  for (size_t g = 0; g < part.rows.size(); ++g) leftover += part.rows[g].size() - part.columns[g].size();
  const int nb = static_cast<int>(border_columns_.size());
  if (static_cast<size_t>(nb) != border_rows_.size() + leftover || nb > max_border) {
    error_ = "BorderedBlockLu: border of " + std::to_string(nb) + " columns and " +
             std::to_string(border_rows_.size() + leftover) + " rows";
    return false;
  }
  build_groups(A, part);
  if (!build_slots(A)) return false;
  S_ = MatX::Zero(nb, nb);
  border_rhs_ = VecX::Zero(nb);
  border_solution_ = VecX::Zero(nb);
  nonzeros_ = A.nonZeros();
  analyzed_ = !groups_.empty();
  if (!analyzed_) error_ = "BorderedBlockLu: no group has rows";
  return analyzed_;
}

// Row groups: the one group among a row's columns, the border for none or several; the columns by
// column_groups. Also the nonzeros per row and column.
bool BorderedBlockLu::partition(const Eigen::SparseMatrix<double>& A, const std::vector<int>& column_groups,
                                Partition& part) {
  const int n = static_cast<int>(A.rows());
  if (A.cols() != n || static_cast<int>(column_groups.size()) != n) {
    error_ = "BorderedBlockLu: matrix not square or column groups of the wrong size";
    return false;
  }
  const int num_groups =
      column_groups.empty() ? 0 : *std::max_element(column_groups.begin(), column_groups.end()) + 1;
  if (num_groups <= 0) {
    error_ = "BorderedBlockLu: no column groups";
    return false;
  }
  part.n = n;
  constexpr int kNone = -1, kMixed = -2;  // row_group while scanning: no group yet, several
  std::vector<int> row_group(n, kNone);
  part.row_count.assign(n, 0);
  part.column_count.assign(n, 0);
  for (int c = 0; c < n; ++c) {
    const int g = column_groups[c];
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      const int r = static_cast<int>(it.row());
      ++part.row_count[r];
      ++part.column_count[c];
      if (g < 0 || row_group[r] == kMixed) continue;
      row_group[r] = row_group[r] == kNone || row_group[r] == g ? g : kMixed;
    }
  }
  part.rows.assign(num_groups, {});
  part.columns.assign(num_groups, {});
  for (int r = 0; r < n; ++r) {
    if (row_group[r] >= 0)
      part.rows[row_group[r]].push_back(r);
    else
      border_rows_.push_back(r);
  }
  for (int c = 0; c < n; ++c) {
    if (column_groups[c] >= 0)
      part.columns[column_groups[c]].push_back(c);
    else
      border_columns_.push_back(c);
  }
  return true;
}

// Square every group: surplus columns (e.g. a rod length) or rows go to the border.
void BorderedBlockLu::square_groups(Partition& part) {
  for (size_t g = 0; g < part.rows.size(); ++g) {
    const int surplus = static_cast<int>(part.columns[g].size()) - static_cast<int>(part.rows[g].size());
    if (surplus > 0) move_densest(part.columns[g], part.column_count, surplus, border_columns_);
    if (surplus < 0) move_densest(part.rows[g], part.row_count, -surplus, border_rows_);
  }
}

// The wide columns of each group (file comment) to the border; the group keeps its rows. A column's
// span: from the first to the last of the group's rows that touch it, the rows in the order of their first
// column.
void BorderedBlockLu::move_wide_columns(const Eigen::SparseMatrix<double>& A, Partition& part) {
  const int n = part.n;
  std::vector<int> group_of_row(n, -1), group_of_column(n, -1), first_column(n, n), position(n, -1);
  for (size_t g = 0; g < part.rows.size(); ++g) {
    for (int r : part.rows[g]) group_of_row[r] = static_cast<int>(g);
    for (int c : part.columns[g]) group_of_column[c] = static_cast<int>(g);
  }
  for (int c = 0; c < n; ++c) {
    if (group_of_column[c] < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it)
      if (group_of_row[it.row()] == group_of_column[c])
        first_column[it.row()] = std::min(first_column[it.row()], c);
  }
  for (const std::vector<int>& rows : part.rows) {
    std::vector<int> ordered = rows;
    std::stable_sort(ordered.begin(), ordered.end(),
                     [&](int a, int b) { return first_column[a] < first_column[b]; });
    for (size_t k = 0; k < ordered.size(); ++k) position[ordered[k]] = static_cast<int>(k);
  }
  std::vector<int> lowest(n, n), highest(n, -1);
  for (int c = 0; c < n; ++c) {
    if (group_of_column[c] < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      if (group_of_row[it.row()] != group_of_column[c]) continue;
      lowest[c] = std::min(lowest[c], position[it.row()]);
      highest[c] = std::max(highest[c], position[it.row()]);
    }
  }
  for (size_t g = 0; g < part.rows.size(); ++g) {
    const int rows = static_cast<int>(part.rows[g].size());
    if (part.columns[g].empty()) continue;
    std::vector<int> spans;
    for (int c : part.columns[g]) spans.push_back(std::max(0, highest[c] - lowest[c] + 1));
    std::vector<int> sorted = spans;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const int median = sorted[sorted.size() / 2];
    // The band narrows only when every column spanning more than half of the rows leaves.
    std::vector<int> wide, kept;
    bool narrows = true;
    for (size_t k = 0; k < spans.size(); ++k) {
      const bool spans_half = 2 * spans[k] > rows;
      narrows = narrows && (!spans_half || spans[k] > 2 * median);
      (spans_half ? wide : kept).push_back(part.columns[g][k]);
    }
    if (!narrows || wide.empty() || kMaxWideFraction * static_cast<int>(wide.size()) > rows) continue;
    border_columns_.insert(border_columns_.end(), wide.begin(), wide.end());
    part.columns[g].swap(kept);
  }
}

// Local numbering: group g's columns in the order of part.columns, its rows by (first column + last
// column) (group_band_widths: rows without a column of the group last), the band widths, the dense
// border parts.
void BorderedBlockLu::build_groups(const Eigen::SparseMatrix<double>& A, const Partition& part) {
  const int n = part.n, nb = static_cast<int>(border_columns_.size());
  local_column_.assign(n, -1);
  local_row_.assign(n, -1);
  group_of_row_.assign(n, -1);
  group_of_column_.assign(n, -1);
  for (const std::vector<int>& columns : part.columns)
    for (size_t k = 0; k < columns.size(); ++k) local_column_[columns[k]] = static_cast<int>(k);
  for (int k = 0; k < nb; ++k) local_column_[border_columns_[k]] = k;
  for (size_t k = 0; k < border_rows_.size(); ++k) local_row_[border_rows_[k]] = static_cast<int>(k);
  int leftover_row = static_cast<int>(border_rows_.size());
  for (size_t g = 0; g < part.rows.size(); ++g) {
    if (part.rows[g].empty()) continue;
    Group group;
    group.columns = part.columns[g];
    // A row with no entry in the group comes last: A_g is singular unless the row is left over.
    const BandWidths widths = group_band_widths(A, part.rows[g], group.columns, &group.rows);
    for (size_t k = 0; k < group.rows.size(); ++k) {
      local_row_[group.rows[k]] = static_cast<int>(k);
      group_of_row_[group.rows[k]] = static_cast<int>(groups_.size());
    }
    for (int c : group.columns) group_of_column_[c] = static_cast<int>(groups_.size());
    const int rows = static_cast<int>(group.rows.size()), columns = static_cast<int>(group.columns.size());
    group.band.reshape(rows, columns, widths.kl, widths.ku);  // the numeric storage: on first factorize
    group.leftover_row = leftover_row;
    leftover_row += rows - columns;
    groups_.push_back(std::move(group));
  }
}

// Where each nonzero of A goes, and which border columns and rows couple to each group.
bool BorderedBlockLu::build_slots(const Eigen::SparseMatrix<double>& A) {
  const int n = static_cast<int>(A.rows()), nb = static_cast<int>(border_columns_.size());
  int value = 0;  // A is compressed: its nonzeros in CSC order
  std::vector<std::vector<bool>> coupled(groups_.size(), std::vector<bool>(nb, false));
  std::vector<std::vector<Group::RowSpan>> spans(groups_.size());  // per group and border row
  for (size_t g = 0; g < groups_.size(); ++g)
    for (int k = 0; k < nb; ++k) spans[g].push_back({k, n, -1});
  for (int c = 0; c < n; ++c) {
    const int gc = group_of_column_[c], column = local_column_[c];
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      const int r = static_cast<int>(it.row());
      const int gr = group_of_row_[r], row = local_row_[r];
      const int v = value++;
      int target = kD;
      Slot s{};
      if (gr >= 0 && gc == gr) {
        target = kBand;
        s = {v, gr, groups_[gr].band.index(row, column)};
      } else if (gr >= 0 && gc < 0) {
        target = kB;
        s = {v, gr, row + column * static_cast<int>(groups_[gr].rows.size())};
        coupled[gr][column] = true;
      } else if (gr < 0 && gc >= 0) {
        target = kC;
        s = {v, gc, column + row * static_cast<int>(groups_[gc].columns.size())};
        Group::RowSpan& span = spans[gc][row];
        span.begin = std::min(span.begin, column);
        span.end = std::max(span.end, column + 1);
      } else if (gr < 0 && gc < 0) {
        s = {v, -1, row + column * nb};
      } else {  // a group row in another group's column: cannot happen by the row rule
        error_ = "BorderedBlockLu: internal error in the row groups";
        return false;
      }
      slots_[target].push_back(s);
    }
  }
  for (size_t g = 0; g < groups_.size(); ++g) {
    for (int k = 0; k < nb; ++k) {
      if (coupled[g][k]) groups_[g].coupled_border.push_back(k);
      if (spans[g][k].begin < spans[g][k].end) groups_[g].coupled_rows.push_back(spans[g][k]);
    }
  }
  return true;
}

bool BorderedBlockLu::factorize(const Eigen::SparseMatrix<double>& A) {
  if (!analyzed_ || A.nonZeros() != nonzeros_) {
    error_ = "BorderedBlockLu: factorize before analyze_pattern or with another pattern";
    return false;
  }
  // B_g and C_g keep their zeros outside the pattern (only the factorisation writes outside it). The
  // numeric storage is made here the first time: an analysed pattern carries none (cheap to copy).
  const int nb = static_cast<int>(border_columns_.size());
  for (Group& g : groups_) {
    if (!g.has_storage) {
      g.B = MatX::Zero(g.rows.size(), nb);
      g.Ct = MatX::Zero(g.columns.size(), nb);
      g.W = MatX::Zero(g.rows.size(), nb);
      g.z = VecX::Zero(g.rows.size());
      g.has_storage = true;
    }
    g.band.set_zero();
  }
  S_.setZero();
  const double* values = A.valuePtr();
  for (const Slot& s : slots_[kBand]) groups_[s.group].band.data()[s.index] = values[s.value];
  for (const Slot& s : slots_[kB]) groups_[s.group].B.data()[s.index] = values[s.value];
  for (const Slot& s : slots_[kC]) groups_[s.group].Ct.data()[s.index] = values[s.value];
  for (const Slot& s : slots_[kD]) S_.data()[s.index] = values[s.value];
  for (size_t g = 0; g < groups_.size(); ++g) {
    Group& group = groups_[g];
    if (!group.band.factorize()) {
      error_ = "BorderedBlockLu: diagonal block " + std::to_string(g) + " is singular";
      return false;
    }
    const int columns = static_cast<int>(group.columns.size()), leftover = group.leftover();
    // W_g = U^-1 G_1 and the leftover rows' G_2 (a row of S each); S -= C_g W_g over the spans of C_g.
    for (int k : group.coupled_border) {
      group.W.col(k) = group.B.col(k);
      group.band.solve_in_place(group.W.col(k).data());
      for (int i = 0; i < leftover; ++i) S_(group.leftover_row + i, k) = group.W(columns + i, k);
      for (const Group::RowSpan& r : group.coupled_rows) {
        const int length = r.end - r.begin;
        S_(r.row, k) -=
            group.Ct.col(r.row).segment(r.begin, length).dot(group.W.col(k).segment(r.begin, length));
      }
    }
  }
  if (S_.size() > 0) {
    schur_.compute(S_);
    const auto& lu = schur_.matrixLU();
    for (int k = 0; k < lu.rows(); ++k) {
      if (!(std::abs(lu(k, k)) > 0.0) || !std::isfinite(lu(k, k))) {
        error_ = "BorderedBlockLu: the Schur complement on the border is singular";
        return false;
      }
    }
  }
  return true;
}

void BorderedBlockLu::solve(const VecX& b, VecX& x) const {
  x.resize(b.size());
  const int nb = static_cast<int>(border_columns_.size());
  for (size_t k = 0; k < border_rows_.size(); ++k) border_rhs_[k] = b[border_rows_[k]];
  // Only the nonzero spans of C_g and the coupled columns of W_g (the others are zero).
  for (const Group& g : groups_) {
    const int columns = static_cast<int>(g.columns.size());
    for (size_t k = 0; k < g.rows.size(); ++k) g.z[k] = b[g.rows[k]];
    g.band.solve_in_place(g.z.data());
    for (int i = 0; i < g.leftover(); ++i) border_rhs_[g.leftover_row + i] = g.z[columns + i];
    for (const Group::RowSpan& r : g.coupled_rows) {
      const int length = r.end - r.begin;
      border_rhs_[r.row] -= g.Ct.col(r.row).segment(r.begin, length).dot(g.z.segment(r.begin, length));
    }
  }
  if (nb > 0) border_solution_ = schur_.solve(border_rhs_);
  for (const Group& g : groups_) {
    const int columns = static_cast<int>(g.columns.size());
    subtract_border_columns(g.W.data(), static_cast<int>(g.W.rows()), g.coupled_border,
                            border_solution_.data(), columns, g.z.data());
    for (int k = 0; k < columns; ++k) x[g.columns[k]] = g.z[k];
  }
  for (int k = 0; k < nb; ++k) x[border_columns_[k]] = border_solution_[k];
}

int BorderedBlockLu::wide_columns() const {
  int count = 0;
  for (const Group& g : groups_) count += g.leftover();
  return count;
}

long BorderedBlockLu::factor_nonzeros() const {
  long count = static_cast<long>(S_.size());
  const long nb = static_cast<long>(border_columns_.size());  // Ct: columns x nb, W: rows x nb
  for (const Group& g : groups_)
    count += g.band.factor_nonzeros() + static_cast<long>(g.columns.size() + g.rows.size()) * nb;
  return count;
}

}  // namespace pcr
