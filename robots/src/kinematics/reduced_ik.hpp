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
#include <memory>
#include <vector>

#include "pcr/robots/kinematics.hpp"

namespace pcr::kinematics {

/// The FK system of an IK problem: the target rows (kind "target.pose") inactive and the inputs fixed
/// (at their initial values; evaluations take them from x). Square, in the IK problem's variable layout.
Problem forward_problem_of(const Problem& ik_problem, const RobotAssembly& assembly);

class ReducedIk {
 public:
  /// ik_problem: the assembly's problem with the IK target blocks (kind "target.pose") and the fixed
  /// target variable blocks target_variables. Validates options.ik (InputError naming the value).
  ReducedIk(const RobotAssembly& assembly, const Problem& ik_problem,
            std::vector<VariableId> target_variables, const KinematicsOptions& options);
  ~ReducedIk();
  ReducedIk(const ReducedIk&) = delete;
  ReducedIk& operator=(const ReducedIk&) = delete;

  void set_target(int target, const VecX& pose7);
  /// x: an FK equilibrium (or initial guess) of the IK problem's layout in, solution out (unchanged
  /// if no evaluation succeeded). reference: inputs for the distance term.
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

/// Whether the options need the reduced-space path from the start (an objective other than the input
/// distance, or stress limits); the input distance goes there when Newton cannot finish.
bool uses_reduced_space(const IkOptions& options);

}  // namespace pcr::kinematics
