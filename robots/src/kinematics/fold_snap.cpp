// The snap's search for a landing point past a fold (segment_tracer.hpp, docs/paths_through_folds.md
// "Events"): by Newton from the fold state pushed along the fold mode, by the damped motion of the
// platforms from there.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "pcr/solve/newton_solver.hpp"
#include "pseudo_transient_snap.hpp"
#include "segment_tracer.hpp"

namespace pcr::kinematics {

namespace {

/// Pushes of the fold state along the fold mode (pushed_along_fold_mode: the largest platform or passive
/// joint coordinate moved by this much; 0.01 = 1 % of the length scale or ~0.02 rad) from which the snap
/// starts Newton, and the damped motion. The random sweeps' landings lie 2-15 mm and 0.04-0.75 rad from
/// their folds (docs/benchmarks.md); larger pushes stretch the rods along a mode that is linear only
/// at the fold, and Newton and the damped steps diverge from there. Newton from pushes of 0.01 and 0.03
/// either way went back to the fold state in 221 of 222 runs (58 snaps of random cold solves of
/// universal_pair, universal_passive, six_rus and planar_post; the other reached an equilibrium not
/// stable enough), at 12-20 iterations each (linear convergence onto the singular fold): only the
/// larger pushes are tried.
constexpr double kNewtonPushes[] = {0.1, 0.3, -0.1};
constexpr double kDampedPushes[] = {0.01, -0.01, 0.05, -0.05, 0.2, -0.2};

}  // namespace

bool SegmentTracer::snap(const ArcPoint& fold, int nu_fold_side, ArcPoint& landing, int& nu_landing) {
  // The snap happens when the input passes the fold's: the landing point is at the fold's inputs.
  const double target = fold.lambda + 1e-12;
  // A landing point no less stable than the ending branch (stable for a robot whose branch was stable);
  // an unknown verdict only where the ending branch's was unknown too.
  const auto acceptable = [nu_fold_side](int nu) {
    return nu_fold_side < 0 || (nu >= 0 && nu <= nu_fold_side);
  };
  if (snap_by_newton(fold, target, acceptable, landing, nu_landing)) return true;
  if (snap_by_pseudo_transient(fold, target, acceptable, landing, nu_landing)) return true;
  std::ostringstream why;
  if (nu_fold_side < 0)  // not counted (or unknown): any equilibrium was acceptable
    why << "no equilibrium found to snap to at path parameter " << segment_ + fold.lambda;
  else
    why << "no equilibrium as stable as the ending branch (" << unstable_modes_text(nu_fold_side)
        << ") found to snap to at path parameter " << segment_ + fold.lambda;
  out_.stopped = why.str();
  return false;
}

/// Damped Newton (NewtonSolver) on the FK system at the fold's inputs from starts away from the fold: the
/// fold state pushed along the fold mode (the tangent there, pointing from the ending branch to the one
/// beyond it) by growing amounts, either way, then the assembly's straight initial guess. The first
/// acceptable equilibrium that is not the fold state itself.
bool SegmentTracer::snap_by_newton(const ArcPoint& fold, double target, const Acceptable& acceptable,
                                   ArcPoint& landing, int& nu_landing) {
  NewtonOptions no;
  no.tolerance = tolerance_;
  NewtonSolver newton(a_.problem(), no);
  const VecX u = arc_.inputs_at(target);
  std::vector<VecX> starts;
  for (double amplitude : kNewtonPushes) starts.push_back(pushed_along_fold_mode(fold, amplitude));
  starts.push_back(a_.initial_guess());
  for (VecX& x : starts) {
    a_.set_inputs(x, u);
    if (!newton.solve(x, 60).converged() || !moved_from_fold(fold, x)) continue;
    nu_landing = unstable_mode_count(a_, x);
    if (acceptable(nu_landing) && land_at(fold, x, target, landing)) return true;
  }
  return false;
}

/// Pseudo-transient continuation (pseudo_transient_snap.hpp: damped platforms and passive joints, the
/// rods quasi-static) at the fold's inputs from the fold state pushed along the fold mode, either way:
/// the damped motion of the robot past the fold. The first acceptable equilibrium away from the fold.
bool SegmentTracer::snap_by_pseudo_transient(const ArcPoint& fold, double target,
                                             const Acceptable& acceptable, ArcPoint& landing,
                                             int& nu_landing) {
  const VecX u = arc_.inputs_at(target);
  // The platforms and passive joints damped alone, then with the diagonal shift on the other unknowns
  // (pseudo_transient_snap.hpp; 1e-3 of the dampers' unit stiffness).
  for (double shift : {0.0, 1e-3})
    for (double amplitude : kDampedPushes) {
      VecX x = pushed_along_fold_mode(fold, amplitude);
      a_.set_inputs(x, u);
      const PseudoTransientResult r = pseudo_transient_equilibrium(a_, x, tolerance_, shift);
      extra_jacobians_ += r.jacobian_evaluations;
      extra_iterations_ += r.iterations;
      if (!r.converged || !moved_from_fold(fold, r.x)) continue;
      nu_landing = unstable_mode_count(a_, r.x);
      if (acceptable(nu_landing) && land_at(fold, r.x, target, landing)) return true;
    }
  return false;
}

/// The fold state moved along the fold mode (the tangent there, pointing from the ending branch to the
/// one beyond it) so that its largest platform or passive joint coordinate moves by `amplitude` (a
/// position over the length scale, a quaternion component, a joint angle; the fold state's own mode
/// gives the shape of the push, the amplitude its size in the robot's terms, whatever the weights W of
/// the continuation). Without platforms and passive joints: amplitude x max_step along the tangent.
VecX SegmentTracer::pushed_along_fold_mode(const ArcPoint& fold, double amplitude) const {
  const VecX direction = arc_.predictor(fold, 1.0).x - fold.x;
  const Problem& problem = a_.problem();
  const double L0 = a_.length_scale();
  double largest = 0.0;
  auto measure = [&](VariableId v, int size, double scale) {
    const int offset = problem.variable(v).offset;
    for (int k = 0; k < size; ++k) largest = std::max(largest, std::abs(direction[offset + k]) / scale);
  };
  for (int i = 0; i < static_cast<int>(a_.model().platforms().size()); ++i) {
    measure(a_.platform_variable(i), 3, L0);
    if (problem.variable(a_.platform_variable(i)).size >= 7) {
      const int offset = problem.variable(a_.platform_variable(i)).offset + 3;
      for (int k = 0; k < 4; ++k) largest = std::max(largest, std::abs(direction[offset + k]));
    }
  }
  const std::vector<int>& joints = a_.model().passive_joints();
  for (int i = 0; i < static_cast<int>(joints.size()); ++i)
    measure(a_.passive_joint_variable(i), 1,
            a_.model().joints()[joints[i]].type == JointType::Prismatic ? L0 : 1.0);
  const double sigma = largest > 0.0 ? amplitude / largest : amplitude * o_.max_step;
  return arc_.predictor(fold, sigma).x;
}

/// Whether the equilibrium x is another one than the fold state (its first platform moved by more than
/// 1e-4 of the length scale; without platforms every x counts).
bool SegmentTracer::moved_from_fold(const ArcPoint& fold, const VecX& x) const {
  if (a_.model().platforms().empty()) return true;
  const double moved = (a_.platform_pose(x, 0).position - a_.platform_pose(fold.x, 0).position).norm();
  return moved >= 1e-4 * a_.length_scale();
}

/// The landing point x (an equilibrium at the target inputs) with its tangent, by the corrector at the
/// same inputs.
bool SegmentTracer::land_at(const ArcPoint& fold, const VecX& x, double target, ArcPoint& landing) {
  ArcPoint guess = fold;
  guess.x = x;
  guess.lambda = target;
  VecX e_lambda = VecX::Zero(fold.tangent.size());
  e_lambda[e_lambda.size() - 1] = 1.0;
  return arc_.at_lambda(guess, e_lambda, target, landing);
}

}  // namespace pcr::kinematics
