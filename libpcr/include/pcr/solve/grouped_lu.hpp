#pragma once
// LU of a sequence of square matrices with one fixed pattern whose columns come in variable groups (the
// rods' control points: bands) and a border: BorderedBlockLu where the pattern has that structure and a
// block is regular, the sparse LU otherwise (a singular block, e.g. at a fold of a rod's own system). Each
// solver analyses the pattern once, when it is first used. For the systems built beside the Newton
// solver's (the pseudo-arclength corrector's bordered matrix, the damped FK system of the snaps).
#include <Eigen/SparseCore>
#include <utility>
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/solve/bordered_block_lu.hpp"
#include "pcr/solve/sparse_lu.hpp"

namespace pcr {

class GroupedLu {
 public:
  /// column_groups[c]: the variable group of column c (>= 0), or -1 for a border column.
  explicit GroupedLu(std::vector<int> column_groups = {}) : groups_(std::move(column_groups)) {}
  void set_column_groups(std::vector<int> column_groups) { *this = GroupedLu(std::move(column_groups)); }

  /// Factorises A (the pattern of the first A given, as every later one); false when it is singular.
  bool factorize(const Eigen::SparseMatrix<double>& A) {
    if (!blocks_analyzed_) {
      blocks_analyzed_ = true;
      blocks_ok_ = blocks_.analyze_pattern(A, groups_);
    }
    use_sparse_ = !(blocks_ok_ && blocks_.factorize(A));
    if (!use_sparse_) return true;
    if (!sparse_analyzed_) {
      sparse_analyzed_ = true;
      sparse_.analyze_pattern(A);
    }
    return sparse_.factorize(A);
  }
  /// x = A^-1 b after a successful factorize().
  void solve(const VecX& b, VecX& x) const {
    if (use_sparse_)
      sparse_.solve(b, x);
    else
      blocks_.solve(b, x);
  }
  VecX solve(const VecX& b) const {
    VecX x;
    solve(b, x);
    return x;
  }

 private:
  std::vector<int> groups_;
  BorderedBlockLu blocks_;
  SparseLu sparse_;
  bool blocks_ok_ = false, blocks_analyzed_ = false, sparse_analyzed_ = false, use_sparse_ = false;
};

}  // namespace pcr
