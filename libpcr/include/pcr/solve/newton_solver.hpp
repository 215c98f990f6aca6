#pragma once
// Damped Newton for square, equality-only problems c(x) = c_l (= c_u), no objective, no bounds on the
// free variables (docs/design.md §5 "skip what a scene does not need"). Fixed variables are constants: they
// keep the values they have in the x passed to solve() (write Problem::fix_variable's values there).
//   J dx = -(c(x) - c_l)   (LU: pattern analysed once, numeric factorisation per iteration)
//   x <- x + alpha dx,  alpha = 1, 1/2, ... until |r(x + alpha dx)|_2 <= (1 - armijo alpha) |r(x)|_2
//   or Deuflhard's natural monotonicity test holds (newton_loop.hpp, the loop this solver runs).
// Converged when max_i |c_i - c_l,i| <= tolerance (unscaled) and x is finite.
#include <limits>
#include <memory>

#include "pcr/core/types.hpp"
#include "pcr/solve/problem.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr {

/// The LU factorisation of the Newton systems.
enum class NewtonLinearSolver {
  /// BorderedBlocks when the problem tags variable groups (VariableBlock::group, e.g. one per rod in a
  /// robot assembly), else Sparse.
  Auto,
  Sparse,          ///< SparseLu (Eigen's supernodal SparseLU) on the whole free Jacobian
  BorderedBlocks,  ///< BorderedBlockLu: a band LU per group and a Schur complement on the rest
};

struct NewtonOptions {
  double tolerance = 1e-10;  ///< on max_i |c_i(x) - c_l,i| over the active rows, as assembled
  int max_iterations = 50;
  double armijo = 1e-4;    ///< sufficient decrease factor of the line search
  double backtrack = 0.5;  ///< step reduction factor
  double min_step = 1e-8;  ///< line search gives up below this alpha
  /// Singular / ill-conditioned detection: a step larger than max_step_ratio * (1 + |x|_inf), or a linear
  /// solve with relative residual |J dx + r| / |r| above linear_residual_limit.
  double max_step_ratio = 1e10;
  double linear_residual_limit = 1e-6;
  /// Quasi-Newton across iterations and solves: reuse the last LU factorisation J0 with Broyden
  /// rank-one updates (Deuflhard's QNERR) while the steps contract, |s_{k+1}| (1 - alpha) <=
  /// chord_contraction |s_k| (affine-invariant measure); otherwise take a fresh Newton step. Pays off
  /// for warm-started sequences (FK/IK along a path), where the Jacobian barely changes; along a path
  /// the updates can also carry over to the next solve (NewtonSolver::continue_path).
  bool reuse_factorization = false;
  double chord_contraction = 0.7;
  /// With BorderedBlocks (or Auto choosing it), a factorisation whose block or Schur complement is
  /// singular, or whose Newton step fails the linear residual check, is redone with the sparse LU.
  NewtonLinearSolver linear_solver = NewtonLinearSolver::Auto;
};

/// Holds the factorisation workspace; solve() allocates nothing after the first call unless the
/// problem's structure changed. Not thread-safe (one solve at a time per solver and problem).
class NewtonSolver {
 public:
  /// Throws InputError if problem is not square / equality-only / free of objective terms and bounds.
  NewtonSolver(const Problem& problem, NewtonOptions options = {});
  ~NewtonSolver();
  NewtonSolver(const NewtonSolver&) = delete;
  NewtonSolver& operator=(const NewtonSolver&) = delete;

  /// x: start point in, final iterate out (size num_variables()). The entries of fixed variables are
  /// the values used (not overwritten with the Problem's: the caller writes them, e.g. set_inputs).
  SolveSummary solve(VecX& x);
  /// The same with other limits for this solve: iterations (quasi-Newton steps included) and fresh
  /// Jacobians (e.g. a short budget for a continuation step, which fails fast when it is too long).
  SolveSummary solve(VecX& x, int max_iterations,
                     int max_jacobian_evaluations = std::numeric_limits<int>::max());
  const NewtonOptions& options() const;
  /// The next solve continues the path of the last ones (e.g. its start was extrapolated from them): its
  /// first quasi-Newton step uses the Broyden updates kept from them (the last few steps), which follow
  /// the drift of the Jacobian along the path. By default a solve starts from the plain factorisation:
  /// for starts off the path the kept updates point the wrong way (more fresh Jacobians, measured).
  void continue_path();
  /// Which LU holds the last factorisation: "bordered blocks", "sparse" or "none".
  const char* factorization_kind() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Whether every residual |r_i| above tolerance is within its round-off bound 2 eps sum_j |J_ij x_j|
/// (twice what changing every unknown by one unit in the last place can change r_i by: no point in double
/// precision need do better) and within kRoundOffTolerances x tolerance x max(1, max_j |x_j| / scale_j)
/// over the unknowns j of row i (scale: Problem::variable_scales(), one per unknown); bound: the largest
/// bound of those rows (0 when none is above tolerance).
bool residuals_within_round_off(const Eigen::SparseMatrix<double, Eigen::RowMajor>& J, const VecX& x,
                                const VecX& scale, const VecX& r, double tolerance, double& bound);
/// How far above the tolerance a residual at its round-off is still accepted, for rows whose unknowns
/// are of their natural magnitude (VariableBlock::scale). Rows balancing unknowns n times larger (a rod
/// pressed on a post with 1e5 times its force scale) carry n times the round-off, and are accepted up to
/// n times more. Large round-off bounds from a stiff Jacobian with unknowns of natural size are not:
/// slender rods in the primal form stall at 1e-9 - 1e-7, where their solution is wrong by a locking error
/// of 60 % and more (docs/benchmarks.md "Hard single rods").
constexpr double kRoundOffTolerances = 10.0;

}  // namespace pcr
