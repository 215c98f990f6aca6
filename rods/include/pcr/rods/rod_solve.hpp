#pragma once
// Solving one rod with its own end conditions: build the collocation problem, solve it with Newton
// (default for this square system) or Ipopt from the stress-free shape, and fall back to load stepping —
// continuation in a load factor lambda from 0 to 1 scaling all loads and intrinsic strains and moving
// prescribed end frames from where the initial guess has them to the model's, warm-started with a secant
// predictor — when the direct solve fails. A converged state whose axial stretch v3 = 1 + eps3 is not
// positive somewhere (a rod compressed to a point or inverted) is not admissible: it counts as a failure
// of the direct solve and, at the end, as a failed solve.
#include <memory>
#include <vector>

#include "pcr/rods/collocation_rod.hpp"
#include "pcr/rods/stability/stability.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr {

enum class SolverKind { Newton, Ipopt };
const char* to_string(SolverKind solver);

struct RodSolveOptions {
  RodDiscretization discretization;
  SolverKind solver = SolverKind::Newton;
  double tolerance = 1e-10;   ///< max-abs of the dimensionless residual (see collocation_rod.hpp)
  int max_iterations = 50;    ///< per solve
  bool load_stepping = true;  ///< automatic when the direct solve fails
  /// Without an initial guess: start the direct solve from a coarse shooting solve (shooting_start.cpp:
  /// RK4 with 4 steps, at most 8 iterations, then one integration of its base state on 16 + E steps,
  /// interpolated at the Greville abscissae) where it converges, else (and when false) from the stress-free
  /// shape. The result is the collocation solution either way.
  bool shooting_start = true;
  int max_load_steps = 400;
  /// Newton reuses its last LU factorisation with Broyden updates while the steps contract
  /// (NewtonOptions::reuse_factorization): fewer factorisations and Jacobians in a cold solve. The result
  /// satisfies the same tolerance; false takes a fresh Jacobian every iteration.
  bool reuse_factorization = true;
  /// Stability indicator of the result (RodSolution::stability); costs two sparse LU factorisations.
  bool check_stability = false;
  /// Stability verdict of a converged result (RodSolution::stability_verdict, rod_stability.hpp): the
  /// number of unstable modes of the equilibrium and its margin, from the second variation of the energy.
  /// Off by default: it costs 15-250 % of a cold solve (docs/benchmarks.md, "Stability verdict of single
  /// rods"); NotChecked without it.
  bool stability_verdict = false;
};

/// Stability indicator (docs/design.md §4): the sign of det J (the Jacobian of the collocation system with
/// respect to the free unknowns) at the solution against its sign in the unloaded state (load factor 0,
/// where the straight initial guess is the solution and is stable). det J vanishes where an equilibrium
/// path crosses a fold or a bifurcation (a zero eigenvalue of the second variation of the energy), so
/// a different sign means an odd number of such crossings lies between the two states, and for
/// conservative loads the solution has an odd number of unstable modes: e.g. the straight column above
/// the Euler load. The same sign does not prove stability: an even number of crossings keeps it, e.g.
/// above the second critical load, or a double critical mode such as the buckling of a rod with a
/// circular section (both bending directions at once).
enum class StabilityIndicator {
  NotChecked,  ///< not asked, not converged, singular, or the initial guess is not the unloaded solution
  SignKept,    ///< det J has the unloaded state's sign
  Unstable,    ///< det J changed sign: unstable equilibrium
};
const char* to_string(StabilityIndicator s);

struct RodSolution {
  SolveSummary summary;  ///< of the last solve; iterations summed over all load steps
  int load_steps = 0;    ///< 0 when the direct solve succeeded
  StabilityIndicator stability = StabilityIndicator::NotChecked;
  Stability
      stability_verdict;  ///< RodSolveOptions::stability_verdict (docs/design.md §4); NotChecked otherwise
  std::shared_ptr<const CollocationRod> rod;
  RodVariables variables;
  VecX x;  ///< all variables of the rod's problem (control points, then L)

  RodState at(double s) const { return rod->state_at(x, variables, s); }
  std::vector<RodState> sample(int num_points) const { return rod->sample(x, variables, num_points); }
  RodState base() const { return at(0.0); }
  RodState tip() const { return at(rod->length(x, variables)); }
};

/// Solves the rod, directly from the stress-free shape (CollocationRod::stress_free_configuration),
/// then if needed by load stepping from the straight rod; `initial` (a configuration of
/// CollocationRod::configuration_size() values) replaces both starts.
RodSolution solve_rod(const RodModel& model, const RodSolveOptions& options = {},
                      const VecX* initial = nullptr);

/// Control points of `solution` carried to another discretisation of the same formulation, by
/// interpolation at the new Greville abscissae (the same curve when the new space contains the old
/// one, e.g. after knot insertion).
VecX refine_solution(const RodSolution& solution, const RodDiscretization& finer);

}  // namespace pcr
