#pragma once
// One segment of a path through folds (path_through_folds.hpp): pseudo-arclength continuation from a
// converged state at inputs u_a to u_b (arclength_corrector.hpp), with fold location, snap-through and
// bifurcation detection (internal header of pcr::robots).
#include <string>
#include <vector>

#include "pcr/robots/path_through_folds.hpp"

namespace pcr::kinematics {

struct SegmentOutcome {
  bool reached = false;     ///< converged at u_b
  VecX x;                   ///< at u_b when reached, else the last point (the fold, or where it stopped)
  int unstable_modes = -1;  ///< at x (-1: not counted, or the verdict is unknown)
  std::vector<PathEvent> events;
  std::vector<TracePoint> trace;  ///< options.keep_trace
  int steps = 0, iterations = 0, jacobian_evaluations = 0;
  bool ended_at_fold = false;  ///< FoldPolicy::Stop and a fold before u_b
  std::string stopped;         ///< why not reached
};

/// Unstable modes of the equilibrium x (robot_stability), -1 when the verdict is not a count.
int unstable_mode_count(const RobotAssembly& assembly, const VecX& x);
/// The same of a verdict already computed.
int unstable_mode_count(const Stability& s);

/// x_start: converged at u_a; modes_start: its unstable modes (-1: unknown or not counted). segment:
/// the path index of u_a (event path parameters are segment + lambda).
SegmentOutcome continue_segment(const RobotAssembly& assembly, const VecX& x_start, int modes_start,
                                const VecX& u_a, const VecX& u_b, int segment, double tolerance,
                                const PathThroughFoldsOptions& options);

}  // namespace pcr::kinematics
