#include "pcr/solve/solve_summary.hpp"

#include <cstdio>

namespace pcr {

const char* to_string(SolveStatus status) {
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

std::string SolveSummary::brief_report() const {
  char steps[48] = "";
  if (load_steps > 0)
    std::snprintf(steps, sizeof steps, ", %d load step%s", load_steps, load_steps == 1 ? "" : "s");
  char buffer[200];
  std::snprintf(buffer, sizeof buffer, "%s: %s in %d iteration%s%s, |c|max = %.3g, %.3g ms",
                solver.empty() ? "solver" : solver.c_str(), to_string(status), iterations,
                iterations == 1 ? "" : "s", steps, residual_max_abs, wall_time_seconds * 1e3);
  std::string line = buffer;
  if (!message.empty()) line += " (" + message + ")";
  return line;
}

}  // namespace pcr
