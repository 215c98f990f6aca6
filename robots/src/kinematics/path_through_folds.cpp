// FK along a path of inputs through folds (path_through_folds.hpp).
#include "pcr/robots/path_through_folds.hpp"

#include <chrono>
#include <sstream>

#include "fold_continuation.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/robot_stability.hpp"
#include "solve_support.hpp"

namespace pcr {

const char* to_string(PathEventKind kind) {
  switch (kind) {
    case PathEventKind::Fold: return "fold";
    case PathEventKind::Snap: return "snap";
    case PathEventKind::Bifurcation: return "bifurcation";
  }
  return "?";
}

std::string PathThroughFoldsResult::summary() const {
  int reached = 0, folds = 0, snaps = 0, bifurcations = 0;
  const RobotSolution* first_failed = nullptr;
  for (const RobotSolution& p : points) {
    reached += p.summary.converged() ? 1 : 0;
    if (!p.summary.converged() && !first_failed) first_failed = &p;
  }
  for (const PathEvent& e : events) {
    folds += e.kind == PathEventKind::Fold ? 1 : 0;
    snaps += e.kind == PathEventKind::Snap ? 1 : 0;
    bifurcations += e.kind == PathEventKind::Bifurcation ? 1 : 0;
  }
  std::ostringstream s;
  s << points.size() << " points, " << reached << " reached; folds " << folds << ", snaps " << snaps
    << ", bifurcations " << bifurcations << "; " << steps << " continuation steps, " << iterations
    << " iterations, " << jacobian_evaluations << " Jacobians, " << wall_time_seconds << " s";
  if (first_failed) s << "; first failure: " << first_failed->summary.message;
  return s.str();
}

namespace {

using Clock = std::chrono::steady_clock;

double residual_max_abs(const RobotAssembly& a, const VecX& x) {
  VecX c;
  a.problem().evaluate_residuals(x, c);
  return c.size() ? (c - a.problem().row_lower()).cwiseAbs().maxCoeff() : 0.0;
}

/// The path point read from the state x with the segment's counts.
RobotSolution point_at(const RobotAssembly& a, const KinematicsOptions& ko,
                       const std::vector<std::vector<BasisDerivatives>>& bases, const VecX& x,
                       const kinematics::SegmentOutcome& seg, Clock::time_point start) {
  RobotSolution s = read_solution(a, x, bases);
  s.summary.solver = "newton-arclength";
  s.summary.iterations = seg.iterations;
  s.summary.jacobian_evaluations = seg.jacobian_evaluations;
  s.summary.residual_max_abs = residual_max_abs(a, x);
  s.summary.wall_time_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (seg.reached) {
    s.summary.status = SolveStatus::Converged;
    s.summary.message = "pseudo-arclength continuation, " + std::to_string(seg.steps) + " steps";
    if (ko.stability_verdict) s.stability_verdict = robot_stability(a, x);
  } else {
    s.summary.status = SolveStatus::Failed;
    s.summary.message = seg.stopped;
  }
  kinematics::append_contact_warning(s);
  return s;
}

}  // namespace

PathThroughFoldsResult solve_path_through_folds(const std::shared_ptr<const RobotAssembly>& assembly,
                                                const KinematicsOptions& kinematics,
                                                const std::vector<VecX>& path,
                                                const PathThroughFoldsOptions& options) {
  const auto start = Clock::now();
  require(!path.empty(), "solve_path_through_folds: the path has no point");
  for (const VecX& u : path) assembly->check_inputs(u);
  require(kinematics.solver == SolverKind::Newton, "solve_path_through_folds: needs the Newton solver");
  const RobotAssembly& a = *assembly;
  const auto bases = sample_bases(a, kinematics.centerline_points);
  PathThroughFoldsResult out;
  ForwardKinematics fk(assembly, kinematics);
  out.points.push_back(fk.solve(path[0]));
  out.iterations += out.points[0].summary.iterations;
  out.jacobian_evaluations += out.points[0].summary.jacobian_evaluations;
  bool ended = !out.points[0].summary.converged();
  VecX x = fk.state();
  int modes = ended || !options.count_unstable_modes ? -1 : kinematics::unstable_mode_count(a, x);
  std::string why_ended = ended ? "the first path point did not converge" : "";
  for (size_t k = 1; k < path.size(); ++k) {
    const auto t0 = Clock::now();
    kinematics::SegmentOutcome seg;
    if (ended) {
      seg.stopped = "not reached: " + why_ended;
    } else {
      seg = kinematics::continue_segment(a, x, modes, path[k - 1], path[k], static_cast<int>(k - 1),
                                         kinematics.tolerance, options);
      out.events.insert(out.events.end(), seg.events.begin(), seg.events.end());
      out.trace.insert(out.trace.end(), seg.trace.begin(), seg.trace.end());
      out.steps += seg.steps;
      out.iterations += seg.iterations;
      out.jacobian_evaluations += seg.jacobian_evaluations;
      x = seg.x;
      modes = seg.unstable_modes;
      if (!seg.reached) {
        ended = true;
        why_ended = seg.stopped;
      }
    }
    out.points.push_back(point_at(a, kinematics, bases, x, seg, t0));
    out.points.back().inputs = path[k];  // the requested inputs (x holds the fold's when not reached)
  }
  out.wall_time_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

}  // namespace pcr
