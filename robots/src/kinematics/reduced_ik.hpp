#pragma once
// Reduced-space inverse kinematics (internal header of pcr::robots): Ipopt over the inputs u only,
//   min_u f(u, x(u))  s.t.  g(x(u)) = 0 (targets),  sigma_j(x(u)) / sigma_max <= 1,  u_l <= u <= u_u,
// where x(u) is the forward kinematics solution: every evaluation at a new u runs a Newton solve of
// the square FK system, warm-started from the last converged one. Gradients by the implicit function
// theorem: S = dx/du = -J_x^-1 J_u (one sparse LU of the FK Jacobian per u, m_in solves), then
// df/du = df/dx S + df/du|_x, dg/du = dg/dx S. Hessian: limited-memory BFGS (the problem has only as
// many variables as inputs). A failed FK solve is reported to Ipopt as a failed evaluation (it cuts
// the step back), never as a result.
// Why not the full space: Ipopt over all ~1000 assembly variables with the effort objective ended in
// Restoration_Failed (L-BFGS on nonlinear equality constraints); here every iterate is an equilibrium.
// Model and data: ReducedIkModel (the FK system, the target rows, input layout, stress points) is built
// once and shared; ReducedIk holds one solver's state (the FK Newton workspace, x(u) and S cached for
// the last u) and the small Ipopt problem over u whose blocks evaluate through that state.
#include <memory>
#include <vector>

#include "ik_objectives.hpp"
#include "pcr/robots/kinematics.hpp"

namespace pcr::kinematics {

/// The FK system of an IK problem: its target blocks (target_residuals) inactive and the inputs fixed
/// (evaluations and solvers take their values from x). Square, in the IK problem's variable layout.
Problem forward_problem_of(const Problem& ik_problem, const RobotAssembly& assembly,
                           const std::vector<ResidualId>& target_residuals);

/// Whether the options need the reduced-space path from the start (an objective other than the input
/// distance, or stress limits); the input distance goes there when Newton cannot finish.
bool uses_reduced_space(const IkOptions& options);

struct ReducedIkModel {
  /// ik_problem: the IK square problem (inputs free, fixed target pose blocks) with the target blocks
  /// target_residuals. Validates options.ik (InputError naming the value).
  ReducedIkModel(std::shared_ptr<const RobotAssembly> assembly, const Problem& ik_problem,
                 const std::vector<ResidualId>& target_residuals, const KinematicsOptions& options);
  int num_inputs() const { return static_cast<int>(input_offsets.size()); }

  std::shared_ptr<const RobotAssembly> assembly;
  KinematicsOptions options;
  Problem forward;                     ///< FK: target rows off, inputs fixed (square)
  Problem targets;                     ///< only the target rows on
  std::vector<int> input_offsets;      ///< of each input in x
  VecX input_scales;                   ///< longest rod for lengths, 1 rad for angles
  std::vector<StressPoint> stress_at;  ///< with a stress limit
};

class ReducedIk {
 public:
  explicit ReducedIk(std::shared_ptr<const ReducedIkModel> model);
  ~ReducedIk();
  ReducedIk(const ReducedIk&) = delete;
  ReducedIk& operator=(const ReducedIk&) = delete;

  /// x: an FK equilibrium (or initial guess) of the IK problem's layout with the target poses in
  /// (they stay as they are), solution out (unchanged if no evaluation succeeded). reference: inputs
  /// for the distance term.
  SolveSummary solve(VecX& x, const VecX& reference);

  /// The reduced problem over the inputs (one variable block), for checks: prepare() sets the warm
  /// start x and the reference as solve() does; the problem's evaluations then run FK at each u.
  void prepare(const VecX& x, const VecX& reference);
  const Problem& problem() const;

  struct Evaluator;

 private:
  std::shared_ptr<Evaluator> evaluator_;
  struct Solver;
  std::unique_ptr<Solver> solver_;
};

}  // namespace pcr::kinematics
