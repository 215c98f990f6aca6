// Problem's evaluations: residuals, Jacobian, objective, Hessian, row bounds and violations. They only read
// the Problem; their scratch (pointers to the blocks' values and dense derivative arrays) is a frame of a
// per-thread stack, so several threads may evaluate one Problem at once, and a block may evaluate another
// Problem inside its own evaluation (the reduced-space IK runs FK solves there) without touching the
// outer evaluation's scratch. Frames are kept and grow to the largest block: no allocation once sized.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "problem_impl.hpp"

namespace pcr {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Scratch {
  std::vector<const double*> values;  // per touched variable block: its values in x
  std::vector<double*> derivatives;   // per touched variable block: its part of dense
  std::vector<double> dense;          // stacked dense Jacobians / gradients, or a dense Hessian square
};

struct ScratchStack {
  std::vector<std::unique_ptr<Scratch>> frames;  // unique_ptr: frames stay put when the stack grows
  size_t depth = 0;
};

/// The next frame of this thread's scratch stack, sized for at least `pointers` variable blocks and
/// `dense` values, for the lifetime of the object.
class ScratchFrame {
 public:
  ScratchFrame(size_t pointers, size_t dense) : stack_(stack()) {
    if (stack_.depth == stack_.frames.size()) stack_.frames.push_back(std::make_unique<Scratch>());
    scratch_ = stack_.frames[stack_.depth].get();
    if (scratch_->values.size() < pointers) {
      scratch_->values.resize(pointers);
      scratch_->derivatives.resize(pointers);
    }
    if (scratch_->dense.size() < dense) scratch_->dense.resize(dense);
    ++stack_.depth;
  }
  ~ScratchFrame() { --stack_.depth; }
  ScratchFrame(const ScratchFrame&) = delete;
  ScratchFrame& operator=(const ScratchFrame&) = delete;
  Scratch* operator->() const { return scratch_; }
  Scratch& operator*() const { return *scratch_; }

 private:
  static ScratchStack& stack() {
    thread_local ScratchStack frames;
    return frames;
  }
  ScratchStack& stack_;
  Scratch* scratch_;
};

/// Points s.values at the blocks ids in x.
void point_at_values(const std::vector<VariableBlock>& variables, const std::vector<VariableId>& ids,
                     const VecX& x, Scratch& s) {
  for (size_t k = 0; k < ids.size(); ++k) s.values[k] = x.data() + variables[ids[k]].offset;
}

/// Points s.derivatives at consecutive dense arrays of rows x size(ids[k]) in s.dense.
void point_at_dense(const std::vector<VariableBlock>& variables, const std::vector<VariableId>& ids, int rows,
                    Scratch& s) {
  double* dense = s.dense.data();
  for (size_t k = 0; k < ids.size(); ++k) {
    s.derivatives[k] = dense;
    dense += static_cast<size_t>(rows) * variables[ids[k]].size;
  }
}

// True when M already has exactly the pattern (rows, cols, outer, inner) (column indices of matrices
// built here are only ever written by make_pattern).
bool has_pattern(const SparseRowMajor& M, int rows, int cols, const std::vector<int>& outer,
                 const std::vector<int>& inner) {
  if (M.rows() != rows || M.cols() != cols || M.nonZeros() != static_cast<Eigen::Index>(inner.size()) ||
      !M.isCompressed())
    return false;
  return std::equal(outer.begin(), outer.end(), M.outerIndexPtr()) &&
         std::equal(inner.begin(), inner.end(), M.innerIndexPtr());
}

// A compressed row-major matrix with the given row pointers and column indices (values zero), the index
// arrays copied as they are (a sparse-to-sparse assignment from a Map would re-insert every entry).
SparseRowMajor make_pattern(int rows, int cols, const std::vector<int>& outer,
                            const std::vector<int>& inner) {
  SparseRowMajor M(rows, cols);
  M.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), M.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), M.innerIndexPtr());
  std::fill(M.valuePtr(), M.valuePtr() + inner.size(), 0.0);
  return M;
}

// max(l - c, c - u, 0), +inf for a non-finite c.
double row_violation(double c, double l, double u) {
  if (!std::isfinite(c)) return kInf;
  return std::max({l - c, c - u, 0.0});
}

}  // namespace

void Problem::evaluate_residuals(const VecX& x, VecX& c) const {
  const Impl& m = impl();
  require(x.size() == m.num_variables, "evaluate_residuals: x has size ", x.size(), ", expected ",
          m.num_variables);
  if (c.size() != m.rows.num_rows) c.resize(m.rows.num_rows);
  ScratchFrame s(m.max_block_variables, 0);
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (!m.active[b]) continue;
    const ResidualBlock& block = *m.residuals[b];
    point_at_values(m.variables, block.variables(), x, *s);
    block.evaluate(s->values.data(), c.data() + m.rows.row_offset[b], nullptr);
  }
}

void Problem::evaluate_residuals_and_jacobian(const VecX& x, VecX& c, SparseRowMajor& J) const {
  const Impl& m = impl();
  require(x.size() == m.num_variables, "evaluate_residuals_and_jacobian: x has size ", x.size(),
          ", expected ", m.num_variables);
  if (c.size() != m.rows.num_rows) c.resize(m.rows.num_rows);
  const JacobianStructure& p = m.jacobian;
  if (!has_pattern(J, m.rows.num_rows, m.num_variables, p.outer, p.inner))
    J = make_pattern(m.rows.num_rows, m.num_variables, p.outer, p.inner);
  double* J_values = J.valuePtr();
  ScratchFrame s(m.max_block_variables, m.max_dense);
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (!m.active[b]) continue;
    const ResidualBlock& block = *m.residuals[b];
    point_at_values(m.variables, block.variables(), x, *s);
    point_at_dense(m.variables, block.variables(), block.num_rows(), *s);
    block.evaluate(s->values.data(), c.data() + m.rows.row_offset[b], s->derivatives.data());
    // Scatter the structurally nonzero entries of the stacked dense Jacobians into J.
    const double* stacked = s->dense.data();
    for (int e = p.scatter_offset[b]; e < p.scatter_offset[b + 1]; ++e)
      J_values[p.scatter[e].second] = stacked[p.scatter[e].first];
  }
}

double Problem::evaluate_objective(const VecX& x, VecX* gradient) const {
  const Impl& m = impl();
  require(x.size() == m.num_variables, "evaluate_objective: x has size ", x.size(), ", expected ",
          m.num_variables);
  if (gradient) {
    if (gradient->size() != m.num_variables) gradient->resize(m.num_variables);
    gradient->setZero();
  }
  ScratchFrame s(m.max_block_variables, m.max_dense);
  double f = 0.0;
  for (const auto& term : m.objectives) {
    const auto& ids = term->variables();
    point_at_values(m.variables, ids, x, *s);
    point_at_dense(m.variables, ids, 1, *s);
    f += term->evaluate(s->values.data(), gradient ? s->derivatives.data() : nullptr);
    if (!gradient) continue;
    for (size_t k = 0; k < ids.size(); ++k) {
      const VariableBlock& v = m.variables[ids[k]];
      gradient->segment(v.offset, v.size) += Eigen::Map<const VecX>(s->derivatives[k], v.size);
    }
  }
  return f;
}

void Problem::evaluate_hessian(const VecX& x, double objective_factor, const VecX& multipliers,
                               SparseRowMajor& H) const {
  if (!provides_hessian()) throw std::logic_error("Problem::evaluate_hessian: a block provides no Hessian");
  const Impl& m = impl();
  require(x.size() == m.num_variables, "evaluate_hessian: x has size ", x.size(), ", expected ",
          m.num_variables);
  require(multipliers.size() == m.rows.num_rows, "evaluate_hessian: multipliers have size ",
          multipliers.size(), ", expected ", m.rows.num_rows);
  const HessianStructure& p = m.hessian_pattern();
  if (!has_pattern(H, m.num_variables, m.num_variables, p.outer, p.inner))
    H = make_pattern(m.num_variables, m.num_variables, p.outer, p.inner);
  double* H_values = H.valuePtr();
  std::fill(H_values, H_values + H.nonZeros(), 0.0);
  ScratchFrame s(m.max_block_variables, m.max_square);
  auto accumulate = [&](const std::vector<int>& map, double scale) {
    for (size_t e = 0; e < map.size(); ++e) {
      if (map[e] >= 0) H_values[map[e]] += scale * s->dense[e];
    }
  };
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (!m.active[b]) continue;
    const ResidualBlock& block = *m.residuals[b];
    point_at_values(m.variables, block.variables(), x, *s);
    block.evaluate_hessian(s->values.data(), multipliers.data() + m.rows.row_offset[b], s->dense.data());
    accumulate(p.residual_map[b], 1.0);
  }
  if (objective_factor == 0.0) return;
  for (size_t t = 0; t < m.objectives.size(); ++t) {
    point_at_values(m.variables, m.objectives[t]->variables(), x, *s);
    m.objectives[t]->evaluate_hessian(s->values.data(), s->dense.data());
    accumulate(p.objective_map[t], objective_factor);
  }
}

VecX Problem::row_lower() const {
  const Impl& m = impl();
  VecX l(m.rows.num_rows);
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (m.active[b])
      l.segment(m.rows.row_offset[b], m.residuals[b]->num_rows()) = m.residuals[b]->row_lower();
  }
  return l;
}

VecX Problem::row_upper() const {
  const Impl& m = impl();
  VecX u(m.rows.num_rows);
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (m.active[b])
      u.segment(m.rows.row_offset[b], m.residuals[b]->num_rows()) = m.residuals[b]->row_upper();
  }
  return u;
}

double Problem::constraint_violation(const VecX& c) const {
  const Impl& m = impl();
  require(c.size() == m.rows.num_rows, "constraint_violation: c has size ", c.size(), ", expected ",
          m.rows.num_rows);
  double worst = 0.0;
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (!m.active[b]) continue;
    const ResidualBlock& block = *m.residuals[b];
    const int offset = m.rows.row_offset[b];
    for (int r = 0; r < block.num_rows(); ++r)
      worst = std::max(worst, row_violation(c[offset + r], block.row_lower()[r], block.row_upper()[r]));
  }
  return worst;
}

std::vector<std::pair<std::string, double>> Problem::violation_by_kind(const VecX& c) const {
  const Impl& m = impl();
  require(c.size() == m.rows.num_rows, "violation_by_kind: c has size ", c.size(), ", expected ",
          m.rows.num_rows);
  std::vector<std::pair<std::string, double>> result;
  for (const auto& kind : m.rows.kinds) result.emplace_back(kind, 0.0);
  for (size_t b = 0; b < m.residuals.size(); ++b) {
    if (!m.active[b]) continue;
    const ResidualBlock& block = *m.residuals[b];
    const int offset = m.rows.row_offset[b];
    double& worst = result[m.rows.kind_of_block[b]].second;
    const double* lower = block.row_lower().data();
    const double* upper = block.row_upper().data();
    for (int r = 0; r < block.num_rows(); ++r)
      worst = std::max(worst, row_violation(c[offset + r], lower[r], upper[r]));
  }
  return result;
}

}  // namespace pcr
