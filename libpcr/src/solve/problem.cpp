// Problem: block bookkeeping and validation (the derived structure: problem_structure.cpp; evaluation:
// problem_evaluate.cpp).
#include "pcr/solve/problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "problem_impl.hpp"

namespace pcr {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// Checks a block's or term's variable list against the problem: ids exist, none twice, sizes as expected.
template <class Block>
void check_touched_variables(const Block& block, const std::vector<VariableBlock>& variables,
                             const std::string& where, const char* expects) {
  const auto& ids = block.variables();
  for (size_t k = 0; k < ids.size(); ++k) {
    require(ids[k] >= 0 && ids[k] < static_cast<int>(variables.size()), where, ": variable id ", ids[k],
            " (position ", k, ") is not a variable block of this problem (", variables.size(), " blocks)");
    require(std::count(ids.begin(), ids.end(), ids[k]) == 1, where, ": variable block '",
            variables[ids[k]].name, "' is listed twice");
    const int expected = block.expected_variable_size(static_cast<int>(k));
    require(expected < 0 || expected == variables[ids[k]].size, where, ": variable block '",
            variables[ids[k]].name, "' has size ", variables[ids[k]].size, ", ", expects, " ", expected);
  }
}
}  // namespace

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

const Problem::Impl& Problem::impl() const {
  if (!impl_) throw std::logic_error("pcr::Problem used after being moved from");
  return *impl_;
}

Problem::Impl& Problem::impl() {
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
  v.scale = VecX::Ones(initial.size());
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
  m.extend_variables();
  ++m.version;
  return id;
}

ResidualId Problem::add_residual_block(std::shared_ptr<const ResidualBlock> block) {
  ensure_impl();
  Impl& m = *impl_;
  require(block != nullptr, "add_residual_block: null block");
  const std::string where = "residual block '" + block->name() + "' (kind '" + block->kind() + "')";
  check_touched_variables(*block, m.variables, where, "the block expects");
  require(block->row_lower().size() == block->num_rows() && block->row_upper().size() == block->num_rows(),
          where, ": row bounds have sizes ", block->row_lower().size(), " and ", block->row_upper().size(),
          ", expected ", block->num_rows());
  m.residuals.push_back(std::move(block));
  m.active.push_back(1);
  const ResidualId id = static_cast<int>(m.residuals.size()) - 1;
  m.append_residual(id);
  ++m.version;
  return id;
}

void Problem::add_objective_term(std::shared_ptr<const ObjectiveTerm> term) {
  ensure_impl();
  Impl& m = *impl_;
  require(term != nullptr, "add_objective_term: null term");
  check_touched_variables(*term, m.variables, "objective term '" + term->name() + "'", "the term expects");
  m.objectives.push_back(std::move(term));
  m.append_objective(static_cast<int>(m.objectives.size()) - 1);
  ++m.version;
}

void Problem::set_residual_active(ResidualId id, bool active) {
  Impl& m = impl();
  m.check_residual(id, "set_residual_active");
  if (static_cast<bool>(m.active[id]) == active) return;
  m.active[id] = active ? 1 : 0;
  m.rebuild();
  ++m.version;
}

void Problem::set_residual_active(const std::vector<ResidualId>& ids, bool active) {
  Impl& m = impl();
  for (ResidualId id : ids) m.check_residual(id, "set_residual_active");
  bool changed = false;
  for (ResidualId id : ids) {
    changed = changed || static_cast<bool>(m.active[id]) != active;
    m.active[id] = active ? 1 : 0;
  }
  if (!changed) return;
  m.rebuild();
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

void Problem::set_variable_scale(VariableId id, const VecX& scale) {
  Impl& m = impl();
  m.check_variable(id, "set_variable_scale");
  VariableBlock& v = m.variables[id];
  require(scale.size() == v.size, "variable block '", v.name, "': scale size = ", scale.size(), ", expected ",
          v.size);
  for (int i = 0; i < v.size; ++i)
    require(std::isfinite(scale[i]) && scale[i] > 0.0, "variable block '", v.name, "': scale ", scale[i],
            " of entry ", i, " is not positive and finite");
  v.scale = scale;
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
  return impl().rows.num_rows;
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
std::shared_ptr<const ResidualBlock> Problem::residual_block(ResidualId id) const {
  require(id >= 0 && id < num_residual_blocks(), "residual_block: id ", id, " out of range");
  return impl().residuals[id];
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
  return impl().rows.row_offset[id];
}
bool Problem::has_objective() const {
  return !impl().objectives.empty();
}
std::uint64_t Problem::structure_version() const {
  return impl().version;
}
int Problem::jacobian_nonzeros() const {
  return static_cast<int>(impl().jacobian.inner.size());
}
ResidualId Problem::residual_at_row(int row) const {
  const Impl& m = impl();
  require(row >= 0 && row < m.rows.num_rows, "residual_at_row: row ", row, " out of range [0, ",
          m.rows.num_rows, ")");
  return m.rows.row_owner[row];
}
bool Problem::provides_hessian() const {
  return impl().blocks_without_hessian == 0;
}

VecX Problem::initial_values() const {
  const Impl& m = impl();
  VecX x(m.num_variables);
  for (const auto& v : m.variables) x.segment(v.offset, v.size) = v.initial;
  return x;
}

VecX Problem::variable_lower() const {
  const Impl& m = impl();
  VecX l(m.num_variables);
  for (const auto& v : m.variables) l.segment(v.offset, v.size) = v.lower;
  return l;
}

VecX Problem::variable_scales() const {
  const Impl& m = impl();
  VecX s(m.num_variables);
  for (const auto& v : m.variables) s.segment(v.offset, v.size) = v.scale;
  return s;
}

VecX Problem::variable_upper() const {
  const Impl& m = impl();
  VecX u(m.num_variables);
  for (const auto& v : m.variables) u.segment(v.offset, v.size) = v.upper;
  return u;
}

}  // namespace pcr
