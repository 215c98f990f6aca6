#pragma once
// Forward and inverse kinematics of a robot (docs/design.md §4) on its assembly.
//  - ForwardKinematics: inputs -> platform poses, rod shapes and end wrenches (square system;
//    Newton by default). Each solve is warm-started from the previous solution; a failed solve is
//    retried by continuation in the inputs from the last converged state, then from the default inputs.
//  - InverseKinematics: platform targets -> inputs. A full-pose target on every DOF gives a square
//    system, solved by Newton when the result is inside the input bounds; otherwise (bounds active,
//    partial targets), and for the other objectives (actuation effort, elastic energy) and rod stress
//    limits (IkOptions), Ipopt minimises the objective in the reduced space of the inputs
//    (robots/src/kinematics/reduced_ik.hpp): Ipopt over u only, every evaluation a warm-started Newton
//    FK solve x(u), gradients by the implicit function theorem.
//  - Derivatives by the implicit function theorem on the assembled Jacobian.
// Poses are world-frame; rotations of poses in derivatives are world-frame rotation vectors.
//
// Model and data: what a kinematics object solves on - the assembly, the problems built
// from it (IK: targets as equations, bounds and objective, the FK system at a solution, the reduced
// space) and the options - is immutable once constructed and shared: by the objects over one
// std::shared_ptr<const RobotAssembly>, and by with_fresh_state() copies; the equilibrium at the default
// inputs (DefaultEquilibrium) even by every FK over one model and options. What a solve changes - the
// state x, the path predictor's history, the Newton / Ipopt workspaces, the last Jacobian sign - belongs
// to one object. So objects that share a model may solve in different threads at once (Newton paths
// only: Ipopt 3.11's MUMPS keeps global state, ipopt_solver.hpp). The objects are movable (the
// solvers' references into the model stay valid) and not copyable: a copy would either share the
// workspaces or silently lose them; with_fresh_state() makes the independent object explicitly.
#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pcr/robots/robot_assembly.hpp"
#include "pcr/robots/robot_solution.hpp"
#include "pcr/rods/rod_solve.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr {

/// What inverse kinematics minimises over the inputs u that reach the targets.
enum class IkObjective {
  InputDistance,    ///< 1/2 sum ((u_i - r_i) / scale_i)^2, r = reference inputs (scale: longest rod or 1 rad)
  ActuationEffort,  ///< 1/2 sum over fed rods of (n(0) . d3(0) / F0)^2 (axial force at the feed point)
  ElasticEnergy,    ///< (1/2 int_rods m_b^T K_BT^-1 m_b + n_b^T K_SE^-1 n_b ds) / M0, all rods
};
const char* to_string(IkObjective objective);

struct IkOptions {
  IkObjective objective = IkObjective::InputDistance;
  /// Weight of the input-distance term added to the effort or energy objective (regularisation; 0 = none).
  double distance_weight = 0.0;
  /// Upper limit [Pa] on every rod's outer-fibre stress |N| / A + |M_perp| c / I_min at
  /// stress_points_per_rod equally spaced points (c: the section's outer radius). Needs E and the
  /// outer radius of every rod (set by RodModel::set_material_and_section).
  std::optional<double> max_rod_stress;
  int stress_points_per_rod = 0;  ///< 0: 2 elements + 1 (element ends and midpoints)
  /// InputDistance without stress limits, targets that leave inputs free (fewer target rows than
  /// inputs): Ipopt over all assembly variables with the equations as constraints instead of the
  /// reduced space. Off by default: on stewart_gough with a position-only target the full-space Ipopt
  /// (L-BFGS) crawled to 3,000 iterations and 142 s without meeting its tolerance, 21 mm from the
  /// optimum that the reduced space reaches in 22 iterations and 0.4 s (docs/benchmarks.md,
  /// "IK objectives"). The full space is always used where the reduced one cannot be: as many target rows as
  /// inputs or more (e.g. a full-pose target on the planar robot, 3 of its rows redundant) when Newton
  /// does not finish (bounds active, or not square).
  bool full_space = false;
  /// Reduced space: Ipopt's "tol" and limit on the dimensionless target residual.
  double optimality_tolerance = 1e-8;
  double target_tolerance = 1e-9;
  int max_iterations = 200;  ///< Ipopt iterations in the reduced space
  /// Reduced space: an FK evaluation whose inputs lie farther than this from the last point with a
  /// sensitivity (Euclidean norm; rod lengths divided by the assembly's length scale, angles in rad)
  /// is refused, and Ipopt shortens its step. A long trial step can land the FK on another equilibrium
  /// branch near whose folds the next solves fail: stewart_gough, distance IK from the default inputs
  /// (test_ik_objectives), took 700 FK solves and 60 s without the limit, 38 and 0.6 s with 0.05.
  double max_input_step = 0.05;
};

struct KinematicsOptions {
  AssemblyOptions assembly;
  SolverKind solver = SolverKind::Newton;  ///< FK only; IK picks Newton or Ipopt as described above
  double tolerance = 1e-10;                ///< max-abs of the dimensionless residuals
  int max_iterations = 100;
  int centerline_points = 21;  ///< points per rod in the results
  /// false: RodResult::centerline is left empty (the rest of the results as with true; the axial stretch
  /// check still samples the centerline_points), for paths whose caller needs only inputs, poses and
  /// wrenches: the samples are about a tenth of a warm R5b solve (docs/benchmarks.md, "Time split of a
  /// warm R5b solve").
  bool read_centerline = true;
  /// Newton reuses its last factorisation across warm-started solves (see NewtonOptions).
  bool reuse_factorization = true;
  /// LU of the Newton systems: Auto factors each rod's band and condenses onto the platform poses and
  /// inputs (BorderedBlockLu), falling back to the sparse LU where a rod's block is singular;
  /// NewtonLinearSolver::Sparse always uses the sparse LU (general pattern, natural ordering).
  NewtonLinearSolver linear_solver = NewtonLinearSolver::Auto;
  /// Stability monitoring along the solves (RobotSolution::jacobian_sign), FK and IK (the FK system at
  /// the IK solution's inputs); costs one Jacobian evaluation and one sparse LU factorisation per
  /// converged solve (R5b with 8 elements per rod: about 1 + 3.5 ms, printed by bench_robots).
  bool check_stability = false;
  /// Stability verdict of every converged solve (RobotSolution::stability_verdict, robot_stability.hpp),
  /// FK and IK (the FK system at the IK solution's inputs): per rod its Jacobi integration and node
  /// elimination, for the platforms one Jacobian evaluation, one LU and 6 solves per platform. Off by
  /// default: Stewart-Gough about 5 ms, a third of a cold FK solve (docs/benchmarks.md). With it, an FK
  /// solve that starts from a stable equilibrium (cold: the default one; warm: the last solution) and ends
  /// on an unstable one also follows the line from that start through its folds and keeps the result with
  /// fewer unstable modes (docs/paths_through_folds.md "Which equilibrium forward kinematics returns").
  bool stability_verdict = false;
  IkOptions ik;  ///< inverse kinematics only
};

/// The equilibrium at the model's default inputs, solved by Newton (Ipopt for SolverKind::Ipopt) from
/// the straight initial guess: where a cold forward kinematics solve starts (and the continuations of its
/// fallbacks). Solved once per model and options that shape it (the assembly options, the solver and
/// its tolerance, iteration limit, factorisation reuse and linear solver) on first use, and shared by
/// every ForwardKinematics over them (also across threads): "Model and data" above.
struct DefaultEquilibrium {
  bool converged = false;
  VecX x;                ///< the assembly's variables; the straight initial guess when not converged
  SolveSummary summary;  ///< of its one solve
};

namespace kinematics {
struct FkData;
struct IkData;
}  // namespace kinematics

class ForwardKinematics {
 public:
  explicit ForwardKinematics(std::shared_ptr<const RobotModel> model, const KinematicsOptions& options = {});
  /// Over an assembly shared with other kinematics objects (options.assembly is not used: the assembly
  /// carries its own discretisation).
  explicit ForwardKinematics(std::shared_ptr<const RobotAssembly> assembly,
                             const KinematicsOptions& options = {});
  ForwardKinematics(ForwardKinematics&&) noexcept;
  ForwardKinematics& operator=(ForwardKinematics&&) noexcept;
  ~ForwardKinematics();
  ForwardKinematics(const ForwardKinematics&) = delete;
  ForwardKinematics& operator=(const ForwardKinematics&) = delete;
  /// Another FK on the same assembly and options with its own state, starting as a new object does.
  ForwardKinematics with_fresh_state() const;

  /// Solves for the given inputs (model order); throws InputError for a wrong size or out-of-bounds value.
  RobotSolution solve(const VecX& inputs);
  const RobotAssembly& assembly() const;
  const std::shared_ptr<const RobotAssembly>& assembly_ptr() const;
  /// The assembly's variables at the last converged solution.
  const VecX& state() const;
  bool has_solution() const;
  /// The start of cold solves (solved here if no ForwardKinematics over the same model and options
  /// needed it yet); the same object for all of them.
  const DefaultEquilibrium& default_equilibrium() const;

  /// d(platform poses)/d(inputs) at the last solution: 6 rows per platform [dx (3), dtheta (3)].
  MatX input_jacobian() const;
  /// d(pose of `platform`)/d(external wrench on it) at the last solution (6 x 6): columns are a
  /// force (3) at the platform origin and a torque (3), world frame.
  MatX compliance(int platform) const;

 private:
  explicit ForwardKinematics(std::unique_ptr<kinematics::FkData> data);
  kinematics::FkData& data() const;
  std::unique_ptr<kinematics::FkData> data_;
};

/// A target on a link carried by a platform. `mode` selects position (x, y, z, world frame) and/or
/// orientation (rotation about x, y, z of the target frame); `components` can switch single ones off,
/// for robots with fewer inputs than 6 per platform (e.g. a planar robot: x, z and rotation about y).
struct LinkTarget {
  std::string link;
  enum class Mode { Pose, Position, Orientation } mode = Mode::Pose;
  Pose pose;
  std::array<bool, 6> components{{true, true, true, true, true, true}};
};

class InverseKinematics {
 public:
  /// targets fix which links are targeted and how; their poses can change at every solve.
  InverseKinematics(std::shared_ptr<const RobotModel> model, const std::vector<LinkTarget>& targets,
                    const KinematicsOptions& options = {});
  /// Over an assembly shared with other kinematics objects (options.assembly is not used).
  InverseKinematics(std::shared_ptr<const RobotAssembly> assembly, const std::vector<LinkTarget>& targets,
                    const KinematicsOptions& options = {});
  InverseKinematics(InverseKinematics&&) noexcept;
  InverseKinematics& operator=(InverseKinematics&&) noexcept;
  ~InverseKinematics();
  InverseKinematics(const InverseKinematics&) = delete;
  InverseKinematics& operator=(const InverseKinematics&) = delete;
  /// Another IK on the same (shared) problems and options with its own state, starting as a new object
  /// does.
  InverseKinematics with_fresh_state() const;

  /// Solves for target poses (same order as the constructor's targets), warm-started from the
  /// previous solution. reference: inputs to stay close to (default: the previous solution's).
  RobotSolution solve(const std::vector<Pose>& target_poses, const VecX* reference = nullptr);
  const RobotAssembly& assembly() const;
  const std::shared_ptr<const RobotAssembly>& assembly_ptr() const;
  /// The square IK system, the layout of state(): the assembly's variables, then one fixed pose block
  /// [x (3), Q (4)] per target (target_variable); the targets as equations (target_residual), inputs free
  /// without bounds.
  const Problem& problem() const;
  VariableId target_variable(int target) const;
  ResidualId target_residual(int target) const;
  const VecX& state() const;
  /// Whether the targets fix every degree of freedom (square system).
  bool square() const;

 private:
  explicit InverseKinematics(std::unique_ptr<kinematics::IkData> data);
  kinematics::IkData& data() const;
  std::unique_ptr<kinematics::IkData> data_;
};

/// Results (poses, rods, wrenches) read from the assembly's variables x.
RobotSolution read_solution(const RobotAssembly& assembly, const VecX& x, int centerline_points);
/// The same with each rod's sample bases computed once (CollocationRod::sample_basis, one entry per
/// rod with max(2, centerline_points) points), for many solutions of one assembly.
/// with_centerline = false leaves RodResult::centerline empty (KinematicsOptions::read_centerline).
RobotSolution read_solution(const RobotAssembly& assembly, const VecX& x,
                            const std::vector<std::vector<BasisDerivatives>>& sample_bases,
                            bool with_centerline = true);
/// sample_bases for read_solution.
std::vector<std::vector<BasisDerivatives>> sample_bases(const RobotAssembly& assembly, int centerline_points);

}  // namespace pcr
