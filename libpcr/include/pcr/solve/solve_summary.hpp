#pragma once
// What every solve returns: an outcome is a value, never an exception.
#include <string>
#include <utility>
#include <vector>

namespace pcr {

enum class SolveStatus { Converged, MaxIterations, Infeasible, Singular, Diverged, InvalidInput, Failed };

/// "converged", "max_iterations", ...
const char* to_string(SolveStatus status);

struct SolveSummary {
  SolveStatus status = SolveStatus::Failed;
  std::string solver;  ///< "ipopt" or "newton" (or another method's name)
  int iterations = 0;
  /// Jacobian evaluations of the system (Newton: fresh Jacobians, each followed by a numeric LU
  /// factorisation; Ipopt: constraint Jacobians), summed over every attempt of a kinematics solve.
  int jacobian_evaluations = 0;
  double residual_max_abs = 0.0;  ///< unscaled max |c_i(x) - bound| over all active rows
  std::vector<std::pair<std::string, double>> residual_by_kind;  ///< max-abs per residual block kind
  double objective = 0.0;
  double wall_time_seconds = 0.0;
  std::string message;

  bool converged() const { return status == SolveStatus::Converged; }
  /// One line: "newton: converged in 4 iterations, |c|max = 3.1e-12, 0.21 ms".
  std::string brief_report() const;
};

}  // namespace pcr
