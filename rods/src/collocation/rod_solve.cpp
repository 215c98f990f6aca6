#include "pcr/rods/rod_solve.hpp"

#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>

#include "mesh_tables.hpp"
#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/rods/stability/rod_stability.hpp"
#include "pcr/solve/free_jacobian.hpp"
#include "pcr/solve/ipopt_solver.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "pcr/solve/sparse_lu.hpp"
#include "shooting_start.hpp"

#include "pcr/splines/basis.hpp"
#include "pcr/splines/spline_curve.hpp"

namespace pcr {
namespace {

// End point of a rod of length L with constant body curvature theta / L leaving the origin along e3
// with R = I: integral_0^L exp(s hat(theta) / L) e3 ds (Rodrigues; a = theta / |theta|, w = |theta| / L):
// e3 sin(wL) / w + (a x e3) (1 - cos(wL)) / w + a (a . e3) (L - sin(wL) / w).
Vec3 arc_end(const Vec3& theta, double L) {
  const double angle = theta.norm();
  if (angle < 1e-8) return L * Vec3::UnitZ();
  const Vec3 a = theta / angle, e3 = Vec3::UnitZ();
  const double w = angle / L;
  return e3 * (std::sin(angle) / w) + a.cross(e3) * ((1.0 - std::cos(angle)) / w) +
         a * a.dot(e3) * (L - std::sin(angle) / w);
}

// Prescribed end frames along the continuation: at lambda = 0 where the initial guess has its ends (so
// that it solves the unloaded problem exactly), at lambda = 1 the model's. Orientation: q(lambda) =
// q0 (x) [cos(lambda phi), sin(lambda phi) a] with q0^-1 (x) q1 = [cos phi, sin phi a], phi in [0, pi]
// (slerp; the end turns about one axis to the model's quaternion with its sign, as the clamped end
// condition q = q1 asks). Position: the tip moves as the end of an arc bent by the rotation vector
// 2 lambda phi a (in the guess's tip frame), plus lambda times what that arc misses at lambda = 1; so a
// tip frame that a circular arc reaches is approached through the arcs, equilibria of pure bending,
// instead of along a straight line that compresses the rod through its buckling load. The base moves
// along a straight line (it is the guess's fixed end unless only the tip is clamped).
class MovingEnds {
 public:
  MovingEnds(const CollocationRod& rod, const VecX& x0, const RodVariables& vars) : model_(rod.model()) {
    length_ = rod.length(x0, vars);
    const RodState ends[2] = {rod.state_at(x0, vars, 0.0), rod.state_at(x0, vars, length_)};
    const RodEnd* model_ends[2] = {&model_.base, &model_.tip};
    for (int k = 0; k < 2; ++k) {
      start_[k].position = ends[k].position;
      start_[k].orientation = ends[k].quaternion.normalized();
      target_[k] = start_[k];
      if (model_ends[k]->kind == RodEndKind::Free) continue;
      target_[k].position = model_ends[k]->position;
      target_[k].orientation = path_orientation(*model_ends[k], start_[k].orientation);
      const double moved = (target_[k].position - start_[k].position).norm() / length_ +
                           (target_[k].orientation - start_[k].orientation).norm();
      moves_ = moves_ || moved > 1e-12;
    }
  }
  /// Whether the initial guess misses a prescribed end frame (else the model's own ends are used).
  bool moves() const { return moves_; }
  /// The model with its prescribed end frames at lambda (lambda < 1; at 1 the model itself).
  RodModel at(double lambda) const {
    RodModel m = model_;
    if (m.base.kind != RodEndKind::Free) {
      m.base.position = start_[0].position + lambda * (target_[0].position - start_[0].position);
      m.base.orientation = turned(start_[0].orientation, target_[0].orientation, lambda);
    }
    if (m.tip.kind != RodEndKind::Free) {
      const Quat& q0 = start_[1].orientation;
      const Vec3 theta = rotation_vector(q0, target_[1].orientation);
      const Mat3 R0 = rotation_matrix(q0);
      const Vec3 straight = R0 * arc_end(Vec3::Zero(), length_);
      auto arc = [&](double t) { return Vec3(R0 * arc_end(t * theta, length_) - straight); };
      m.tip.position =
          start_[1].position + arc(lambda) + lambda * (target_[1].position - start_[1].position - arc(1.0));
      m.tip.orientation = turned(q0, target_[1].orientation, lambda);
    }
    return m;
  }

 private:
  // The end orientation the path turns to: the model's (a collar prescribes only its axis R e3, but
  // its frame's rotation from the guess's tells which way the rod turns, e.g. by 0.9 turns rather than
  // by -0.1: the smallest rotation onto the axis took the collar of test_collocation_rod's 0.9-turn arc
  // to an inverted rod); for a spherical joint (no orientation prescribed) the start's.
  static Quat path_orientation(const RodEnd& end, const Quat& start) {
    return end.kind == RodEndKind::Spherical ? start : Quat(end.orientation.normalized());
  }
  // 2 phi a with q0^-1 (x) q1 = [cos phi, sin phi a], phi in [0, pi] (body frame of q0).
  static Vec3 rotation_vector(const Quat& q0, const Quat& q1) {
    const Quat d = quat_multiply(quat_conjugate(q0), q1);
    const Vec3 v = d.tail<3>();
    const Vec3 axis = v.norm() > 1e-12 ? Vec3(v.normalized()) : Vec3::UnitX();  // d = -1: any axis
    return 2.0 * std::atan2(v.norm(), d[0]) * axis;
  }
  static Quat turned(const Quat& q0, const Quat& q1, double lambda) {
    return quat_multiply(q0, quat_from_rotation_vector(lambda * rotation_vector(q0, q1)));
  }
  RodModel model_;
  RodEnd start_[2], target_[2];
  double length_ = 1.0;
  bool moves_ = false;
};

// Empty when the axial stretch is admissible (admissible_axial_stretch) at 4 n + 1 points along the rod,
// else where it is not. Newton can reach such states from the straight rod, e.g. when the two clamped
// ends coincide.
std::string collapse_of(const CollocationRod& rod, const VecX& x, const RodVariables& vars) {
  const std::shared_ptr<const collocation::MeshTables> mesh =
      collocation::mesh_tables(rod.discretization().degree, rod.discretization().elements);
  std::vector<Vec3> positions;
  std::vector<double> stretches;
  rod.sample_centerline(x, vars, mesh->check_basis, positions, stretches);
  for (size_t k = 0; k < stretches.size(); ++k) {
    if (!admissible_axial_stretch(stretches[k])) {
      std::ostringstream msg;
      msg << "axial stretch v3 = 1 + eps3 = " << stretches[k]
          << " at s = " << rod.length(x, vars) * k / (stretches.size() - 1)
          << " m (the rod is compressed to a point or inverted there; admissible: v3 > 0)";
      return msg.str();
    }
  }
  return {};
}

// x: the problem's values, or empty to start from `configuration` (CollocationRod::configuration_size()
// values; the straight rod when null).
SolveSummary solve_at(const CollocationRod& rod, const RodSolveOptions& options, double load_factor, VecX& x,
                      RodVariables& vars, const VecX* configuration = nullptr) {
  Problem problem;
  // One variable group: Newton factors the rod's band directly (NewtonLinearSolver::Auto).
  vars = rod.add_to_problem(problem, {}, load_factor, false, 0, configuration);
  if (x.size() != problem.num_variables()) x = problem.initial_values();
  if (options.solver == SolverKind::Newton) {
    NewtonOptions o;
    o.tolerance = options.tolerance;
    o.max_iterations = options.max_iterations;
    o.reuse_factorization = options.reuse_factorization;
    return NewtonSolver(problem, o).solve(x);
  }
  IpoptOptions o;
  o.tol = options.tolerance;
  o.constraint_tolerance = options.tolerance;
  o.max_iterations = options.max_iterations;
  return IpoptSolver(problem, o).solve(x);
}

// Sign of det J at the unloaded state (load factor 0, the initial guess) and at the solution.
// The unloaded state is the straight initial guess (whatever initial guess the solve itself used).
StabilityIndicator stability_of(const CollocationRod& rod, const VecX& x_solution, double tolerance) {
  Problem unloaded, loaded;
  rod.add_to_problem(unloaded, {}, 0.0);
  rod.add_to_problem(loaded, {}, 1.0);
  const VecX x0 = unloaded.initial_values();
  VecX c;
  unloaded.evaluate_residuals(x0, c);
  if (!(unloaded.constraint_violation(c) <= tolerance)) return StabilityIndicator::NotChecked;
  const int sign0 = jacobian_determinant_sign(unloaded, x0),
            sign1 = jacobian_determinant_sign(loaded, x_solution);
  if (sign0 == 0 || sign1 == 0) return StabilityIndicator::NotChecked;
  return sign0 == sign1 ? StabilityIndicator::SignKept : StabilityIndicator::Unstable;
}

// The values of a Problem holding the rod's variables alone, from `configuration` (the straight rod when
// null, exact at load factor 0).
VecX problem_values(const CollocationRod& rod, const VecX* configuration) {
  Problem probe;
  rod.add_variables(probe, false, -1, configuration);
  return probe.initial_values();
}

// The direct solve's start configuration: `initial`, else a coarse shooting solution
// (RodSolveOptions::shooting_start) or the stress-free shape (the straight rod without intrinsic strains).
VecX direct_start(const CollocationRod& rod, const RodSolveOptions& options, const VecX* initial) {
  if (initial) return *initial;
  std::optional<VecX> start;
  if (options.shooting_start) start = collocation::shooting_start(rod);
  if (!start) start = rod.stress_free_configuration();
  return std::move(*start);
}

// Where load stepping ended: the last converged state x at load factor lambda, the last solve's summary.
struct LoadStepping {
  VecX x;
  double lambda = 0.0;
  int steps = 0, iterations = 0;
  SolveSummary last;
};

// Continuation: lambda from 0 (the initial guess x0 is exact for zero load and the ends where the guess
// has them) to 1: loads and intrinsic strains scaled by lambda, prescribed end frames moved from the
// guess's to the model's (MovingEnds); step grows by 1.5 after a success and halves after a failure.
LoadStepping step_the_loads(const CollocationRod& rod, const RodSolveOptions& options, const VecX& x0,
                            RodVariables& vars) {
  const MovingEnds ends(rod, x0, vars);
  LoadStepping out;
  double step = 0.25, previous_step = 0.0;
  out.x = x0;
  VecX x_previous = x0;
  out.last.status = SolveStatus::Failed;
  while (out.lambda < 1.0 && out.steps < options.max_load_steps && step > 1e-7) {
    const double target = std::min(1.0, out.lambda + step);
    VecX trial = out.x;
    if (previous_step > 0.0)
      trial += (out.x - x_previous) * ((target - out.lambda) / previous_step);  // secant predictor
    if (ends.moves() && target < 1.0)
      out.last =
          solve_at(CollocationRod(ends.at(target), rod.discretization()), options, target, trial, vars);
    else
      out.last = solve_at(rod, options, target, trial, vars);
    out.iterations += out.last.iterations;
    ++out.steps;
    if (out.last.converged()) {
      x_previous = out.x;
      out.x = trial;
      previous_step = target - out.lambda;
      out.lambda = target;
      step *= 1.5;
    } else {
      step *= 0.5;
    }
  }
  return out;
}

// The solution after load stepping (that of lambda = 1, or the failed direct solve's with the stepping's
// status), its message naming both, and a failure where the result is inadmissible.
void take_load_stepping_result(const CollocationRod& rod, const LoadStepping& stepping, RodSolution& sol) {
  sol.load_steps = stepping.steps;
  std::ostringstream msg;
  msg << "direct solve failed (" << to_string(sol.summary.status)
      << (sol.summary.message.empty() ? "" : ": " + sol.summary.message)
      << "); load stepping: " << stepping.steps << " steps, reached lambda = " << stepping.lambda;
  if (stepping.lambda >= 1.0 && stepping.last.converged()) {
    sol.x = stepping.x;
    sol.summary = stepping.last;
  } else {
    sol.summary.status =
        stepping.last.status == SolveStatus::Converged ? SolveStatus::MaxIterations : stepping.last.status;
  }
  sol.summary.message = msg.str() + (sol.summary.message.empty() ? "" : "; " + sol.summary.message);
  const std::string collapse = sol.summary.converged() ? collapse_of(rod, sol.x, sol.variables) : "";
  if (!collapse.empty()) {
    sol.summary.status = SolveStatus::Failed;
    sol.summary.message += "; converged to an inadmissible state: " + collapse;
  }
}

}  // namespace

const char* to_string(StabilityIndicator s) {
  switch (s) {
    case StabilityIndicator::SignKept: return "sign_kept";
    case StabilityIndicator::Unstable: return "unstable";
    default: return "not_checked";
  }
}

const char* to_string(SolverKind solver) {
  return solver == SolverKind::Newton ? "newton" : "ipopt";
}

RodSolution solve_rod(const RodModel& model, const RodSolveOptions& options, const VecX* initial) {
  const auto start = std::chrono::steady_clock::now();
  RodSolution sol;
  sol.rod = std::make_shared<const CollocationRod>(model, options.discretization);
  const CollocationRod& rod = *sol.rod;
  const VecX start_configuration = direct_start(rod, options, initial);
  sol.summary = solve_at(rod, options, 1.0, sol.x, sol.variables, &start_configuration);
  int iterations = sol.summary.iterations;
  const std::string direct_collapse = sol.summary.converged() ? collapse_of(rod, sol.x, sol.variables) : "";
  if (!direct_collapse.empty()) {
    sol.summary.status = SolveStatus::Failed;
    sol.summary.message = "converged to an inadmissible state: " + direct_collapse;
  }
  // Continuation helps a Newton iteration that is lost far from the solution (or that reached an
  // inadmissible state), not one that stalls at round-off just above the tolerance: then the direct
  // result is reported as it is.
  const bool stalled_near_solution = direct_collapse.empty() && sol.summary.residual_max_abs < 1e-6;
  if (!sol.summary.converged() && options.load_stepping && !stalled_near_solution) {
    // From `initial` or the straight rod, exact at load factor 0.
    const LoadStepping stepping = step_the_loads(rod, options, problem_values(rod, initial), sol.variables);
    iterations += stepping.iterations;
    take_load_stepping_result(rod, stepping, sol);
  }
  sol.summary.iterations = iterations;
  if (options.check_stability && sol.summary.converged())
    sol.stability = stability_of(rod, sol.x, options.tolerance);
  if (options.stability_verdict && sol.summary.converged())
    sol.stability_verdict = rod_stability(rod, sol.x, sol.variables);
  sol.summary.wall_time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sol;
}

VecX refine_solution(const RodSolution& solution, const RodDiscretization& finer) {
  const CollocationRod& rod = *solution.rod;
  require(finer.formulation == rod.discretization().formulation,
          "refine_solution: the formulation must stay the same (",
          to_string(rod.discretization().formulation), ")");
  // Interpolation of the solution's spline at the Greville abscissae of the new basis: exact (up to
  // round-off) when the new space contains the old one (knot insertion), otherwise accurate to the
  // interpolation error, which is all an initial guess needs.
  const CollocationRod target(rod.model(), finer);
  const std::vector<double> tau = target.knots().greville();
  const int n_old = rod.num_control_points(), cp = rod.control_point_size();
  MatX points(cp, n_old);
  for (int i = 0; i < n_old; ++i)
    points.col(i) = solution.x.segment(solution.variables.control_point_offset + i * cp, cp);
  const SplineCurve curve(rod.knots(), points);
  const int n = target.num_control_points();
  MatX values(n, cp);
  for (int j = 0; j < n; ++j) values.row(j) = curve.evaluate(tau[j]).transpose();
  SparseLu lu;
  require(lu.compute(collocation_matrix(target.knots(), tau, 0)),
          "refine_solution: Greville interpolation matrix is singular");
  const MatX refined = lu.solve(values);  // n x cp
  VecX out = VecX::Zero(target.configuration_size());
  for (int j = 0; j < n; ++j) out.segment(j * cp, cp) = refined.row(j).transpose();
  if (solution.variables.wrench >= 0)  // condensed form: the constant force and moment carry over
    out.tail(6) = solution.x.segment(solution.variables.wrench_offset, 6);
  return out;
}

}  // namespace pcr
