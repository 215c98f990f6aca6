#include "pcr/rods/shooting/shooting_summary.hpp"

#include <cstdio>

namespace pcr {

std::string ShootingSummary::brief_report() const {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), "%s: %s in %d iterations (%d load steps), |r|max = %.2e, %.3g ms",
                solver.c_str(), to_string(status), iterations, load_steps, residual_max_abs,
                1e3 * wall_time_seconds);
  std::string line(buffer);
  if (!message.empty()) line += " (" + message + ")";
  return line;
}

}  // namespace pcr
