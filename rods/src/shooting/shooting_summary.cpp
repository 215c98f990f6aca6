#include "pcr/rods/shooting/shooting_summary.hpp"

#include <cstdio>

namespace pcr {

const char* shooting_status_name(SolveStatus status) {
  switch (status) {
    case SolveStatus::Converged: return "converged";
    case SolveStatus::MaxIterations: return "max_iterations";
    case SolveStatus::Infeasible: return "infeasible";
    case SolveStatus::Singular: return "singular";
    case SolveStatus::Diverged: return "diverged";
    case SolveStatus::InvalidInput: return "invalid_input";
    case SolveStatus::Failed: return "failed";
  }
  return "unknown";
}

std::string ShootingSummary::brief_report() const {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), "%s: %s in %d iterations (%d load steps), |r|max = %.2e, %.3g ms",
                solver.c_str(), shooting_status_name(status), iterations, load_steps, residual_max_abs,
                1e3 * wall_time_seconds);
  std::string line(buffer);
  if (!message.empty()) line += " (" + message + ")";
  return line;
}

}  // namespace pcr
