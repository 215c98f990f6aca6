#pragma once
// Interior-point solve of a Problem with Ipopt (hidden: no Ipopt header here; docs/design.md §5).
//   min f(x) (0 without objective terms)  s.t.  c_l <= c(x) <= c_u,  x_l <= x <= x_u.
// One IpoptApplication is initialised per solver and reused for every solve; with warm_start the
// previous primal-dual solution seeds the next solve. Fixed variables are constants at the values the
// start x holds, eliminated by Ipopt (fixed_variable_treatment make_parameter). After Ipopt returns, the
// unscaled constraint violation is recomputed here: status Converged only if it is <= constraint_tolerance
// and x is finite.
//
// NOT thread-safe: MUMPS in Ipopt 3.11 keeps global state, so there must be no concurrent Ipopt solves in
// one process (not even with different IpoptSolver objects).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/solve/problem.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr {

enum class IpoptHessian {
  ExactWhenAvailable,  ///< exact if Problem::provides_hessian(), else limited-memory BFGS
  LimitedMemory,
};

enum class IpoptScaling {
  None,           ///< nlp_scaling_method none
  GradientBased,  ///< Ipopt's default: rows/objective with gradients above 100 scaled down
};

struct IpoptOptions {
  double tol = 1e-8;                   ///< Ipopt "tol" (scaled overall NLP error)
  double constraint_tolerance = 1e-8;  ///< Ipopt "constr_viol_tol" and our unscaled acceptance test
  int max_iterations = 3000;           ///< "max_iter"
  IpoptHessian hessian = IpoptHessian::ExactWhenAvailable;
  int print_level = 0;          ///< "print_level" 0..12
  bool warm_start = true;       ///< seed solves after the first with the previous multipliers
  double warm_start_mu = 1e-6;  ///< "mu_init" for warm-started solves
  /// Default chosen with bench_solve (docs/benchmarks.md "Solvers"): gradient-based needs 8 instead of 12 iterations
  /// on HS071 with its objective scaled by 1e4, and is the same on well-scaled problems.
  IpoptScaling scaling = IpoptScaling::GradientBased;
  std::string linear_solver = "mumps";  ///< "linear_solver"
  /// Any other Ipopt option as (name, value), parsed by the option's registered type (integer, number,
  /// string); applied last, so it may override the fields above. Unknown or rejected: InputError.
  std::vector<std::pair<std::string, std::string>> extra_options;
};

class IpoptSolver {
 public:
  /// Throws InputError for invalid options or if Ipopt cannot be initialised.
  IpoptSolver(const Problem& problem, IpoptOptions options = {});
  ~IpoptSolver();
  IpoptSolver(const IpoptSolver&) = delete;
  IpoptSolver& operator=(const IpoptSolver&) = delete;

  /// x: start point in (its fixed entries are the fixed values), solution (or last iterate) out, size
  /// num_variables().
  SolveSummary solve(VecX& x);
  /// Forgets the stored multipliers: the next solve is a cold start.
  void reset_warm_start();
  const IpoptOptions& options() const;
  /// The constraint rows' multipliers at the last solve's end, in Ipopt's sign (its Lagrangian is
  /// f + lambda . c: a row held at its lower bound has lambda <= 0); empty before the first solve or when
  /// they were not finite.
  VecX constraint_multipliers() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pcr
