// A Problem as the Newton loop's system (see problem_system.hpp).
#include "problem_system.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <new>

#include "newton_pattern_cache.hpp"
#include "pcr/core/error.hpp"
#include "problem_impl.hpp"

namespace pcr {

void ProblemSystem::prepare() {
  if (version_ == problem_.structure_version()) return;
  require(!problem_.has_objective(), "NewtonSolver: the problem has objective terms (use IpoptSolver)");
  const int n = problem_.num_variables(), m = problem_.num_rows();
  reduced_column_.assign(n, -1);
  column_groups_.clear();
  int n_free = 0;
  for (VariableId v = 0; v < problem_.num_variable_blocks(); ++v) {
    const VariableBlock& b = problem_.variable(v);
    const bool fixed = problem_.variable_fixed(v);
    for (int j = 0; j < b.size; ++j) {
      if (fixed) continue;
      require(std::isinf(b.lower[j]) && std::isinf(b.upper[j]), "NewtonSolver: variable block '", b.name,
              "' entry ", j, " has bounds [", b.lower[j], ", ", b.upper[j],
              "] (Newton ignores bounds; use IpoptSolver)");
      reduced_column_[b.offset + j] = n_free++;
      column_groups_.push_back(b.group);
    }
  }
  require(n_free == m, "NewtonSolver: the problem is not square: ", n_free, " free variables, ", m,
          " active rows");
  const VecX lower = problem_.row_lower(), upper = problem_.row_upper();
  for (int i = 0; i < m; ++i) {
    if (lower[i] != upper[i] || !std::isfinite(lower[i])) {
      const ResidualId b = problem_.residual_at_row(i);
      throw_input_error("NewtonSolver: residual block '", problem_.residual(b).name(), "' row ",
                        i - problem_.row_offset(b), " is not an equality: bounds [", lower[i], ", ", upper[i],
                        "]");
    }
  }
  target_ = lower;
  c_.resize(m);
  c_trial_.resize(m);
  linear_check_.resize(m);
  x_trial_.resize(n);
  J_ = Eigen::SparseMatrix<double, Eigen::RowMajor>();
  value_map_.clear();
  factored_ = Factored::None;
  version_ = problem_.structure_version();
}

std::shared_ptr<NewtonPatternAnalysis> SolverAnalyses::take(std::uint64_t version, int linear_solver) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!newton_ || newton_->version != version || static_cast<int>(newton_->linear_solver) != linear_solver)
    return nullptr;
  return std::move(newton_);
}

void SolverAnalyses::leave(std::shared_ptr<NewtonPatternAnalysis> analysis) {
  std::lock_guard<std::mutex> lock(mutex_);
  newton_ = std::move(analysis);
}

ProblemSystem::ProblemSystem(const Problem& problem, const NewtonOptions& options)
    : problem_(problem), options_(options), analyses_(problem.impl().analyses.ptr) {}

ProblemSystem::~ProblemSystem() {
  // value_map_ is current for version_ (prepare() clears it when the structure changes).
  const std::shared_ptr<SolverAnalyses> analyses = analyses_.lock();
  if (!analyses || value_map_.empty()) return;
  try {
    auto left = std::make_shared<NewtonPatternAnalysis>();
    left->version = version_;
    left->linear_solver = options_.linear_solver;
    left->value_map = std::move(value_map_);
    left->J_free.swap(J_free_);  // Eigen's SparseMatrix has no move: swap, not a copy
    left->blocks = std::move(blocks_);
    analyses->leave(std::move(left));
  } catch (const std::bad_alloc&) {
    // Nothing left: the next solver analyses the structure itself.
  }
}

bool ProblemSystem::take_left_analysis() {
  const std::shared_ptr<SolverAnalyses> analyses = analyses_.lock();
  if (!analyses) return false;
  const std::shared_ptr<NewtonPatternAnalysis> a =
      analyses->take(version_, static_cast<int>(options_.linear_solver));
  if (!a || a->value_map.size() != static_cast<size_t>(J_.nonZeros())) return false;
  value_map_ = std::move(a->value_map);
  J_free_.swap(a->J_free);
  blocks_ = std::move(a->blocks);
  return true;
}

// Free-column copy of J's pattern (J must hold the problem's pattern) and its symbolic analysis.
void ProblemSystem::build_free_pattern() {
  // The sparse LU's analysis waits until it is needed (factorize_free).
  sparse_analyzed_ = false;
  if (take_left_analysis()) return;
  // A structure analysed before (by any problem): its analysis (newton_pattern_cache.hpp).
  const NewtonPatternKey key{J_, reduced_column_, column_groups_, options_.linear_solver};
  if (const std::shared_ptr<const NewtonPatternAnalysis> cached = find_newton_pattern(key)) {
    value_map_ = cached->value_map;
    J_free_ = cached->J_free;
    blocks_ = cached->blocks;
    return;
  }
  // J_free in CSC straight from the row-major J: count the entries per free column, then place them
  // row by row, so each column's rows come out sorted and value_map is the position written.
  const int n = static_cast<int>(J_.rows());
  std::vector<int> starts(n + 1, 0);
  for (int p = 0; p < J_.nonZeros(); ++p) {
    const int col = reduced_column_[J_.innerIndexPtr()[p]];
    if (col >= 0) ++starts[col + 1];
  }
  for (int c = 0; c < n; ++c) starts[c + 1] += starts[c];
  J_free_.resize(n, n);
  J_free_.resizeNonZeros(starts[n]);
  std::copy(starts.begin(), starts.end(), J_free_.outerIndexPtr());
  value_map_.assign(J_.nonZeros(), -1);
  for (int i = 0; i < J_.outerSize(); ++i) {
    for (int p = J_.outerIndexPtr()[i]; p < J_.outerIndexPtr()[i + 1]; ++p) {
      const int col = reduced_column_[J_.innerIndexPtr()[p]];
      if (col < 0) continue;
      const int q = starts[col]++;
      J_free_.innerIndexPtr()[q] = i;
      J_free_.valuePtr()[q] = 0.0;
      value_map_[p] = q;
    }
  }
  const bool grouped =
      std::any_of(column_groups_.begin(), column_groups_.end(), [](int g) { return g >= 0; });
  const bool structured = options_.linear_solver == NewtonLinearSolver::BorderedBlocks ||
                          (options_.linear_solver == NewtonLinearSolver::Auto && grouped);
  if (!structured || !blocks_.analyze_pattern(J_free_, column_groups_)) blocks_ = BorderedBlockLu();
  NewtonPatternAnalysis analysis;
  analysis.value_map = value_map_;
  analysis.J_free = J_free_;
  analysis.blocks = blocks_;
  keep_newton_pattern(key, analysis);
}

bool ProblemSystem::factorize_free(bool sparse_only) {
  factored_ = Factored::None;
  if (!sparse_only && blocks_.analyzed() && blocks_.factorize(J_free_)) {
    factored_ = Factored::Blocks;
    return true;
  }
  if (!sparse_analyzed_) {
    lu_.analyze_pattern(J_free_);
    sparse_analyzed_ = true;
  }
  if (!lu_.factorize(J_free_)) return false;
  factored_ = Factored::Sparse;
  return true;
}

const char* ProblemSystem::factorization_kind() const {
  switch (factored_) {
    case Factored::Blocks: return "bordered blocks";
    case Factored::Sparse: return "sparse";
    default: return "none";
  }
}

bool ProblemSystem::evaluate_start(bool, VecX& r) {
  problem_.evaluate_residuals(*x_, c_);
  r = c_ - target_;
  return true;
}

bool ProblemSystem::evaluate_trial(const VecX& dx, bool, VecX& r) {
  const VecX& x = *x_;
  for (int j = 0; j < x.size(); ++j) {
    const int col = reduced_column_[j];
    x_trial_[j] = x[j] + (col >= 0 ? dx[col] : 0.0);
  }
  problem_.evaluate_residuals(x_trial_, c_trial_);
  r = c_trial_ - target_;
  return true;
}

void ProblemSystem::accept_trial() {
  x_->swap(x_trial_);
  c_.swap(c_trial_);
}

// Newton step, first half: J at x, its free columns, the factorisation.
bool ProblemSystem::within_round_off(const VecX& r, double tolerance, double& bound) const {
  bound = 0.0;
  return x_ && residuals_within_round_off(J_, *x_, problem_.variable_scales(), r, tolerance, bound);
}

SystemStatus ProblemSystem::factorize(VecX&) {
  problem_.evaluate_residuals_and_jacobian(*x_, c_, J_);
  if (value_map_.size() != static_cast<size_t>(J_.nonZeros())) build_free_pattern();
  double* free_values = J_free_.valuePtr();
  const double* values = J_.valuePtr();
  for (size_t p = 0; p < value_map_.size(); ++p) {
    if (value_map_[p] >= 0) free_values[value_map_[p]] = values[p];
  }
  if (!J_free_.coeffs().allFinite())
    return SystemStatus::failed(SolveStatus::Diverged, "non-finite Jacobian entry");
  if (!factorize_free(false))
    return SystemStatus::failed(SolveStatus::Singular, "sparse LU failed: " + lu_.error_message());
  return SystemStatus::success();
}

void ProblemSystem::solve(const VecX& b, VecX& y) {
  if (factored_ == Factored::Blocks)
    blocks_.solve(b, y);
  else
    lu_.solve(b, y);
}

// Newton step, second half: J_free dx = -r, checked for accuracy (the structured LU pivots only within
// each block: an inaccurate solve is redone with the sparse LU) and size (ill-conditioning).
SystemStatus ProblemSystem::newton_direction(const VecX& r, VecX& dx) {
  const double r_norm = r.norm();
  double linear_residual = 0.0;
  for (;;) {
    solve(r, dx);
    dx = -dx;
    linear_check_.noalias() = J_free_ * dx;
    linear_check_ += r;
    linear_residual = linear_check_.norm() / r_norm;
    if (linear_residual <= options_.linear_residual_limit || factored_ != Factored::Blocks) break;
    if (!factorize_free(true))
      return SystemStatus::failed(SolveStatus::Singular, "sparse LU failed: " + lu_.error_message());
  }
  char buffer[160];
  if (!(linear_residual <= options_.linear_residual_limit)) {
    std::snprintf(buffer, sizeof buffer,
                  "ill-conditioned Jacobian: linear solve residual |J dx + r|/|r| = %.3g", linear_residual);
    return SystemStatus::failed(SolveStatus::Singular, buffer);
  }
  const double step = dx.lpNorm<Eigen::Infinity>();
  if (!(step <= options_.max_step_ratio * (1.0 + x_->lpNorm<Eigen::Infinity>()))) {
    std::snprintf(buffer, sizeof buffer, "ill-conditioned Jacobian: Newton step |dx|max = %.3g", step);
    return SystemStatus::failed(SolveStatus::Singular, buffer);
  }
  return SystemStatus::success();
}

}  // namespace pcr
