#pragma once
// Forward kinematics along a path of inputs through folds (docs/paths_through_folds.md): between
// consecutive path points the inputs move along the straight line u(lambda) = u_k + lambda (u_k+1 - u_k),
// and the equilibria are followed by pseudo-arclength continuation in (state, lambda) (Keller 1977;
// Allgower & Georg, Introduction to Numerical Continuation Methods, SIAM 2003), which passes limit
// points where continuation in lambda alone stops or jumps unseen.
//  - Fold (limit point): the lambda component of the curve's tangent changes sign; located by the
//    Illinois variant of regula falsi on it (the input error is quadratic in the arclength error
//    there). Past a fold the branch turns back: the path cannot stay on it. Reported with where it is
//    (path parameter, inputs) and the unstable-mode counts on both sides (robot_stability.hpp).
//  - Snap-through (FoldPolicy::Snap): the robot leaves the ending branch for another equilibrium at the
//    same inputs; found by Newton from the fold state pushed along the fold mode, else by the damped
//    motion of the platforms from there (pseudo-transient continuation); reported with the jump of the
//    platforms. FoldPolicy::Stop ends the path at the fold.
//  - Bifurcation: the number of unstable modes changes between two accepted points without a fold
//    (Maddocks, ARMA 99, 1987: at a fold the index changes by one with the sign of the lambda tangent);
//    located by bisection on the count, reported, and the path stays on its branch.
#include <memory>
#include <string>
#include <vector>

#include "pcr/robots/kinematics.hpp"

namespace pcr {

enum class FoldPolicy {
  Stop,  ///< report the fold, the points past it fail ("the branch ends")
  Snap,  ///< report the fold and follow the stable equilibrium the robot snaps to
};

struct PathThroughFoldsOptions {
  FoldPolicy at_fold = FoldPolicy::Stop;
  /// Unstable modes (robot_stability) at every accepted continuation point: bifurcations, the counts on
  /// both sides of a fold, and stable landing points of a snap need them. Off: folds only.
  bool count_unstable_modes = true;
  double max_step = 0.5;   ///< arclength per step, W-norm (the start tangent has |dlambda| = 1/sqrt(2))
  double min_step = 1e-8;  ///< a step that must be shorter has failed
  int max_steps = 400;     ///< per segment between two path points, snaps included
  /// Fold and bifurcation location: stop when the bracket in lambda (fraction of the segment) is below this.
  double event_tolerance = 1e-10;
  /// Keep every accepted continuation point in PathThroughFoldsResult::trace (a bifurcation diagram).
  bool keep_trace = false;
};

/// An accepted point of the continuation (the equilibrium curve; snap landings and the path points after
/// the first included).
struct TracePoint {
  double path_parameter = 0.0;  ///< segment + lambda
  double tau = 0.0;             ///< dlambda / dsigma: > 0 where the curve goes forward along the path
  int unstable_modes = -1;      ///< -1: not counted
  VecX state;                   ///< the assembly's variables (ForwardKinematics::state layout)
};

enum class PathEventKind { Fold, Snap, Bifurcation };
const char* to_string(PathEventKind kind);

struct PathEvent {
  PathEventKind kind = PathEventKind::Fold;
  /// Where: segment k + lambda, between path points k and k + 1 (lambda in [0, 1]).
  double path_parameter = 0.0;
  VecX inputs;
  /// Unstable modes on the side the path came from and on the other side (-1: not counted). Fold: the
  /// ending branch and the branch beyond the fold; Snap: at the fold and where it lands; Bifurcation:
  /// before and after.
  int unstable_modes_before = -1, unstable_modes_after = -1;
  /// Platform poses at the event (a snap: where it lands).
  std::vector<Pose> platforms;
  /// Snap: platform poses at the fold and after the jump, and the largest platform displacement [m] and
  /// rotation [rad] of the jump.
  std::vector<Pose> platforms_before, platforms_after;
  double jump_position = 0.0, jump_rotation = 0.0;
  std::string description;  ///< one line for people
};

struct PathThroughFoldsResult {
  /// One per path point; a point past a fold that ends the path is failed (status Failed, the message
  /// says why; its values are those at the fold, never NaN).
  std::vector<RobotSolution> points;
  std::vector<PathEvent> events;  ///< in path order
  std::vector<TracePoint> trace;  ///< options.keep_trace: every accepted continuation point
  int steps = 0;                  ///< accepted continuation steps
  int iterations = 0, jacobian_evaluations = 0;
  double wall_time_seconds = 0.0;
  /// "N points, M reached; folds F, snaps S, bifurcations B; ..." with the first failure's reason.
  std::string summary() const;
};

/// FK along the path of inputs (model order, each within bounds): the first point by a ForwardKinematics
/// solve (cold), the rest by continuation. kinematics gives the tolerance (Newton only), the centerline
/// points and whether each point gets its stability verdict (stability_verdict; the unstable modes are
/// counted anyway when options.count_unstable_modes). Throws InputError for a wrong size or
/// out-of-bounds input, or for an empty path.
PathThroughFoldsResult solve_path_through_folds(const std::shared_ptr<const RobotAssembly>& assembly,
                                                const KinematicsOptions& kinematics,
                                                const std::vector<VecX>& path,
                                                const PathThroughFoldsOptions& options = {});

}  // namespace pcr
