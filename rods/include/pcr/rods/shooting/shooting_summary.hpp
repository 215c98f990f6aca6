#pragma once
// Outcome of a shooting solve. Same fields as pcr::SolveSummary (pcr/solve/solve_summary.hpp), kept
// separate until the solver summary's implementation is merged; the lead unifies them.
#include <string>

#include "pcr/solve/solve_summary.hpp"

namespace pcr {

struct ShootingSummary {
  SolveStatus status = SolveStatus::Failed;
  std::string solver = "shooting";
  int iterations = 0;             ///< Newton / Levenberg-Marquardt iterations over all load steps
  double residual_max_abs = 0.0;  ///< unscaled max |r_i| of the boundary residuals at the tip (SI units)
  double residual_scaled_max_abs = 0.0;  ///< same, divided by L, 1, F_c or M_c (what the tolerance tests)
  double wall_time_seconds = 0.0;
  int load_steps = 0;         ///< solves in the load continuation (1 = full load at once)
  int integration_steps = 0;  ///< ODE steps of the last integration
  std::string message;

  bool converged() const { return status == SolveStatus::Converged; }
  /// One line: "shooting: converged in 4 iterations, |r|max = 3.1e-12, 0.21 ms".
  std::string brief_report() const;
};

}  // namespace pcr
