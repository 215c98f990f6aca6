// One segment of a path through folds (fold_continuation.hpp).
#include "fold_continuation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "pcr/math/quaternion.hpp"
#include "pcr/robots/robot_stability.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "segment_tracer.hpp"

namespace pcr::kinematics {

int unstable_mode_count(const RobotAssembly& assembly, const VecX& x) {
  return unstable_mode_count(robot_stability(assembly, x));
}

int unstable_mode_count(const Stability& s) {
  return is_counted(s) ? s.unstable_modes : -1;
}

namespace {

/// Steps past a corner of the curve (step_past_corner: the input moved by this fraction of the segment,
/// the FK Newton solver at fixed inputs), and that solver's iteration budget. On planar_post's corner
/// Newton converged in 6-8 iterations for every d from 1e-8 to 1e-3 (16 at 1e-2), the platform
/// moving by 0.2 m per unit of lambda, as on the branch before: no jump.
constexpr double kCornerSteps[] = {1e-6, 1e-4, 1e-3};
/// The arclength step (a fraction of max_step) below which step() tries the step past a corner before it
/// halves on to min_step: on a smooth curve the predictor's error falls like ds^2 and the corrector
/// converges long before; at a corner it falls like ds (planar_post: 6.9e-7 at ds = 3.9e-6, 1.0e-9 at
/// 1.2e-8) and the corrector fails at every length.
constexpr double kCornerStepBelow = 2e-6;
/// Where Newton does not converge onto the path point (lambda = 1) from the step that passed it, the step
/// is taken again this much shorter (a Stewart-Gough input of the random sweep reached lambda = 0.987
/// and failed there; docs/benchmarks.md "Random FK sweeps").
constexpr double kEndStepCut = 0.25;
constexpr int kCornerIterations = 40;

/// Largest platform displacement [m] and rotation angle [rad] between two sets of poses.
void jump_between(const std::vector<Pose>& before, const std::vector<Pose>& after, PathEvent& e) {
  for (size_t p = 0; p < before.size(); ++p) {
    e.jump_position = std::max(e.jump_position, (after[p].position - before[p].position).norm());
    const Quat dq = quat_multiply(after[p].orientation, quat_conjugate(before[p].orientation));
    e.jump_rotation = std::max(e.jump_rotation, 2.0 * std::atan2(dq.tail<3>().norm(), std::abs(dq[0])));
  }
}

}  // namespace

std::vector<Pose> platform_poses(const RobotAssembly& a, const VecX& x) {
  std::vector<Pose> out;
  for (int p = 0; p < static_cast<int>(a.model().platforms().size()); ++p)
    out.push_back(a.platform_pose(x, p));
  return out;
}

bool SegmentTracer::step(const ArcPoint& p, int nu, double& ds, ArcPoint& q, int& nu_q, double& used) {
  bool tried_corner = false;
  while (ds >= o_.min_step) {
    if (ds < kCornerStepBelow * o_.max_step && !tried_corner) {
      tried_corner = true;
      if (step_past_corner(p, ds, q, nu_q, used)) return true;
    }
    const int before = arc_.iterations();
    if (!arc_.arclength_step(p, ds, q)) {
      ds *= 0.5;
      continue;
    }
    // Too sharp a turn of the tangent: the step may have jumped to another branch; shorter.
    if (arc_.weighted_dot(p.tangent, q.tangent) < 0.9 && ds > 16 * o_.min_step) {
      ds *= 0.5;
      continue;
    }
    nu_q = count(q.x);
    // Resolve events one at a time: the count changes by one at a fold or a simple bifurcation.
    if (nu >= 0 && nu_q >= 0 && std::abs(nu_q - nu) > 1 && ds > 1e-4) {
      ds *= 0.5;
      continue;
    }
    ++out_.steps;
    used = ds;
    if (o_.keep_trace) out_.trace.push_back({segment_ + q.lambda, q.tau(), nu_q, q.x});
    const int iterations = std::max(1, arc_.iterations() - before);
    const double grow = std::clamp(std::sqrt(3.0 / iterations), 0.5, 2.0);
    ds = std::min(o_.max_step, ds * grow);
    return true;
  }
  std::ostringstream why;
  why << "continuation step below " << o_.min_step << " at path parameter " << segment_ + p.lambda;
  out_.stopped = why.str();
  return false;
}

/// The corrector failed from p down to kCornerStepBelow x max_step: a corner of the curve, where a contact
/// switches at a collocation midpoint (the complementarity row's Fischer-Burmeister function is not smooth
/// where its gap and density both vanish). There the predictor misses the curve by O(ds) (a kink: the tangent
/// on the other side differs) and the bordered Newton stalls on the complementarity row however short the
/// step (planar_post, docs/benchmarks.md "Random FK sweeps"). The FK Newton solver (damped, at fixed inputs)
/// steps past it: at lambda + d from p, for d growing from kCornerSteps[0]; q gets the tangent there. A step,
/// counted in the budget; false when none converges (step() then halves on to min_step and stops with its
/// reason).
bool SegmentTracer::step_past_corner(const ArcPoint& p, double& ds, ArcPoint& q, int& nu_q, double& used) {
  if (!(p.tau() > 0.0)) return false;  // past a corner going backwards: not a way along the path
  NewtonOptions no;
  no.tolerance = tolerance_;
  NewtonSolver newton(a_.problem(), no);
  // q's tangent oriented forward in lambda: the corner's two sides are not aligned (the one after it,
  // oriented by p's, pointed back towards the corner on planar_post), and Newton at fixed inputs
  // reached q going forward.
  VecX forward = VecX::Zero(p.tangent.size());
  forward[forward.size() - 1] = 1.0;
  for (double d : kCornerSteps) {
    const double lambda = std::min(1.0, p.lambda + d);
    VecX x = p.x;
    a_.set_inputs(x, arc_.inputs_at(lambda));
    const SolveSummary s = newton.solve(x, kCornerIterations);
    extra_iterations_ += s.iterations;
    extra_jacobians_ += s.jacobian_evaluations;
    ArcPoint guess = p;
    guess.x = x;
    guess.lambda = lambda;
    if (!s.converged() || !arc_.at_lambda(guess, forward, lambda, q)) continue;
    nu_q = count(q.x);
    ++out_.steps;
    const VecX dy = arc_.free_vector(q.x, q.lambda) - arc_.free_vector(p.x, p.lambda);
    used = std::sqrt(arc_.weighted_dot(dy, dy));
    if (o_.keep_trace) out_.trace.push_back({segment_ + q.lambda, q.tau(), nu_q, q.x});
    ds = std::max(o_.min_step, std::min(o_.max_step, used));
    out_.stopped.clear();
    return true;
  }
  return false;
}

/// The fold between p (tau > 0) and q = p + ds (tau <= 0): Illinois (modified regula falsi) on the lambda
/// component tau(sigma) of the tangent along the arc from p. lambda(sigma) = lambda* - kappa (sigma -
/// sigma*)^2 / 2 near it, so the input error is quadratic in the arclength error.
ArcPoint SegmentTracer::locate_fold(const ArcPoint& p, double ds, const ArcPoint& q) {
  double lo = 0.0, f_lo = p.tau(), hi = ds, f_hi = q.tau();
  ArcPoint best = std::abs(f_lo) < std::abs(f_hi) ? p : q, r;
  int side = 0;
  for (int it = 0; it < 60 && hi - lo > 1e-9 * ds; ++it) {
    double c = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(c > lo && c < hi)) c = 0.5 * (lo + hi);
    if (!arc_.arclength_step(p, c, r) && !arc_.arclength_step(p, c = 0.5 * (lo + hi), r)) break;
    const double f = r.tau();
    if (std::abs(f) <= std::abs(best.tau())) best = r;
    if (f == 0.0 || std::abs(f) < 1e-14) break;
    if ((f > 0.0) == (f_lo > 0.0)) {
      lo = c;
      f_lo = f;
      if (side == -1) f_hi *= 0.5;  // Illinois: halve the stale end's value
      side = -1;
    } else {
      hi = c;
      f_hi = f;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  // The point with the smallest |tau| found: its lambda is within kappa (sigma - sigma*)^2 / 2 of the fold's.
  return best;
}

void SegmentTracer::locate_bifurcation(const ArcPoint& p, double ds, int nu, int nu_q) {
  double lo = 0.0, hi = ds;
  ArcPoint r, at_lo = p, at_hi;
  for (int it = 0; it < 50; ++it) {
    const double c = 0.5 * (lo + hi);
    if (!arc_.arclength_step(p, c, r)) break;
    const int nu_c = count(r.x);
    if (nu_c == nu) {
      lo = c;
      at_lo = r;
    } else {
      hi = c;
      at_hi = r;
    }
    if (at_hi.x.size() > 0 && std::abs(at_hi.lambda - at_lo.lambda) < o_.event_tolerance) break;
  }
  ArcPoint at = at_lo;
  if (at_hi.x.size() > 0) at.lambda = 0.5 * (at_lo.lambda + at_hi.lambda);
  PathEvent e = event(PathEventKind::Bifurcation, at, nu, nu_q);
  std::ostringstream d;
  d << "bifurcation at path parameter " << e.path_parameter << ": unstable modes " << nu << " -> " << nu_q
    << " without a fold (multiplicity " << std::abs(nu_q - nu) << "); the path stays on its branch";
  e.description = d.str();
  out_.events.push_back(e);
}

bool SegmentTracer::finish_at_end(const ArcPoint& p, const ArcPoint& q) {
  // Start from the chord between the points either side of lambda = 1.
  ArcPoint guess = q, end;
  const double theta = (1.0 - p.lambda) / (q.lambda - p.lambda);
  if (std::isfinite(theta)) guess.x = p.x + theta * (q.x - p.x);
  if (!arc_.at_lambda(guess, q.tangent, 1.0, end) && !arc_.at_lambda(p, p.tangent, 1.0, end)) {
    out_.stopped =
        "no convergence onto the path point from path parameter " + std::to_string(segment_ + p.lambda);
    return false;
  }
  out_.x = end.x;
  out_.unstable_modes = count(end.x);
  out_.reached = true;
  if (o_.keep_trace) out_.trace.push_back({segment_ + 1.0, end.tau(), out_.unstable_modes, end.x});
  return true;
}

/// The fold between p and q: report it; Stop ends the segment there (false), Snap lands on the stable
/// equilibrium it jumps to (p, nu: the landing point, true).
bool SegmentTracer::pass_fold(ArcPoint& p, int& nu, const ArcPoint& fold, int nu_beyond) {
  PathEvent e = event(PathEventKind::Fold, fold, nu, nu_beyond);
  std::ostringstream d;
  d << "fold at path parameter " << e.path_parameter << ": the branch with " << unstable_modes_text(nu)
    << " ends (beyond the fold: " << nu_beyond << ")";
  e.description = d.str();
  out_.events.push_back(e);
  out_.x = fold.x;
  if (o_.at_fold == FoldPolicy::Stop) {
    out_.ended_at_fold = true;
    out_.stopped = e.description;
    return false;
  }
  ArcPoint landing;
  int nu_landing = -1;
  if (!snap(fold, nu, landing, nu_landing)) return false;
  arc_.rebalance(landing);  // the branch it lands on may move faster in x than the start did
  PathEvent s = event(PathEventKind::Snap, fold, nu, nu_landing);
  s.platforms_before = platform_poses(a_, fold.x);
  s.platforms_after = platform_poses(a_, landing.x);
  s.platforms = s.platforms_after;
  jump_between(s.platforms_before, s.platforms_after, s);
  std::ostringstream text;
  text << "snap-through at path parameter " << s.path_parameter << ": the platforms jump by "
       << s.jump_position << " m and " << s.jump_rotation << " rad to an equilibrium with "
       << unstable_modes_text(nu_landing);
  s.description = text.str();
  out_.events.push_back(s);
  if (o_.keep_trace) out_.trace.push_back({segment_ + landing.lambda, landing.tau(), nu_landing, landing.x});
  p = landing;
  nu = nu_landing;
  out_.x = p.x;
  out_.unstable_modes = nu;
  return true;
}

SegmentOutcome SegmentTracer::run(const VecX& x_start, int modes_start) {
  out_.x = x_start;
  out_.unstable_modes = modes_start;
  ArcPoint p, q;
  if (arc_.start(x_start, p)) {
    int nu = modes_start, nu_q = 0;
    double ds = 0.5 * o_.max_step, used = 0.0;
    while (budget_left() && step(p, nu, ds, q, nu_q, used)) {
      if (p.tau() > 0.0 && q.tau() <= 0.0) {  // a fold between p and q
        const ArcPoint fold = locate_fold(p, used, q);
        if (fold.lambda >= 1.0) {  // the path point comes before it
          finish_at_end(p, fold);
          break;
        }
        int nu_beyond = nu_q;
        if (!o_.count_unstable_modes) {  // counted at the fold's sides only
          nu = unstable_mode_count(a_, p.x);
          nu_beyond = unstable_mode_count(a_, q.x);
        }
        if (!pass_fold(p, nu, fold, nu_beyond)) break;
        ds = 0.25 * o_.max_step;
        continue;
      }
      if (q.lambda >= 1.0) {
        if (finish_at_end(p, q)) {
          if (nu >= 0 && out_.unstable_modes >= 0 && out_.unstable_modes != nu)
            locate_bifurcation(p, used, nu, out_.unstable_modes);
          break;
        }
        // Newton at lambda = 1 failed from the chord and from p: the path bends too much between them for
        // either start; a shorter step from p ends nearer the path point.
        if (used * kEndStepCut < o_.min_step) break;
        out_.stopped.clear();
        ds = kEndStepCut * used;
        continue;
      }
      if (nu >= 0 && nu_q >= 0 && nu_q != nu) locate_bifurcation(p, used, nu, nu_q);
      p = q;
      nu = nu_q;
      out_.x = p.x;
      out_.unstable_modes = nu;
    }
    if (!out_.reached && out_.stopped.empty())
      out_.stopped = "step budget (" + std::to_string(o_.max_steps) + ") used up at path parameter " +
                     std::to_string(segment_ + p.lambda);
  } else {
    out_.stopped = "the bordered Jacobian is singular at path parameter " + std::to_string(segment_);
  }
  out_.iterations = arc_.iterations() + extra_iterations_;
  out_.jacobian_evaluations = arc_.jacobian_evaluations() + extra_jacobians_;
  return out_;
}

SegmentOutcome continue_segment(const RobotAssembly& assembly, const VecX& x_start, int modes_start,
                                const VecX& u_a, const VecX& u_b, int segment, double tolerance,
                                const PathThroughFoldsOptions& options) {
  SegmentTracer tracer(assembly, u_a, u_b, segment, tolerance, options);
  return tracer.run(x_start, modes_start);
}

}  // namespace pcr::kinematics
