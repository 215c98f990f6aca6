// Hysteresis check of a forward kinematics result (branch_check.hpp).
#include "pcr/robots/branch_check.hpp"

#include <algorithm>
#include <sstream>

#include "pcr/core/error.hpp"

namespace pcr {

BranchComparison compare_with_cold_solve(const ForwardKinematics& fk, const RobotSolution& result,
                                         double threshold) {
  require(result.summary.converged(), "compare_with_cold_solve: the result did not converge");
  if (threshold < 0.0) threshold = 1e-6 * fk.assembly().length_scale();
  BranchComparison out;
  ForwardKinematics cold = fk.with_fresh_state();
  out.cold = cold.solve(result.inputs);
  out.cold_converged = out.cold.summary.converged();
  std::ostringstream d;
  if (!out.cold_converged) {
    d << "the cold solve did not converge (" << out.cold.summary.message << ")";
    out.description = d.str();
    return out;
  }
  for (size_t p = 0; p < result.platforms.size() && p < out.cold.platforms.size(); ++p)
    out.platform_distance = std::max(out.platform_distance,
                                     (result.platforms[p].position - out.cold.platforms[p].position).norm());
  out.different_branch = out.platform_distance > threshold;
  if (out.different_branch)
    d << "hysteresis: this equilibrium is " << out.platform_distance
      << " m (platform position) from the one a cold solve reaches at the same inputs ("
      << out.cold.summary.message << ")";
  else
    d << "the cold solve reaches the same equilibrium (within " << out.platform_distance << " m)";
  out.description = d.str();
  return out;
}

}  // namespace pcr
