// Damped Newton with an LU of the free columns (see newton_solver.hpp).
#include "pcr/solve/newton_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "pcr/core/error.hpp"
#include "pcr/solve/bordered_block_lu.hpp"
#include "pcr/solve/sparse_lu.hpp"

namespace pcr {

namespace {
using SparseRowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using SparseColMajor = Eigen::SparseMatrix<double>;

// One pass over v: whether every entry is finite, the largest |entry| and the 2-norm (the quantities the
// iteration tests on each residual and step).
struct VectorStats {
  bool finite;
  double max_abs, norm;
};
VectorStats stats_of(const VecX& v) {
  bool finite = true;
  double max_abs = 0.0, sum = 0.0;
  for (const double e : v) {
    const double a = std::abs(e);
    finite = finite && a <= std::numeric_limits<double>::max();  // false for inf and nan
    max_abs = std::max(max_abs, a);
    sum += a * a;
  }
  return {finite, max_abs, std::sqrt(sum)};
}

std::string format(const char* fmt, double a, double b = 0.0) {
  char buffer[200];
  std::snprintf(buffer, sizeof buffer, fmt, a, b);
  return buffer;
}
}  // namespace

struct NewtonSolver::Impl {
  const Problem& problem;
  NewtonOptions options;
  std::uint64_t version = 0;  // problem structure the workspace was built for

  std::vector<int> reduced_column;  // global column -> free column, -1 for a fixed one
  VecX target;                      // c_l = c_u of every row
  SparseRowMajor J;                 // full Jacobian in the problem's pattern
  SparseColMajor J_free;            // free columns, column-major for the sparse LU
  std::vector<int> value_map;       // J value index -> J_free value index, -1 for fixed columns
  std::vector<int> column_groups;   // VariableBlock::group of each free column
  // The factorisation of J_free: the structured one when the problem has groups (NewtonLinearSolver),
  // the sparse LU when asked for or when the structured one fails.
  BorderedBlockLu blocks;
  SparseLu lu;
  bool sparse_analyzed = false;
  enum class Factored { None, Sparse, Blocks } factored = Factored::None;  // what holds J0 (for reuse)
  VecX c, r, r_trial, x_trial, dx_free, dx, linear_check;
  // Quasi-Newton steps on the last factorisation J0 (free columns): steps[0 .. num_steps), see solve();
  // starts[j]: steps[j] is the first step of a sequence (of a solve, or after a fresh Jacobian).
  std::vector<VecX> steps;
  std::vector<double> step_norms2;  // |steps[j]|^2
  std::vector<char> starts;
  int num_steps = 0;
  bool continue_path = false;  // the next solve starts with the kept steps (NewtonSolver::continue_path)
  static constexpr int kMaxSteps = 16;     // then a fresh Jacobian (bounds the update work and storage)
  static constexpr int kCarriedSteps = 6;  // steps of earlier solves kept for the next one (see solve())

  Impl(const Problem& p, NewtonOptions o) : problem(p), options(o) {}
  void prepare();
  void build_free_pattern();
  /// Factorises J_free (the structured LU unless sparse_only or it fails); false when singular.
  bool factorize(bool sparse_only);
  /// x = J0^-1 b with the current factorisation.
  void linear_solve(const VecX& b, VecX& x) const {
    if (factored == Factored::Blocks)
      blocks.solve(b, x);
    else
      lu.solve(b, x);
  }
  /// x = H b, H = prod_j (I + s_{j+1} s_j^T / |s_j|^2) J0^-1: the quasi-Newton inverse after the
  /// Broyden updates of steps[0 .. num_steps), one per pair of consecutive steps of a sequence.
  void quasi_newton_solve(const VecX& b, VecX& x) const {
    linear_solve(b, x);
    for (int j = 0; j + 1 < num_steps; ++j)
      if (!starts[j + 1]) x += steps[j + 1] * (steps[j].dot(x) / step_norms2[j]);
  }
  /// Before a new sequence: keeps the last sequences of at most kCarriedSteps steps in all.
  void drop_old_steps() {
    int first = num_steps;
    for (int j = 0; j < num_steps; ++j) {
      if (starts[j] && num_steps - j <= kCarriedSteps) {
        first = j;
        break;
      }
    }
    for (int j = first; j < num_steps; ++j) {
      steps[j - first].swap(steps[j]);
      step_norms2[j - first] = step_norms2[j];
      starts[j - first] = starts[j];
    }
    num_steps -= first;
  }
};

// Validates the problem for Newton and sizes the workspace (only when the structure changed).
void NewtonSolver::Impl::prepare() {
  if (version == problem.structure_version()) return;
  require(!problem.has_objective(), "NewtonSolver: the problem has objective terms (use IpoptSolver)");
  const int n = problem.num_variables(), m = problem.num_rows();
  reduced_column.assign(n, -1);
  column_groups.clear();
  int n_free = 0;
  for (VariableId v = 0; v < problem.num_variable_blocks(); ++v) {
    const VariableBlock& b = problem.variable(v);
    const bool fixed = problem.variable_fixed(v);
    for (int j = 0; j < b.size; ++j) {
      if (fixed) continue;
      require(std::isinf(b.lower[j]) && std::isinf(b.upper[j]), "NewtonSolver: variable block '", b.name,
              "' entry ", j, " has bounds [", b.lower[j], ", ", b.upper[j],
              "] (Newton ignores bounds; use IpoptSolver)");
      reduced_column[b.offset + j] = n_free++;
      column_groups.push_back(b.group);
    }
  }
  require(n_free == m, "NewtonSolver: the problem is not square: ", n_free, " free variables, ", m,
          " active rows");
  const VecX lower = problem.row_lower(), upper = problem.row_upper();
  for (int i = 0; i < m; ++i) {
    if (lower[i] != upper[i] || !std::isfinite(lower[i])) {
      const ResidualId b = problem.residual_at_row(i);
      throw_input_error("NewtonSolver: residual block '", problem.residual(b).name(), "' row ",
                        i - problem.row_offset(b), " is not an equality: bounds [", lower[i], ", ", upper[i],
                        "]");
    }
  }
  target = lower;
  c.resize(m);
  r.resize(m);
  r_trial.resize(m);
  linear_check.resize(m);
  dx_free.resize(m);
  steps.assign(kMaxSteps, VecX::Zero(m));
  starts.assign(kMaxSteps, 1);
  step_norms2.assign(kMaxSteps, 0.0);
  num_steps = 0;
  dx = VecX::Zero(n);
  x_trial.resize(n);
  J = SparseRowMajor();
  value_map.clear();
  factored = Factored::None;
  version = problem.structure_version();
}

// Free-column copy of J's pattern (J must hold the problem's pattern) and its symbolic analysis.
void NewtonSolver::Impl::build_free_pattern() {
  // J_free in CSC straight from the row-major J: count the entries per free column, then place them
  // row by row, so each column's rows come out sorted and value_map is the position written.
  const int n = static_cast<int>(J.rows());
  std::vector<int> starts(n + 1, 0);
  for (int p = 0; p < J.nonZeros(); ++p) {
    const int col = reduced_column[J.innerIndexPtr()[p]];
    if (col >= 0) ++starts[col + 1];
  }
  for (int c = 0; c < n; ++c) starts[c + 1] += starts[c];
  J_free.resize(n, n);
  J_free.resizeNonZeros(starts[n]);
  std::copy(starts.begin(), starts.end(), J_free.outerIndexPtr());
  value_map.assign(J.nonZeros(), -1);
  for (int i = 0; i < J.outerSize(); ++i) {
    for (int p = J.outerIndexPtr()[i]; p < J.outerIndexPtr()[i + 1]; ++p) {
      const int col = reduced_column[J.innerIndexPtr()[p]];
      if (col < 0) continue;
      const int q = starts[col]++;
      J_free.innerIndexPtr()[q] = i;
      J_free.valuePtr()[q] = 0.0;
      value_map[p] = q;
    }
  }
  // The sparse LU's analysis waits until it is needed (factorize).
  sparse_analyzed = false;
  const bool grouped = std::any_of(column_groups.begin(), column_groups.end(), [](int g) { return g >= 0; });
  const bool structured = options.linear_solver == NewtonLinearSolver::BorderedBlocks ||
                          (options.linear_solver == NewtonLinearSolver::Auto && grouped);
  if (!structured || !blocks.analyze_pattern(J_free, column_groups)) blocks = BorderedBlockLu();
}

bool NewtonSolver::Impl::factorize(bool sparse_only) {
  factored = Factored::None;
  if (!sparse_only && blocks.analyzed() && blocks.factorize(J_free)) {
    factored = Factored::Blocks;
    return true;
  }
  if (!sparse_analyzed) {
    lu.analyze_pattern(J_free);
    sparse_analyzed = true;
  }
  if (!lu.factorize(J_free)) return false;
  factored = Factored::Sparse;
  return true;
}

NewtonSolver::NewtonSolver(const Problem& problem, NewtonOptions options)
    : impl_(std::make_unique<Impl>(problem, options)) {
  require(options.tolerance > 0.0, "NewtonOptions: tolerance = ", options.tolerance, " <= 0");
  require(options.max_iterations >= 0, "NewtonOptions: max_iterations = ", options.max_iterations, " < 0");
  require(options.armijo > 0.0 && options.armijo < 1.0, "NewtonOptions: armijo = ", options.armijo,
          " not in (0, 1)");
  require(options.backtrack > 0.0 && options.backtrack < 1.0,
          "NewtonOptions: backtrack = ", options.backtrack, " not in (0, 1)");
  require(options.min_step > 0.0 && options.min_step < 1.0, "NewtonOptions: min_step = ", options.min_step,
          " not in (0, 1)");
  impl_->prepare();
}

NewtonSolver::~NewtonSolver() = default;
void NewtonSolver::continue_path() {
  impl_->continue_path = true;
}

const NewtonOptions& NewtonSolver::options() const {
  return impl_->options;
}

const char* NewtonSolver::factorization_kind() const {
  switch (impl_->factored) {
    case Impl::Factored::Blocks: return "bordered blocks";
    case Impl::Factored::Sparse: return "sparse";
    default: return "none";
  }
}

SolveSummary NewtonSolver::solve(VecX& x) {
  return solve(x, impl_->options.max_iterations);
}

SolveSummary NewtonSolver::solve(VecX& x, int max_iterations, int max_jacobian_evaluations) {
  const auto start_time = std::chrono::steady_clock::now();
  Impl& w = *impl_;
  require(max_iterations >= 0, "NewtonSolver::solve: max_iterations = ", max_iterations, " < 0");
  require(max_jacobian_evaluations >= 0,
          "NewtonSolver::solve: max_jacobian_evaluations = ", max_jacobian_evaluations, " < 0");
  const NewtonOptions& o = w.options;
  w.prepare();
  const Problem& problem = w.problem;
  require(x.size() == problem.num_variables(), "NewtonSolver::solve: x has size ", x.size(), ", expected ",
          problem.num_variables());

  SolveSummary summary;
  summary.solver = "newton";
  int jacobian_evaluations = 0;
  auto finish = [&](SolveStatus status, std::string message) {
    summary.status = status;
    summary.message = std::move(message);
    summary.jacobian_evaluations = jacobian_evaluations;
    summary.residual_by_kind = problem.violation_by_kind(w.c);
    summary.residual_max_abs = 0.0;  // = problem.constraint_violation(w.c), without a second pass
    for (const auto& kind : summary.residual_by_kind)
      summary.residual_max_abs = std::max(summary.residual_max_abs, kind.second);
    // Never report a non-finite point as converged.
    if (summary.status == SolveStatus::Converged &&
        !(x.allFinite() && std::isfinite(summary.residual_max_abs))) {
      summary.status = SolveStatus::Diverged;
    }
    summary.wall_time_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
    return summary;
  };

  if (!x.allFinite()) {
    w.c.setConstant(std::numeric_limits<double>::infinity());
    return finish(SolveStatus::InvalidInput, "start point is not finite");
  }
  problem.evaluate_residuals(x, w.c);
  w.r = w.c - w.target;
  // With reuse_factorization, iterations first try the last factorisation J0 with Broyden's "good"
  // rank-one updates in Deuflhard's error-oriented form (QNERR, Newton Methods for Nonlinear Problems,
  // 2004, sec. 2.1.4): with steps s_0 = -J0^-1 r(x_0) (or the last Newton step) and x_{k+1} = x_k + s_k,
  //   w = -J0^-1 r(x_{k+1});  w += s_{j+1} (s_j . w) / |s_j|^2  for j = 0 .. k-1;
  //   theta = |w| / |s_k|,  alpha = (s_k . w) / |s_k|^2,  s_{k+1} = w / (1 - alpha).
  // The step is kept while theta <= chord_contraction (affine-invariant contraction; |alpha| <= theta
  // keeps 1 - alpha >= 1/2), else the iteration is redone from x_k with a fresh Jacobian. Convergence is
  // superlinear, against linear for the plain simplified Newton step.
  // Along a path (continue_path()) the updates outlive the solve: the first step of the next solve is
  // s = -H r with H after all kept updates (Broyden's good update holds for any step s = -H r, so a new
  // sequence simply starts there, and the recursion skips the pair that would join two sequences). The
  // Jacobian drifts mostly in the directions of the recent steps, which the kept updates follow; the
  // last kCarriedSteps steps are kept (whole sequences), a fresh Jacobian drops them all. Otherwise the
  // solve starts from the plain factorisation J0.
  if (!w.continue_path) w.num_steps = 0;
  w.continue_path = false;
  bool refresh = !(o.reuse_factorization && w.factored != Impl::Factored::None);
  bool have_correction = false;  // w.steps[w.num_steps - 1] is the next step from x
  auto take_step_from = [&](const VecX& x0, const VecX& step) {
    for (int j = 0; j < x0.size(); ++j) {
      const int col = w.reduced_column[j];
      w.x_trial[j] = x0[j] + (col >= 0 ? step[col] : 0.0);
    }
  };
  // Broyden update after the step w.steps[num_steps - 1] led to the residual r_new: appends the next
  // step and returns true if it contracts, false if a fresh Jacobian is needed.
  auto broyden_next = [&](const VecX& r_new) {
    if (w.num_steps >= Impl::kMaxSteps) return false;
    w.quasi_newton_solve(r_new, w.dx_free);
    w.dx_free = -w.dx_free;
    const VecX& s_k = w.steps[w.num_steps - 1];
    const double s2 = w.step_norms2[w.num_steps - 1];
    const VectorStats w_stats = stats_of(w.dx_free);
    if (!w_stats.finite || !(s2 > 0.0) || !(w_stats.norm <= o.chord_contraction * std::sqrt(s2)))
      return false;
    const double alpha = s_k.dot(w.dx_free) / s2;
    w.starts[w.num_steps] = 0;
    w.steps[w.num_steps] = w.dx_free / (1.0 - alpha);
    w.step_norms2[w.num_steps] = w.steps[w.num_steps].squaredNorm();
    ++w.num_steps;
    return true;
  };
  for (int iteration = 0;; ++iteration) {
    summary.iterations = iteration;
    const VectorStats r_stats = stats_of(w.r);
    if (!r_stats.finite) return finish(SolveStatus::Diverged, "non-finite residual");
    const double r_max = r_stats.max_abs;
    if (r_max <= o.tolerance)
      return finish(SolveStatus::Converged,
                    o.reuse_factorization ? std::to_string(jacobian_evaluations) + " Jacobian evaluations"
                                          : std::string());
    if (iteration >= max_iterations)
      return finish(SolveStatus::MaxIterations,
                    format("no convergence in %.0f iterations (|r|max = %.3g)", max_iterations, r_max));
    const double r_norm = r_stats.norm;

    if (!refresh) {
      if (!have_correction) {  // a new sequence: the quasi-Newton step with the kept updates
        w.drop_old_steps();
        VecX& s0 = w.steps[w.num_steps];
        w.quasi_newton_solve(w.r, s0);
        s0 = -s0;
        w.step_norms2[w.num_steps] = s0.squaredNorm();
        w.starts[w.num_steps++] = 1;
      }
      take_step_from(x, w.steps[w.num_steps - 1]);
      problem.evaluate_residuals(w.x_trial, w.c);
      w.r_trial = w.c - w.target;
      const VectorStats trial = stats_of(w.r_trial);
      const bool finite = trial.finite;
      // A step that lands within the tolerance is kept whatever the contraction test would say: near the
      // solution the corrections are dominated by round-off (|J0^-1| times the residual's noise), and a
      // fresh Jacobian there would be wasted.
      if (finite && trial.max_abs <= o.tolerance) {
        x.swap(w.x_trial);
        w.r.swap(w.r_trial);
        have_correction = false;
        continue;
      }
      if (finite && broyden_next(w.r_trial)) {
        x.swap(w.x_trial);
        w.r.swap(w.r_trial);
        have_correction = true;
        continue;
      }
      // Too slow or diverging: a fresh Jacobian, at the trial point if the step still reduced |r|.
      refresh = true;
      have_correction = false;
      if (finite && trial.norm < r_norm) {
        x.swap(w.x_trial);
        w.r.swap(w.r_trial);
        continue;  // convergence test and Newton step from the new point
      }
      problem.evaluate_residuals(x, w.c);
    }

    // Newton direction: J_free dx = -r.
    if (jacobian_evaluations >= max_jacobian_evaluations)
      return finish(SolveStatus::MaxIterations,
                    format("no convergence with %.0f Jacobian evaluations (|r|max = %.3g)",
                           max_jacobian_evaluations, r_max));
    problem.evaluate_residuals_and_jacobian(x, w.c, w.J);
    ++jacobian_evaluations;
    if (w.value_map.size() != static_cast<size_t>(w.J.nonZeros())) w.build_free_pattern();
    double* free_values = w.J_free.valuePtr();
    const double* values = w.J.valuePtr();
    for (size_t p = 0; p < w.value_map.size(); ++p) {
      if (w.value_map[p] >= 0) free_values[w.value_map[p]] = values[p];
    }
    if (!w.J_free.coeffs().allFinite()) return finish(SolveStatus::Diverged, "non-finite Jacobian entry");
    if (!w.factorize(false)) {
      return finish(SolveStatus::Singular, "sparse LU failed: " + w.lu.error_message());
    }
    double linear_residual = 0.0;
    for (;;) {
      w.linear_solve(w.r, w.dx_free);
      w.dx_free = -w.dx_free;
      w.linear_check.noalias() = w.J_free * w.dx_free;
      w.linear_check += w.r;
      linear_residual = w.linear_check.norm() / r_norm;
      // The structured LU pivots only within each block: redo an inaccurate solve with the sparse LU.
      if (linear_residual <= o.linear_residual_limit || w.factored != Impl::Factored::Blocks) break;
      if (!w.factorize(true))
        return finish(SolveStatus::Singular, "sparse LU failed: " + w.lu.error_message());
    }
    const double step = w.dx_free.lpNorm<Eigen::Infinity>();
    if (!(linear_residual <= o.linear_residual_limit)) {
      return finish(
          SolveStatus::Singular,
          format("ill-conditioned Jacobian: linear solve residual |J dx + r|/|r| = %.3g", linear_residual));
    }
    if (!(step <= o.max_step_ratio * (1.0 + x.lpNorm<Eigen::Infinity>()))) {
      return finish(SolveStatus::Singular,
                    format("ill-conditioned Jacobian: Newton step |dx|max = %.3g", step));
    }
    for (int j = 0; j < x.size(); ++j) {
      const int col = w.reduced_column[j];
      w.dx[j] = col >= 0 ? w.dx_free[col] : 0.0;
    }

    // Step length: accept alpha when either the residual decreases (Armijo on |r|_2) or the simplified
    // Newton correction dx_bar = -J^-1 r(x + alpha dx), computed with the same factorisation, satisfies
    // Deuflhard's natural monotonicity test |dx_bar| <= (1 - alpha/2) |dx| (affine invariant: not fooled
    // by rows of very different scales, where a full step can raise |r| and still be right).
    const double dx_norm = w.dx_free.norm();
    double alpha = 1.0;
    for (;;) {
      w.x_trial = x + alpha * w.dx;
      problem.evaluate_residuals(w.x_trial, w.c);
      w.r_trial = w.c - w.target;
      if (w.r_trial.allFinite()) {
        if (w.r_trial.norm() <= (1.0 - o.armijo * alpha) * r_norm) break;
        w.linear_solve(w.r_trial, w.linear_check);
        if (w.linear_check.allFinite() && w.linear_check.norm() <= (1.0 - 0.5 * alpha) * dx_norm) break;
      }
      alpha *= o.backtrack;
      if (alpha < o.min_step) {
        problem.evaluate_residuals(x, w.c);  // report the last accepted point
        return finish(SolveStatus::Failed,
                      format("line search found no decrease of |r| nor of the Newton correction along the "
                             "Newton step (|r|max = %.3g): local minimum of |r| or inconsistent system",
                             r_max));
      }
    }
    // Keep this factorisation for quasi-Newton steps while they contract fast enough (the full Newton
    // step is the first step of the Broyden sequence: J0 s_0 = -r holds exactly).
    refresh = true;
    have_correction = false;
    if (o.reuse_factorization && alpha == 1.0 && w.r_trial.allFinite()) {
      w.steps[0] = w.dx_free;
      w.step_norms2[0] = w.dx_free.squaredNorm();
      w.starts[0] = 1;
      w.num_steps = 1;
      have_correction = broyden_next(w.r_trial);
      refresh = !have_correction;
    }
    x.swap(w.x_trial);
    w.r.swap(w.r_trial);
  }
}

}  // namespace pcr
