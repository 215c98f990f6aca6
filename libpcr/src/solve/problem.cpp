// Problem assembly: block bookkeeping, the fixed Jacobian / Hessian patterns and their evaluation.
#include "pcr/solve/problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "pcr/core/error.hpp"

namespace pcr {

namespace {

using SparseRowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Builds a compressed row-major matrix with the given row pointers and column indices (values zero).
SparseRowMajor make_pattern(int rows, int cols, const std::vector<int>& outer,
                            const std::vector<int>& inner) {
  std::vector<double> zeros(inner.size(), 0.0);
  Eigen::Map<const SparseRowMajor> map(rows, cols, static_cast<int>(inner.size()), outer.data(), inner.data(),
                                       zeros.data());
  return SparseRowMajor(map);
}

// True when M already has exactly the pattern P (sizes and row pointers; column indices are written only
// by this class, so equal row pointers of a compressed matrix built here mean the same pattern).
bool same_pattern(const SparseRowMajor& M, const SparseRowMajor& P) {
  if (M.rows() != P.rows() || M.cols() != P.cols() || M.nonZeros() != P.nonZeros() || !M.isCompressed()) {
    return false;
  }
  return std::equal(P.outerIndexPtr(), P.outerIndexPtr() + P.rows() + 1, M.outerIndexPtr()) &&
         std::equal(P.innerIndexPtr(), P.innerIndexPtr() + P.nonZeros(), M.innerIndexPtr());
}

}  // namespace

struct Problem::Impl {
  std::vector<VariableBlock> variables;
  std::vector<char> fixed;
  int num_variables = 0;
  std::vector<std::shared_ptr<const ResidualBlock>> residuals;
  std::vector<char> active;
  std::vector<std::shared_ptr<const ObjectiveTerm>> objectives;
  std::uint64_t version = 1;  // bumped by every structural change

  // ---- Derived structure, rebuilt lazily when built_version != version (mutable cache). ----
  std::uint64_t built_version = 0;
  int num_rows = 0;
  std::vector<int> row_offset;     // per residual block, -1 when inactive
  std::vector<int> row_owner;      // per row, its residual block
  std::vector<int> kind_of_block;  // per residual block, index into kinds (-1 when inactive)
  std::vector<std::string> kinds;  // kinds of active blocks in order of first appearance
  SparseRowMajor jacobian_pattern;
  // Scatter of each block's dense Jacobians into J: pairs (index in the block's stacked dense
  // row-major Jacobians, index into J's values), for the structurally nonzero entries, from
  // jacobian_scatter[jacobian_scatter_offset[b]] to jacobian_scatter[jacobian_scatter_offset[b + 1]].
  std::vector<int> jacobian_scatter_offset;
  std::vector<std::pair<int, int>> jacobian_scatter;
  // Scratch (sized to the largest block): value pointers, Jacobian pointers, dense Jacobian buffer.
  std::vector<const double*> value_ptrs;
  std::vector<double*> derivative_ptrs;
  std::vector<double> dense_scratch;

  // Hessian structure (built on first use after a structural change).
  std::uint64_t hessian_built_version = 0;
  SparseRowMajor hessian_pattern;
  // Per active residual block / objective term: position in H of each local (i, j) entry, -1 if the
  // entry lies in the strict upper triangle.
  std::vector<std::vector<int>> residual_hessian_map, objective_hessian_map;

  int local_size(const std::vector<VariableId>& ids) const {
    int n = 0;
    for (VariableId v : ids) n += variables[v].size;
    return n;
  }
  void check_variable(VariableId id, const char* what) const {
    require(id >= 0 && id < static_cast<int>(variables.size()), what, ": variable id ", id,
            " out of range [0, ", variables.size(), ")");
  }
  void ensure_structure();
  void ensure_hessian_structure();
};

void Problem::Impl::ensure_structure() {
  if (built_version == version) return;
  const int nb = static_cast<int>(residuals.size());
  row_offset.assign(nb, -1);
  kind_of_block.assign(nb, -1);
  kinds.clear();
  row_owner.clear();
  num_rows = 0;
  size_t max_vars = 1, max_dense = 1;
  for (const auto& t : objectives) {
    max_vars = std::max(max_vars, t->variables().size());
    max_dense = std::max(max_dense, static_cast<size_t>(local_size(t->variables())));
  }
  for (int b = 0; b < nb; ++b) {
    const ResidualBlock& block = *residuals[b];
    max_vars = std::max(max_vars, block.variables().size());
    max_dense = std::max(max_dense, static_cast<size_t>(block.num_rows()) * local_size(block.variables()));
    if (!active[b]) continue;
    row_offset[b] = num_rows;
    num_rows += block.num_rows();
    row_owner.insert(row_owner.end(), block.num_rows(), b);
    auto it = std::find(kinds.begin(), kinds.end(), block.kind());
    kind_of_block[b] = static_cast<int>(it - kinds.begin());
    if (it == kinds.end()) kinds.push_back(block.kind());
  }
  value_ptrs.assign(max_vars, nullptr);
  derivative_ptrs.assign(max_vars, nullptr);
  dense_scratch.assign(max_dense, 0.0);

  // Per active block: its structurally nonzero entries (dense index, row, column), in the order of a
  // compressed row (touched variable blocks by increasing column offset, then columns).
  struct Entry {
    int dense, row, col;
  };
  std::vector<std::vector<Entry>> entries(nb);
  std::vector<int> outer(num_rows + 1, 0);
  for (int b = 0; b < nb; ++b) {
    if (!active[b]) continue;
    const ResidualBlock& block = *residuals[b];
    const auto& ids = block.variables();
    const int nk = static_cast<int>(ids.size()), rows = block.num_rows();
    std::vector<int> dense_start(nk, 0);  // start of variable k's dense rows x size array
    for (int k = 1; k < nk; ++k) dense_start[k] = dense_start[k - 1] + rows * variables[ids[k - 1]].size;
    std::vector<int> order(nk);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](int a, int c) { return variables[ids[a]].offset < variables[ids[c]].offset; });
    std::vector<char> mask(dense_start[nk - 1] + rows * variables[ids[nk - 1]].size);
    for (int k = 0; k < nk; ++k)
      block.structural_mask(k, variables[ids[k]].size, mask.data() + dense_start[k]);
    for (int r = 0; r < rows; ++r)
      for (int k : order) {
        const VariableBlock& v = variables[ids[k]];
        for (int j = 0; j < v.size; ++j) {
          if (!mask[dense_start[k] + r * v.size + j]) continue;
          entries[b].push_back({dense_start[k] + r * v.size + j, row_offset[b] + r, v.offset + j});
          ++outer[row_offset[b] + r + 1];
        }
      }
  }
  std::partial_sum(outer.begin(), outer.end(), outer.begin());
  std::vector<int> inner(outer.back());
  jacobian_scatter_offset.assign(nb + 1, 0);
  jacobian_scatter.clear();
  jacobian_scatter.reserve(outer.back());
  std::vector<int> next(outer.begin(), outer.end() - 1);  // next free slot of each row
  for (int b = 0; b < nb; ++b) {
    jacobian_scatter_offset[b] = static_cast<int>(jacobian_scatter.size());
    for (const Entry& e : entries[b]) {
      const int position = next[e.row]++;
      inner[position] = e.col;
      jacobian_scatter.emplace_back(e.dense, position);
    }
  }
  jacobian_scatter_offset[nb] = static_cast<int>(jacobian_scatter.size());
  jacobian_pattern = make_pattern(num_rows, num_variables, outer, inner);
  built_version = version;
}

void Problem::Impl::ensure_hessian_structure() {
  ensure_structure();
  if (hessian_built_version == version) return;
  // Collects the lower-triangle entries of every block's dense touched-variable square, then dedups.
  std::vector<Eigen::Triplet<double>> entries;
  auto add_square = [&](const std::vector<VariableId>& ids) {
    for (VariableId a : ids) {
      for (VariableId c : ids) {
        const VariableBlock &va = variables[a], &vc = variables[c];
        for (int i = 0; i < va.size; ++i) {
          for (int j = 0; j < vc.size; ++j) {
            if (vc.offset + j <= va.offset + i) entries.emplace_back(va.offset + i, vc.offset + j, 0.0);
          }
        }
      }
    }
  };
  for (size_t b = 0; b < residuals.size(); ++b) {
    if (active[b]) add_square(residuals[b]->variables());
  }
  for (const auto& t : objectives) add_square(t->variables());
  hessian_pattern.resize(num_variables, num_variables);
  hessian_pattern.setFromTriplets(entries.begin(), entries.end());
  hessian_pattern.makeCompressed();
  auto map_square = [&](const std::vector<VariableId>& ids) {
    const int n = local_size(ids);
    std::vector<int> global(n);
    int p = 0;
    for (VariableId v : ids) {
      for (int i = 0; i < variables[v].size; ++i) global[p++] = variables[v].offset + i;
    }
    std::vector<int> map(static_cast<size_t>(n) * n, -1);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const int row = global[i], col = global[j];
        if (col > row) continue;
        const int* begin = hessian_pattern.innerIndexPtr() + hessian_pattern.outerIndexPtr()[row];
        const int* end = hessian_pattern.innerIndexPtr() + hessian_pattern.outerIndexPtr()[row + 1];
        map[static_cast<size_t>(i) * n + j] =
            static_cast<int>(std::lower_bound(begin, end, col) - hessian_pattern.innerIndexPtr());
      }
    }
    return map;
  };
  residual_hessian_map.assign(residuals.size(), {});
  size_t max_square = 1;
  for (size_t b = 0; b < residuals.size(); ++b) {
    if (!active[b]) continue;
    residual_hessian_map[b] = map_square(residuals[b]->variables());
    max_square = std::max(max_square, residual_hessian_map[b].size());
  }
  objective_hessian_map.clear();
  for (const auto& t : objectives) {
    objective_hessian_map.push_back(map_square(t->variables()));
    max_square = std::max(max_square, objective_hessian_map.back().size());
  }
  if (dense_scratch.size() < max_square) dense_scratch.assign(max_square, 0.0);
  hessian_built_version = version;
}

// ---------------------------------------------------------------------------------------------------

Problem::Problem() : impl_(std::make_unique<Impl>()) {}
Problem::Problem(const Problem& other) : impl_(std::make_unique<Impl>(other.impl())) {}
Problem& Problem::operator=(const Problem& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(other.impl());
  return *this;
}
Problem::Problem(Problem&&) noexcept = default;
Problem& Problem::operator=(Problem&&) noexcept = default;
Problem::~Problem() = default;

void Problem::ensure_impl() {
  if (!impl_) impl_ = std::make_unique<Impl>();
}

Problem::Impl& Problem::impl() const {
  if (!impl_) throw std::logic_error("pcr::Problem used after being moved from");
  return *impl_;
}

VariableId Problem::add_variable_block(const std::string& name, const VecX& initial) {
  return add_variable_block(name, initial, VecX::Constant(initial.size(), -kInf),
                            VecX::Constant(initial.size(), kInf));
}

VariableId Problem::add_variable_block(const std::string& name, const VecX& initial, const VecX& lower,
                                       const VecX& upper) {
  ensure_impl();
  Impl& m = *impl_;
  require(initial.size() >= 1, "variable block '", name, "': size = ", initial.size(), " < 1");
  require(initial.allFinite(), "variable block '", name, "': initial value is not finite");
  VariableBlock v;
  v.name = name;
  v.offset = m.num_variables;
  v.size = static_cast<int>(initial.size());
  v.initial = initial;
  m.variables.push_back(v);
  m.fixed.push_back(0);
  const VariableId id = static_cast<int>(m.variables.size()) - 1;
  try {
    set_variable_bounds(id, lower, upper);
  } catch (...) {
    m.variables.pop_back();
    m.fixed.pop_back();
    throw;
  }
  m.num_variables += v.size;
  ++m.version;
  return id;
}

ResidualId Problem::add_residual_block(std::shared_ptr<const ResidualBlock> block) {
  ensure_impl();
  Impl& m = *impl_;
  require(block != nullptr, "add_residual_block: null block");
  const std::string where = "residual block '" + block->name() + "' (kind '" + block->kind() + "')";
  const auto& ids = block->variables();
  for (size_t k = 0; k < ids.size(); ++k) {
    require(ids[k] >= 0 && ids[k] < static_cast<int>(m.variables.size()), where, ": variable id ", ids[k],
            " (position ", k, ") is not a variable block of this problem (", m.variables.size(), " blocks)");
    require(std::count(ids.begin(), ids.end(), ids[k]) == 1, where, ": variable block '",
            m.variables[ids[k]].name, "' is listed twice");
    const int expected = block->expected_variable_size(static_cast<int>(k));
    require(expected < 0 || expected == m.variables[ids[k]].size, where, ": variable block '",
            m.variables[ids[k]].name, "' has size ", m.variables[ids[k]].size, ", the block expects ",
            expected);
  }
  require(block->row_lower().size() == block->num_rows() && block->row_upper().size() == block->num_rows(),
          where, ": row bounds have sizes ", block->row_lower().size(), " and ", block->row_upper().size(),
          ", expected ", block->num_rows());
  m.residuals.push_back(std::move(block));
  m.active.push_back(1);
  ++m.version;
  return static_cast<int>(m.residuals.size()) - 1;
}

void Problem::add_objective_term(std::shared_ptr<const ObjectiveTerm> term) {
  ensure_impl();
  Impl& m = *impl_;
  require(term != nullptr, "add_objective_term: null term");
  const auto& ids = term->variables();
  for (size_t k = 0; k < ids.size(); ++k) {
    require(ids[k] >= 0 && ids[k] < static_cast<int>(m.variables.size()), "objective term '", term->name(),
            "': variable id ", ids[k], " (position ", k, ") is not a variable block of this problem");
    require(std::count(ids.begin(), ids.end(), ids[k]) == 1, "objective term '", term->name(),
            "': variable block '", m.variables[ids[k]].name, "' is listed twice");
    const int expected = term->expected_variable_size(static_cast<int>(k));
    require(expected < 0 || expected == m.variables[ids[k]].size, "objective term '", term->name(),
            "': variable block '", m.variables[ids[k]].name, "' has size ", m.variables[ids[k]].size,
            ", the term expects ", expected);
  }
  m.objectives.push_back(std::move(term));
  ++m.version;
}

void Problem::set_residual_active(ResidualId id, bool active) {
  Impl& m = impl();
  require(id >= 0 && id < static_cast<int>(m.residuals.size()), "set_residual_active: residual id ", id,
          " out of range [0, ", m.residuals.size(), ")");
  if (static_cast<bool>(m.active[id]) == active) return;
  m.active[id] = active ? 1 : 0;
  ++m.version;
}

void Problem::set_variable_group(VariableId id, int group) {
  Impl& m = impl();
  m.check_variable(id, "set_variable_group");
  m.variables[id].group = group;
}

void Problem::set_variable_bounds(VariableId id, const VecX& lower, const VecX& upper) {
  Impl& m = impl();
  m.check_variable(id, "set_variable_bounds");
  VariableBlock& v = m.variables[id];
  require(lower.size() == v.size, "variable block '", v.name, "': lower bound size = ", lower.size(),
          ", expected ", v.size);
  require(upper.size() == v.size, "variable block '", v.name, "': upper bound size = ", upper.size(),
          ", expected ", v.size);
  for (int i = 0; i < v.size; ++i) {
    require(!std::isnan(lower[i]) && !std::isnan(upper[i]) && lower[i] <= upper[i], "variable block '",
            v.name, "': bounds [", lower[i], ", ", upper[i], "] of entry ", i, " are not an interval");
  }
  v.lower = lower;
  v.upper = upper;
  if (m.fixed[id]) ++m.version;  // un-fixing changes the set of unknowns
  m.fixed[id] = 0;
}

void Problem::fix_variable(VariableId id, const VecX& value) {
  Impl& m = impl();
  m.check_variable(id, "fix_variable");
  VariableBlock& v = m.variables[id];
  require(value.size() == v.size, "fix_variable: variable block '", v.name, "': value size = ", value.size(),
          ", expected ", v.size);
  require(value.allFinite(), "fix_variable: variable block '", v.name, "': value is not finite");
  v.initial = value;
  v.lower = value;
  v.upper = value;
  if (!m.fixed[id]) ++m.version;  // the set of unknowns changed (re-fixing only changes the value)
  m.fixed[id] = 1;
}

bool Problem::variable_fixed(VariableId id) const {
  impl().check_variable(id, "variable_fixed");
  return impl().fixed[id] != 0;
}

int Problem::num_variables() const {
  return impl().num_variables;
}
int Problem::num_rows() const {
  impl().ensure_structure();
  return impl().num_rows;
}
const VariableBlock& Problem::variable(VariableId id) const {
  impl().check_variable(id, "variable");
  return impl().variables[id];
}
int Problem::num_variable_blocks() const {
  return static_cast<int>(impl().variables.size());
}
const ResidualBlock& Problem::residual(ResidualId id) const {
  require(id >= 0 && id < num_residual_blocks(), "residual: id ", id, " out of range");
  return *impl().residuals[id];
}
int Problem::num_residual_blocks() const {
  return static_cast<int>(impl().residuals.size());
}
bool Problem::residual_active(ResidualId id) const {
  require(id >= 0 && id < num_residual_blocks(), "residual_active: id ", id, " out of range");
  return impl().active[id] != 0;
}
int Problem::row_offset(ResidualId id) const {
  require(id >= 0 && id < num_residual_blocks(), "row_offset: id ", id, " out of range");
  impl().ensure_structure();
  return impl().row_offset[id];
}
bool Problem::has_objective() const {
  return !impl().objectives.empty();
}
std::uint64_t Problem::structure_version() const {
  return impl().version;
}
int Problem::jacobian_nonzeros() const {
  impl().ensure_structure();
  return static_cast<int>(impl().jacobian_pattern.nonZeros());
}
ResidualId Problem::residual_at_row(int row) const {
  Impl& m = impl();
  m.ensure_structure();
  require(row >= 0 && row < m.num_rows, "residual_at_row: row ", row, " out of range [0, ", m.num_rows, ")");
  return m.row_owner[row];
}

VecX Problem::initial_values() const {
  const Impl& m = impl();
  VecX x(m.num_variables);
  for (const auto& v : m.variables) x.segment(v.offset, v.size) = v.initial;
  return x;
}

void Problem::evaluate_residuals(const VecX& x, VecX& c) const {
  Impl& m = impl();
  m.ensure_structure();
  require(x.size() == m.num_variables, "evaluate_residuals: x has size ", x.size(), ", expected ",
          m.num_variables);
  if (c.size() != m.num_rows) c.resize(m.num_rows);
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (!m.active[b]) continue;
    const ResidualBlock& block = *m.residuals[b];
    const auto& ids = block.variables();
    for (size_t k = 0; k < ids.size(); ++k) m.value_ptrs[k] = x.data() + m.variables[ids[k]].offset;
    block.evaluate(m.value_ptrs.data(), c.data() + m.row_offset[b], nullptr);
  }
}

void Problem::evaluate_residuals_and_jacobian(const VecX& x, VecX& c, SparseRowMajor& J) const {
  Impl& m = impl();
  m.ensure_structure();
  require(x.size() == m.num_variables, "evaluate_residuals_and_jacobian: x has size ", x.size(),
          ", expected ", m.num_variables);
  if (c.size() != m.num_rows) c.resize(m.num_rows);
  if (!same_pattern(J, m.jacobian_pattern)) J = m.jacobian_pattern;
  double* J_values = J.valuePtr();
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (!m.active[b]) continue;
    const ResidualBlock& block = *m.residuals[b];
    const auto& ids = block.variables();
    const int rows = block.num_rows();
    double* dense = m.dense_scratch.data();
    for (size_t k = 0; k < ids.size(); ++k) {
      m.value_ptrs[k] = x.data() + m.variables[ids[k]].offset;
      m.derivative_ptrs[k] = dense;
      dense += static_cast<size_t>(rows) * m.variables[ids[k]].size;
    }
    block.evaluate(m.value_ptrs.data(), c.data() + m.row_offset[b], m.derivative_ptrs.data());
    // Scatter the structurally nonzero entries of the stacked dense Jacobians into J.
    const double* stacked = m.dense_scratch.data();
    for (int e = m.jacobian_scatter_offset[b]; e < m.jacobian_scatter_offset[b + 1]; ++e)
      J_values[m.jacobian_scatter[e].second] = stacked[m.jacobian_scatter[e].first];
  }
}

double Problem::evaluate_objective(const VecX& x, VecX* gradient) const {
  Impl& m = impl();
  m.ensure_structure();
  require(x.size() == m.num_variables, "evaluate_objective: x has size ", x.size(), ", expected ",
          m.num_variables);
  if (gradient) {
    if (gradient->size() != m.num_variables) gradient->resize(m.num_variables);
    gradient->setZero();
  }
  double f = 0.0;
  for (const auto& term : m.objectives) {
    const auto& ids = term->variables();
    double* dense = m.dense_scratch.data();
    for (size_t k = 0; k < ids.size(); ++k) {
      m.value_ptrs[k] = x.data() + m.variables[ids[k]].offset;
      m.derivative_ptrs[k] = dense;
      dense += m.variables[ids[k]].size;
    }
    f += term->evaluate(m.value_ptrs.data(), gradient ? m.derivative_ptrs.data() : nullptr);
    if (!gradient) continue;
    for (size_t k = 0; k < ids.size(); ++k) {
      const VariableBlock& v = m.variables[ids[k]];
      gradient->segment(v.offset, v.size) += Eigen::Map<const VecX>(m.derivative_ptrs[k], v.size);
    }
  }
  return f;
}

VecX Problem::row_lower() const {
  Impl& m = impl();
  m.ensure_structure();
  VecX l(m.num_rows);
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (m.active[b]) l.segment(m.row_offset[b], m.residuals[b]->num_rows()) = m.residuals[b]->row_lower();
  }
  return l;
}

VecX Problem::row_upper() const {
  Impl& m = impl();
  m.ensure_structure();
  VecX u(m.num_rows);
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (m.active[b]) u.segment(m.row_offset[b], m.residuals[b]->num_rows()) = m.residuals[b]->row_upper();
  }
  return u;
}

VecX Problem::variable_lower() const {
  const Impl& m = impl();
  VecX l(m.num_variables);
  for (const auto& v : m.variables) l.segment(v.offset, v.size) = v.lower;
  return l;
}

VecX Problem::variable_upper() const {
  const Impl& m = impl();
  VecX u(m.num_variables);
  for (const auto& v : m.variables) u.segment(v.offset, v.size) = v.upper;
  return u;
}

namespace {
// max(l - c, c - u, 0), +inf for a non-finite c.
double row_violation(double c, double l, double u) {
  if (!std::isfinite(c)) return kInf;
  return std::max({l - c, c - u, 0.0});
}
}  // namespace

double Problem::constraint_violation(const VecX& c) const {
  Impl& m = impl();
  m.ensure_structure();
  require(c.size() == m.num_rows, "constraint_violation: c has size ", c.size(), ", expected ", m.num_rows);
  double worst = 0.0;
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (!m.active[b]) continue;
    const ResidualBlock& block = *m.residuals[b];
    for (int r = 0; r < block.num_rows(); ++r) {
      worst =
          std::max(worst, row_violation(c[m.row_offset[b] + r], block.row_lower()[r], block.row_upper()[r]));
    }
  }
  return worst;
}

std::vector<std::pair<std::string, double>> Problem::violation_by_kind(const VecX& c) const {
  Impl& m = impl();
  m.ensure_structure();
  require(c.size() == m.num_rows, "violation_by_kind: c has size ", c.size(), ", expected ", m.num_rows);
  std::vector<std::pair<std::string, double>> result;
  for (const auto& kind : m.kinds) result.emplace_back(kind, 0.0);
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (!m.active[b]) continue;
    const ResidualBlock& block = *m.residuals[b];
    double& worst = result[m.kind_of_block[b]].second;
    for (int r = 0; r < block.num_rows(); ++r) {
      worst =
          std::max(worst, row_violation(c[m.row_offset[b] + r], block.row_lower()[r], block.row_upper()[r]));
    }
  }
  return result;
}

bool Problem::provides_hessian() const {
  const Impl& m = impl();
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (m.active[b] && !m.residuals[b]->provides_hessian()) return false;
  }
  for (const auto& t : m.objectives) {
    if (!t->provides_hessian()) return false;
  }
  return true;
}

void Problem::evaluate_hessian(const VecX& x, double objective_factor, const VecX& multipliers,
                               SparseRowMajor& H) const {
  if (!provides_hessian()) throw std::logic_error("Problem::evaluate_hessian: a block provides no Hessian");
  Impl& m = impl();
  m.ensure_hessian_structure();
  require(x.size() == m.num_variables, "evaluate_hessian: x has size ", x.size(), ", expected ",
          m.num_variables);
  require(multipliers.size() == m.num_rows, "evaluate_hessian: multipliers have size ", multipliers.size(),
          ", expected ", m.num_rows);
  if (!same_pattern(H, m.hessian_pattern)) H = m.hessian_pattern;
  double* H_values = H.valuePtr();
  std::fill(H_values, H_values + H.nonZeros(), 0.0);
  auto accumulate = [&](const std::vector<int>& map, double scale) {
    for (size_t e = 0; e < map.size(); ++e) {
      if (map[e] >= 0) H_values[map[e]] += scale * m.dense_scratch[e];
    }
  };
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (!m.active[b]) continue;
    const ResidualBlock& block = *m.residuals[b];
    const auto& ids = block.variables();
    for (size_t k = 0; k < ids.size(); ++k) m.value_ptrs[k] = x.data() + m.variables[ids[k]].offset;
    block.evaluate_hessian(m.value_ptrs.data(), multipliers.data() + m.row_offset[b], m.dense_scratch.data());
    accumulate(m.residual_hessian_map[b], 1.0);
  }
  if (objective_factor == 0.0) return;
  for (size_t t = 0; t < m.objectives.size(); ++t) {
    const auto& ids = m.objectives[t]->variables();
    for (size_t k = 0; k < ids.size(); ++k) m.value_ptrs[k] = x.data() + m.variables[ids[k]].offset;
    m.objectives[t]->evaluate_hessian(m.value_ptrs.data(), m.dense_scratch.data());
    accumulate(m.objective_hessian_map[t], objective_factor);
  }
}

}  // namespace pcr
