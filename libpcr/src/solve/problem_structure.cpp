// Problem's derived structure (problem_impl.hpp): row layout, Jacobian and Hessian patterns and the
// scatter maps of the blocks, updated by the non-const functions of Problem. Adding a block appends
// to the structure in O(size of the block): the Jacobian rows of a new block come after all others,
// and the Hessian entries a new block adds are appended too when they come after every existing one in
// row-major order (blocks added in variable order, e.g. a banded system); otherwise, and after an
// activity change, the Hessian pattern is marked stale and rebuilt from the blocks when first used (a
// rebuild at every such addition made building an energy model with couplings quadratic in its blocks).
#include <algorithm>
#include <numeric>

#include "pcr/solve/compressed_index.hpp"
#include "problem_impl.hpp"

namespace pcr {

namespace {

/// Global variable index of each local entry of a block touching ids (in the order of ids).
std::vector<int> global_indices(const std::vector<VariableBlock>& variables,
                                const std::vector<VariableId>& ids) {
  std::vector<int> global;
  for (VariableId v : ids)
    for (int i = 0; i < variables[v].size; ++i) global.push_back(variables[v].offset + i);
  return global;
}

/// Position of (row, col) in the compressed pattern, -1 if absent.
int find_entry(const std::vector<int>& outer, const std::vector<int>& inner, int row, int col) {
  return compressed_index(outer.data(), inner.data(), row, col);
}

/// Room for `more` elements at the end of v, at least doubling its capacity when it must grow.
template <typename T>
void grow_capacity(std::vector<T>& v, size_t more) {
  if (v.capacity() < v.size() + more) v.reserve(std::max(v.size() + more, 2 * v.capacity()));
}

}  // namespace

void Problem::Impl::note_scratch(const std::vector<VariableId>& ids, size_t dense) {
  const size_t n = static_cast<size_t>(local_size(ids));
  max_block_variables = std::max(max_block_variables, ids.size());
  max_dense = std::max(max_dense, dense);
  max_square = std::max(max_square, n * n);
}

void Problem::Impl::extend_variables() {
  if (hessian.current && !hessian.stale)
    hessian.outer.resize(num_variables + 1, static_cast<int>(hessian.inner.size()));
}

// Appends the rows of active block b (its row offset already set) to the Jacobian pattern: per row its
// structurally nonzero entries, touched variable blocks by increasing column offset, then columns.
void Problem::Impl::append_jacobian_rows(ResidualId b) {
  const ResidualBlock& block = *residuals[b];
  const auto& ids = block.variables();
  const int nk = static_cast<int>(ids.size()), num_block_rows = block.num_rows();
  std::vector<int> dense_start(nk, 0);  // start of variable k's dense rows x size array
  for (int k = 1; k < nk; ++k)
    dense_start[k] = dense_start[k - 1] + num_block_rows * variables[ids[k - 1]].size;
  std::vector<int> order(nk);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int c) { return variables[ids[a]].offset < variables[ids[c]].offset; });
  std::vector<char> mask(dense_start[nk - 1] + num_block_rows * variables[ids[nk - 1]].size);
  for (int k = 0; k < nk; ++k) block.structural_mask(k, variables[ids[k]].size, mask.data() + dense_start[k]);
  // The arrays grow geometrically (reserving one block's worth at a time would reallocate on every
  // block); the columns are then written in place.
  const size_t count =
      static_cast<size_t>(std::count_if(mask.begin(), mask.end(), [](char m) { return m != 0; }));
  const size_t start = jacobian.inner.size();
  grow_capacity(jacobian.inner, count);
  grow_capacity(jacobian.scatter, count);
  grow_capacity(jacobian.outer, static_cast<size_t>(num_block_rows));
  const size_t scatter_start = jacobian.scatter.size();
  jacobian.inner.resize(start + count);
  jacobian.scatter.resize(scatter_start + count);
  int* inner = jacobian.inner.data();
  std::pair<int, int>* scatter = jacobian.scatter.data() + scatter_start - start;  // indexed by `next`
  int next = static_cast<int>(start);
  for (int r = 0; r < num_block_rows; ++r) {
    for (int k : order) {
      const VariableBlock& v = variables[ids[k]];
      const char* row_mask = mask.data() + dense_start[k] + r * v.size;
      for (int j = 0; j < v.size; ++j) {
        if (!row_mask[j]) continue;
        scatter[next] = {dense_start[k] + r * v.size + j, next};
        inner[next++] = v.offset + j;
      }
    }
    jacobian.outer.push_back(next);
  }
}

void Problem::Impl::add_rows(ResidualId b) {
  const ResidualBlock& block = *residuals[b];
  note_scratch(block.variables(), static_cast<size_t>(block.num_rows()) * local_size(block.variables()));
  if (!active[b]) {
    rows.row_offset.push_back(-1);
    rows.kind_of_block.push_back(-1);
    jacobian.scatter_offset.push_back(static_cast<int>(jacobian.scatter.size()));
    return;
  }
  rows.row_offset.push_back(rows.num_rows);
  rows.num_rows += block.num_rows();
  rows.row_owner.insert(rows.row_owner.end(), block.num_rows(), b);
  auto it = std::find(rows.kinds.begin(), rows.kinds.end(), block.kind());
  rows.kind_of_block.push_back(static_cast<int>(it - rows.kinds.begin()));
  if (it == rows.kinds.end()) rows.kinds.push_back(block.kind());
  append_jacobian_rows(b);
  jacobian.scatter_offset.push_back(static_cast<int>(jacobian.scatter.size()));
}

void Problem::Impl::append_residual(ResidualId b) {
  add_rows(b);
  hessian.residual_map.resize(residuals.size());
  if (!residuals[b]->provides_hessian()) {
    ++blocks_without_hessian;
    hessian.current = false;
  } else if (blocks_without_hessian == 0) {
    update_hessian_after_addition(residuals[b]->variables(), hessian.residual_map[b]);
  }
}

void Problem::Impl::append_objective(int t) {
  const ObjectiveTerm& term = *objectives[t];
  note_scratch(term.variables(), static_cast<size_t>(local_size(term.variables())));
  hessian.objective_map.resize(objectives.size());
  if (!term.provides_hessian()) {
    ++blocks_without_hessian;
    hessian.current = false;
  } else if (blocks_without_hessian == 0) {
    update_hessian_after_addition(term.variables(), hessian.objective_map[t]);
  }
}

void Problem::Impl::rebuild() {
  rows = RowLayout();
  jacobian = JacobianStructure();
  max_block_variables = max_dense = max_square = 1;
  blocks_without_hessian = 0;
  for (size_t b = 0; b < residuals.size(); ++b) {
    add_rows(static_cast<ResidualId>(b));
    if (active[b] && !residuals[b]->provides_hessian()) ++blocks_without_hessian;
  }
  for (const auto& t : objectives) {
    note_scratch(t->variables(), static_cast<size_t>(local_size(t->variables())));
    if (!t->provides_hessian()) ++blocks_without_hessian;
  }
  hessian = HessianStructure();
  hessian.current = blocks_without_hessian == 0;
  hessian.stale = hessian.current;
}

const HessianStructure& Problem::Impl::hessian_pattern() const {
  const std::lock_guard<std::mutex> lock(hessian_mutex.mutex);
  if (hessian.stale) const_cast<Impl*>(this)->rebuild_hessian();  // derived data only, under the lock
  return hessian;
}

// The Hessian pattern from scratch: the lower-triangle entries of every active square, sorted and
// deduplicated, then each block's map by binary search.
void Problem::Impl::rebuild_hessian() {
  std::vector<std::pair<int, int>> entries;  // (row, col)
  auto add_square = [&](const std::vector<VariableId>& ids) {
    const std::vector<int> global = global_indices(variables, ids);
    for (int row : global)
      for (int col : global)
        if (col <= row) entries.emplace_back(row, col);
  };
  for (size_t b = 0; b < residuals.size(); ++b)
    if (active[b]) add_square(residuals[b]->variables());
  for (const auto& t : objectives) add_square(t->variables());
  std::sort(entries.begin(), entries.end());
  entries.erase(std::unique(entries.begin(), entries.end()), entries.end());
  hessian.outer.assign(num_variables + 1, 0);
  hessian.inner.clear();
  for (const auto& [row, col] : entries) {
    ++hessian.outer[row + 1];
    hessian.inner.push_back(col);
  }
  std::partial_sum(hessian.outer.begin(), hessian.outer.end(), hessian.outer.begin());
  hessian.current = true;
  hessian.stale = false;
  hessian.residual_map.assign(residuals.size(), {});
  for (size_t b = 0; b < residuals.size(); ++b)
    if (active[b]) append_hessian_square(residuals[b]->variables(), hessian.residual_map[b]);
  hessian.objective_map.assign(objectives.size(), {});
  for (size_t t = 0; t < objectives.size(); ++t)
    append_hessian_square(objectives[t]->variables(), hessian.objective_map[t]);
}

// Adds the entries of the square over ids that the pattern lacks, if they all come after its last entry
// in row-major order (else returns false, pattern unchanged), and writes the square's map.
bool Problem::Impl::append_hessian_square(const std::vector<VariableId>& ids, std::vector<int>& map) {
  const std::vector<int> global = global_indices(variables, ids);
  const int n = static_cast<int>(global.size());
  std::vector<std::pair<int, int>> missing;
  for (int row : global)
    for (int col : global)
      if (col <= row && find_entry(hessian.outer, hessian.inner, row, col) < 0)
        missing.emplace_back(row, col);
  if (!missing.empty()) {
    std::sort(missing.begin(), missing.end());
    missing.erase(std::unique(missing.begin(), missing.end()), missing.end());
    const int nnz = static_cast<int>(hessian.inner.size());
    if (nnz > 0) {
      const int last_row = static_cast<int>(
          std::upper_bound(hessian.outer.begin(), hessian.outer.end(), nnz - 1) - hessian.outer.begin() - 1);
      if (missing.front() <= std::make_pair(last_row, hessian.inner.back())) return false;
    }
    for (const auto& [row, col] : missing) hessian.inner.push_back(col);
    // Rows from the first one with a new entry on: all their entries are new (or, for that first row,
    // follow the old ones), so their row pointers are the running count.
    size_t next = 0;
    for (int row = missing.front().first; row < num_variables; ++row) {
      int count = 0;
      while (next < missing.size() && missing[next].first == row) ++count, ++next;
      hessian.outer[row + 1] =
          hessian.outer[row] +
          (row == missing.front().first ? hessian.outer[row + 1] - hessian.outer[row] + count : count);
    }
  }
  map.assign(static_cast<size_t>(n) * n, -1);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (global[j] <= global[i])
        map[static_cast<size_t>(i) * n + j] = find_entry(hessian.outer, hessian.inner, global[i], global[j]);
  return true;
}

void Problem::Impl::update_hessian_after_addition(const std::vector<VariableId>& ids, std::vector<int>& map) {
  if (!hessian.current || hessian.stale || !append_hessian_square(ids, map)) hessian.stale = true;
}

}  // namespace pcr
