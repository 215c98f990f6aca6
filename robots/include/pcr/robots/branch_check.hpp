#pragma once
// Hysteresis check of a forward kinematics result (docs/paths_through_folds.md): where several equilibria
// exist for the same inputs, a warm-started solve stays on the branch it came from, while a cold solve
// (a fresh ForwardKinematics: Newton from the straight initial guess, then continuation from the default
// inputs) reaches another. This compares the two.
#include <string>

#include "pcr/robots/kinematics.hpp"

namespace pcr {

struct BranchComparison {
  bool cold_converged = false;
  /// Largest platform position difference [m] between the result and the cold solve (0 when not converged).
  double platform_distance = 0.0;
  /// Both converged and their platforms differ by more than the threshold: the result is on another branch
  /// than the cold solve reaches (hysteresis: the inputs' history decides which equilibrium the robot is in).
  bool different_branch = false;
  RobotSolution cold;       ///< the cold solve (with the same options as fk's)
  std::string description;  ///< one line for people
};

/// Solves `result.inputs` cold with fk's model and options (fk.with_fresh_state()) and compares platform
/// positions; threshold [m] (default 1e-6 of the assembly's length scale).
BranchComparison compare_with_cold_solve(const ForwardKinematics& fk, const RobotSolution& result,
                                         double threshold = -1.0);

}  // namespace pcr
