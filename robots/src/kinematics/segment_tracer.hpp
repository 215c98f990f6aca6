#pragma once
// The tracer of one segment of a path through folds (fold_continuation.hpp): the continuation with its
// events (fold_continuation.cpp) and the snap's search for a landing point (fold_snap.cpp). Internal
// header of pcr::robots.
#include <functional>
#include <vector>

#include "arclength_corrector.hpp"
#include "fold_continuation.hpp"

namespace pcr::kinematics {

/// The platforms' poses at the state x.
std::vector<Pose> platform_poses(const RobotAssembly& a, const VecX& x);

/// Pseudo-arclength continuation of one segment u_a -> u_b from a converged state, with fold location,
/// snap-through and bifurcation detection (continue_segment).
class SegmentTracer {
 public:
  SegmentTracer(const RobotAssembly& a, const VecX& u_a, const VecX& u_b, int segment, double tolerance,
                const PathThroughFoldsOptions& o)
      : a_(a), arc_(a, u_a, u_b, tolerance), segment_(segment), tolerance_(tolerance), o_(o) {}

  SegmentOutcome run(const VecX& x_start, int modes_start);

 private:
  int count(const VecX& x) const { return o_.count_unstable_modes ? unstable_mode_count(a_, x) : -1; }
  PathEvent event(PathEventKind kind, const ArcPoint& at, int before, int after) const {
    PathEvent e;
    e.kind = kind;
    e.path_parameter = segment_ + at.lambda;
    e.inputs = arc_.inputs_at(at.lambda);
    e.unstable_modes_before = before;
    e.unstable_modes_after = after;
    e.platforms = platform_poses(a_, at.x);
    return e;
  }
  /// One accepted step from p (step length ds adapted, nu at the new point); false when it cannot go on.
  bool step(const ArcPoint& p, int nu, double& ds, ArcPoint& q, int& nu_q, double& used);
  bool step_past_corner(const ArcPoint& p, double& ds, ArcPoint& q, int& nu_q, double& used);
  bool pass_fold(ArcPoint& p, int& nu, const ArcPoint& fold, int nu_beyond);
  ArcPoint locate_fold(const ArcPoint& p, double ds, const ArcPoint& q);
  void locate_bifurcation(const ArcPoint& p, double ds, int nu, int nu_q);
  bool finish_at_end(const ArcPoint& p, const ArcPoint& q);
  bool snap(const ArcPoint& fold, int nu_fold_side, ArcPoint& landing, int& nu_landing);
  using Acceptable = std::function<bool(int)>;
  bool snap_by_newton(const ArcPoint& fold, double target, const Acceptable& acceptable, ArcPoint& landing,
                      int& nu_landing);
  bool snap_by_pseudo_transient(const ArcPoint& fold, double target, const Acceptable& acceptable,
                                ArcPoint& landing, int& nu_landing);
  bool moved_from_fold(const ArcPoint& fold, const VecX& x) const;
  VecX pushed_along_fold_mode(const ArcPoint& fold, double amplitude) const;
  bool land_at(const ArcPoint& fold, const VecX& x, double target, ArcPoint& landing);
  bool budget_left() const { return out_.steps < o_.max_steps; }

  const RobotAssembly& a_;
  ArcCorrector arc_;
  int segment_;
  double tolerance_;
  const PathThroughFoldsOptions& o_;
  SegmentOutcome out_;
  int extra_jacobians_ = 0, extra_iterations_ = 0;  // of the pseudo-transient snaps (not the corrector's)
};

}  // namespace pcr::kinematics
