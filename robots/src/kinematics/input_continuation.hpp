#pragma once
// Continuation in the actuation inputs, the fallback of ForwardKinematics::solve when the direct
// Newton solve fails (the start is outside Newton's contraction region):
//  - along a straight line u(t) = u0 + t (u1 - u0), adaptive steps in t (LineSteps): each step starts
//    from the secant extrapolation of the last two converged steps and may take a limited number of
//    fresh Jacobians (a step that needs more is too long and is cut); the next step from the predictor's
//    error (LineSteps::predictor_error), else grown by 2 after a fast step (<= 4 iterations) and by 1.25
//    after a slow one; the steps short of u1 are solved to a looser tolerance (SolveAtInputs's
//    `intermediate`), the last one to the full tolerance;
//  - one input at a time: legs that each change a single input, in a few orders. A straight
//    line through input space can run into a fold of the equilibrium manifold (its end state then lies
//    on another branch, out of reach of small steps) where a path around it does not: with this fallback the
//    long random planar sweep converged 97.3 % of its cold FK solves instead of 78.3 % (docs/benchmarks.md,
//    "Random FK sweeps").
#include <functional>
#include <string>

#include "pcr/core/types.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr::kinematics {

/// Solves the FK system at inputs u from the start x (in: start, out: last iterate) with at most
/// max_jacobians fresh Jacobians; intermediate: a step short of the end of a line (a looser tolerance).
using SolveAtInputs =
    std::function<SolveSummary(const VecX& u, VecX& x, int max_jacobians, bool intermediate)>;

struct ContinuationResult {
  bool converged = false;
  SolveSummary last;             ///< summary of the last step's solve
  int steps = 0;                 ///< solves attempted (all legs)
  int iterations = 0;            ///< Newton iterations of all steps
  int jacobian_evaluations = 0;  ///< fresh Jacobians of all steps
  std::string stopped_at;        ///< where it stopped, for the failure message (empty when converged)
};

/// Step control along a line: the first step (fraction of the line) and the factor a failed step is cut by.
/// predictor_error > 0: the next step from the error e = max_i w_i |x_i - x_pred,i| of the converged step's
/// predictor (weights w: ContinuationWeights), which grows like h^k (k = 2 for the secant, 1 for the
/// first step's start at the last state), so the next step h (predictor_error / e)^(1/k), by a factor in
/// [0.5, 4] (Deuflhard's step control for continuation, "Newton Methods for Nonlinear Problems" (2004),
/// section 5.1, with the observed predictor error in place of the contraction estimate).
struct LineSteps {
  double first = 0.5;
  double cut = 0.5;
  double predictor_error = 0.0;
};

/// Weights of the predictor error (LineSteps::predictor_error): 1 / scale of each unknown of the state
/// (lengths by a length scale, rotations and quaternions as they are), 0 for those it ignores.
using ContinuationWeights = VecX;

/// x: converged state at u0 in; on success the converged state at u1 (unchanged otherwise). weights:
/// needed with steps.predictor_error > 0 (size of x).
ContinuationResult continue_along_line(const SolveAtInputs& solve_at, const VecX& u0, const VecX& u1,
                                       int step_jacobians, VecX& x, const LineSteps& steps = {},
                                       const ContinuationWeights& weights = {});

/// Legs from u0 to u1 changing one input each, in the orders (k, k+1, ..., k-1) for k < max_orders;
/// every order starts again from the converged state at u0. Each leg is first tried as one direct solve
/// (at most direct_jacobians fresh Jacobians), then along its line. x as above.
ContinuationResult continue_one_input_at_a_time(const SolveAtInputs& solve_at, const VecX& u0, const VecX& u1,
                                                int direct_jacobians, int step_jacobians, int max_orders,
                                                VecX& x, const LineSteps& steps = {});

}  // namespace pcr::kinematics
