#pragma once
// What every solve returns (collocation Newton and Ipopt, rod and robot shooting): an outcome is a
// value, never an exception.
#include <string>
#include <utility>
#include <vector>

namespace pcr {

enum class SolveStatus { Converged, MaxIterations, Infeasible, Singular, Diverged, InvalidInput, Failed };

/// "converged", "max_iterations", ...
const char* to_string(SolveStatus status);

struct SolveSummary {
  SolveStatus status = SolveStatus::Failed;
  std::string solver;  ///< "newton", "ipopt", "shooting-dormand_prince", ...
  /// Nonlinear iterations (Newton, quasi-Newton and Levenberg-Marquardt steps; Ipopt iterations), summed
  /// over every attempt of the solve (load steps, continuation steps, retries).
  int iterations = 0;
  /// Jacobian evaluations of the system (Newton and shooting: fresh Jacobians, each followed by an LU
  /// factorisation; Ipopt: constraint Jacobians), summed like iterations.
  int jacobian_evaluations = 0;
  /// Max-abs of the residual rows, unscaled: on a Problem (collocation) max |c_i(x) - bound| over all
  /// active rows as assembled; shooting: the boundary and balance residuals in SI units.
  double residual_max_abs = 0.0;
  /// Shooting: the same residuals each divided by its scale (length, 1, force, moment scale), the
  /// measure that the shooting tolerance tests. Solvers on a Problem leave it 0: their rows are already
  /// that measure (residual_max_abs).
  double residual_scaled_max_abs = 0.0;
  /// Newton on a Problem, converged above its tolerance: every residual row above the tolerance is within
  /// its round-off bound 2 eps sum_j |J_ij x_j| (no double-precision point need do better; stiff axial
  /// rows reach 1e-9), the largest of those bounds; 0 when converged within the tolerance.
  double residual_round_off = 0.0;
  std::vector<std::pair<std::string, double>> residual_by_kind;  ///< max-abs per residual block kind
  double objective = 0.0;
  double wall_time_seconds = 0.0;
  /// Shooting only (0 for the solvers on a Problem). Rod shooting: solves of the load continuation
  /// (1 = the full load at once); robot shooting: steps of the continuation in the inputs or targets
  /// that a failed direct solve fell back on (0 = none).
  int load_steps = 0;
  /// Shooting only: ODE steps of the final integration (robot: summed over the rods).
  int integration_steps = 0;
  std::string message;

  bool converged() const { return status == SolveStatus::Converged; }
  /// One line: "newton: converged in 4 iterations, |c|max = 3.1e-12, 0.21 ms" (with ", N load steps"
  /// after the iterations when load_steps > 0).
  std::string brief_report() const;
};

}  // namespace pcr
