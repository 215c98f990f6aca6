#include "pcr/solve/bordered_block_lu.hpp"

#include <algorithm>
#include <cmath>

namespace pcr {

namespace {

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

}  // namespace

bool BorderedBlockLu::analyze_pattern(const Eigen::SparseMatrix<double>& A,
                                      const std::vector<int>& column_groups, int max_border) {
  analyzed_ = false;
  groups_.clear();
  slots_.clear();
  error_.clear();
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
  // Row groups: the one group among a row's columns, -1 for none or several (kMixed while scanning).
  constexpr int kNone = -1, kMixed = -2;
  std::vector<int> row_group(n, kNone), row_count(n, 0), column_count(n, 0);
  for (int c = 0; c < n; ++c) {
    const int g = column_groups[c];
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      const int r = static_cast<int>(it.row());
      ++row_count[r];
      ++column_count[c];
      if (g < 0 || row_group[r] == kMixed) continue;
      row_group[r] = row_group[r] == kNone || row_group[r] == g ? g : kMixed;
    }
  }
  std::vector<std::vector<int>> rows(num_groups), columns(num_groups);
  border_rows_.clear();
  border_columns_.clear();
  for (int r = 0; r < n; ++r) {
    if (row_group[r] >= 0)
      rows[row_group[r]].push_back(r);
    else
      border_rows_.push_back(r);
  }
  for (int c = 0; c < n; ++c) {
    if (column_groups[c] >= 0)
      columns[column_groups[c]].push_back(c);
    else
      border_columns_.push_back(c);
  }
  // Square every group: surplus columns (e.g. a rod length) or rows go to the border.
  for (int g = 0; g < num_groups; ++g) {
    const int surplus = static_cast<int>(columns[g].size()) - static_cast<int>(rows[g].size());
    if (surplus > 0) move_densest(columns[g], column_count, surplus, border_columns_);
    if (surplus < 0) move_densest(rows[g], row_count, -surplus, border_rows_);
  }
  std::sort(border_rows_.begin(), border_rows_.end());
  std::sort(border_columns_.begin(), border_columns_.end());
  const int nb = static_cast<int>(border_columns_.size());
  if (nb != static_cast<int>(border_rows_.size()) || nb > max_border) {
    error_ = "BorderedBlockLu: border of " + std::to_string(nb) + " columns and " +
             std::to_string(border_rows_.size()) + " rows";
    return false;
  }

  // Local numbering: group g's columns in ascending order, its rows by (first column, last column).
  std::vector<int> local_column(n, -1), local_row(n, -1), group_of_row(n, -1), group_of_column(n, -1);
  std::vector<int> first(n, n), last(n, -1);
  for (int g = 0; g < num_groups; ++g)
    for (size_t k = 0; k < columns[g].size(); ++k) {
      local_column[columns[g][k]] = static_cast<int>(k);
      group_of_column[columns[g][k]] = g;
    }
  for (int c = 0; c < n; ++c) {
    if (group_of_column[c] < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      const int r = static_cast<int>(it.row());
      first[r] = std::min(first[r], local_column[c]);
      last[r] = std::max(last[r], local_column[c]);
    }
  }
  for (int k = 0; k < nb; ++k) local_column[border_columns_[k]] = k;
  for (int k = 0; k < nb; ++k) local_row[border_rows_[k]] = k;
  for (int g = 0; g < num_groups; ++g) {
    if (rows[g].empty()) continue;
    std::stable_sort(rows[g].begin(), rows[g].end(), [&](int a, int b) {
      return first[a] + last[a] != first[b] + last[b] ? first[a] + last[a] < first[b] + last[b]
                                                      : first[a] < first[b];
    });
    Group group;
    group.rows = rows[g];
    group.columns = columns[g];
    int kl = 0, ku = 0;
    for (size_t k = 0; k < group.rows.size(); ++k) {
      const int r = group.rows[k];
      local_row[r] = static_cast<int>(k);
      group_of_row[r] = static_cast<int>(groups_.size());
      if (last[r] < 0)
        continue;  // a row with no entry in the group: the block is singular (factorize says so)
      kl = std::max(kl, static_cast<int>(k) - first[r]);
      ku = std::max(ku, last[r] - static_cast<int>(k));
    }
    const int ng = static_cast<int>(group.rows.size());
    group.band.resize(ng, kl, ku);
    group.B = MatX::Zero(ng, nb);
    group.Ct = MatX::Zero(ng, nb);
    group.W = MatX::Zero(ng, nb);
    group.z = VecX::Zero(ng);
    for (int c : columns[g]) group_of_column[c] = static_cast<int>(groups_.size());
    groups_.push_back(std::move(group));
  }

  // Where each nonzero goes.
  slots_.reserve(A.nonZeros());
  std::vector<std::vector<bool>> coupled(groups_.size(), std::vector<bool>(nb, false));
  std::vector<std::vector<Group::RowSpan>> spans(groups_.size());  // per group and border row
  for (size_t g = 0; g < groups_.size(); ++g)
    for (int k = 0; k < nb; ++k) spans[g].push_back({k, n, -1});
  for (int c = 0; c < n; ++c) {
    const int gc = group_of_column[c];
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      const int r = static_cast<int>(it.row());
      const int gr = group_of_row[r];
      Slot s{};
      if (gr >= 0 && gc == gr) {
        s = {kBand, gr, groups_[gr].band.index(local_row[r], local_column[c])};
      } else if (gr >= 0 && gc < 0) {
        s = {kB, gr, local_row[r] + local_column[c] * static_cast<int>(groups_[gr].rows.size())};
        coupled[gr][local_column[c]] = true;
      } else if (gr < 0 && gc >= 0) {
        const int ng = static_cast<int>(groups_[gc].rows.size());
        s = {kC, gc, local_column[c] + local_row[r] * ng};
        Group::RowSpan& span = spans[gc][local_row[r]];
        span.begin = std::min(span.begin, local_column[c]);
        span.end = std::max(span.end, local_column[c] + 1);
      } else if (gr < 0 && gc < 0) {
        s = {kD, -1, local_row[r] + local_column[c] * nb};
      } else {  // a group row in another group's column: cannot happen by the row rule above
        error_ = "BorderedBlockLu: internal error in the row groups";
        return false;
      }
      slots_.push_back(s);
    }
  }
  for (size_t g = 0; g < groups_.size(); ++g) {
    for (int k = 0; k < nb; ++k) {
      if (coupled[g][k]) groups_[g].coupled_border.push_back(k);
      if (spans[g][k].begin < spans[g][k].end) groups_[g].coupled_rows.push_back(spans[g][k]);
    }
  }
  S_ = MatX::Zero(nb, nb);
  border_rhs_ = VecX::Zero(nb);
  border_solution_ = VecX::Zero(nb);
  nonzeros_ = A.nonZeros();
  analyzed_ = !groups_.empty();
  if (!analyzed_) error_ = "BorderedBlockLu: no group has rows";
  return analyzed_;
}

bool BorderedBlockLu::factorize(const Eigen::SparseMatrix<double>& A) {
  if (!analyzed_ || A.nonZeros() != nonzeros_) {
    error_ = "BorderedBlockLu: factorize before analyze_pattern or with another pattern";
    return false;
  }
  // B_g, C_g and W_g keep their zeros outside the pattern (only the factorisation writes outside it).
  for (Group& g : groups_) g.band.set_zero();
  S_.setZero();
  const double* values = A.valuePtr();
  for (size_t p = 0; p < slots_.size(); ++p) {
    const Slot& s = slots_[p];
    switch (s.target) {
      case kBand: groups_[s.group].band.data()[s.index] = values[p]; break;
      case kB: groups_[s.group].B.data()[s.index] = values[p]; break;
      case kC: groups_[s.group].Ct.data()[s.index] = values[p]; break;
      default: S_.data()[s.index] = values[p]; break;
    }
  }
  for (size_t g = 0; g < groups_.size(); ++g) {
    Group& group = groups_[g];
    if (!group.band.factorize()) {
      error_ = "BorderedBlockLu: diagonal block " + std::to_string(g) + " is singular";
      return false;
    }
    for (int k : group.coupled_border) {
      group.W.col(k) = group.B.col(k);
      group.band.solve_in_place(group.W.col(k).data());
    }
    if (!group.coupled_border.empty()) S_.noalias() -= group.Ct.transpose() * group.W;
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
  for (int k = 0; k < nb; ++k) border_rhs_[k] = b[border_rows_[k]];
  // Only the nonzero spans of C_g and the coupled columns of W_g (the others are zero).
  for (const Group& g : groups_) {
    for (size_t k = 0; k < g.rows.size(); ++k) g.z[k] = b[g.rows[k]];
    g.band.solve_in_place(g.z.data());
    for (const Group::RowSpan& r : g.coupled_rows) {
      const int length = r.end - r.begin;
      border_rhs_[r.row] -= g.Ct.col(r.row).segment(r.begin, length).dot(g.z.segment(r.begin, length));
    }
  }
  if (nb > 0) border_solution_ = schur_.solve(border_rhs_);
  for (const Group& g : groups_) {
    for (int k : g.coupled_border) g.z -= g.W.col(k) * border_solution_[k];
    for (size_t k = 0; k < g.columns.size(); ++k) x[g.columns[k]] = g.z[k];
  }
  for (int k = 0; k < nb; ++k) x[border_columns_[k]] = border_solution_[k];
}

long BorderedBlockLu::factor_nonzeros() const {
  long count = static_cast<long>(S_.size());
  for (const Group& g : groups_) count += g.band.factor_nonzeros() + g.Ct.size() + g.W.size();
  return count;
}

}  // namespace pcr
