#include "reduced_ik.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "ik_objectives.hpp"
#include "pcr/core/error.hpp"
#include "pcr/solve/free_jacobian.hpp"
#include "pcr/solve/ipopt_solver.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "pcr/solve/sparse_lu.hpp"

namespace pcr::kinematics {

/// x(u), its sensitivity S = dx/du and the reduced functions, cached for the last u.
struct ReducedIk::Evaluator {
  const std::shared_ptr<const ReducedIkModel> model;  // first: outlives the solver that refers into it
  const RobotAssembly& assembly;
  const KinematicsOptions& options;
  std::unique_ptr<NewtonSolver> newton;  // on model->forward
  VecX reference;
  SparseLu lu;  // of the free FK Jacobian (implicit function theorem)
  bool pattern_analysed = false;
  // Cache.
  VecX x_warm, x_start, u_cached, x;
  bool valid = false, ok = false, have_sensitivity = false, converged_once = false;
  MatX S;                     // dx/du, num_variables x num_inputs
  VecX x_tangent, u_tangent;  // the last point with a sensitivity, for the predictor
  MatX S_tangent;
  int fk_solves = 0, newton_iterations = 0, fk_jacobians = 0;

  explicit Evaluator(std::shared_ptr<const ReducedIkModel> m)
      : model(std::move(m)), assembly(*model->assembly), options(model->options) {
    NewtonOptions n;
    n.tolerance = options.tolerance;
    n.max_iterations = options.max_iterations;
    n.reuse_factorization = options.reuse_factorization;
    n.linear_solver = options.linear_solver;
    newton = std::make_unique<NewtonSolver>(model->forward, n);
  }

  int num_inputs() const { return model->num_inputs(); }

  /// FK at u (cached); with derivatives also S. False when the FK solve failed.
  bool at(const VecX& u, bool derivatives) {
    if (!valid || u != u_cached) {
      valid = true;
      have_sensitivity = false;
      u_cached = u;
      ok = false;
      // Start points in turn: the first-order predictor x_t + S_t (u - u_t) from the last point with
      // a sensitivity, the last converged state, the solve's start point.
      // The predictor gets 8 Newton iterations, the other starts 25 once an evaluation of this solve
      // has converged (a diverging solve is cut short; Ipopt then backtracks to a closer u), the full
      // max_iterations before (cold start). Measured on R5a, distance objective in the reduced space
      // (test effort_and_energy_optima_beat_nearby_feasible_points): 484 -> 407 Newton iterations; the
      // predictor took effort from 94 to 33. One solver serves the three limits (solve(x, limit)), so
      // its factorisation is reused across them: 424 and 27 iterations since.
      std::vector<VecX> starts;
      // A long step is refused as a failed evaluation (Ipopt then shortens it): it can land the FK
      // on another equilibrium branch, near whose folds the following solves fail (IkOptions).
      if (S_tangent.size() > 0 &&
          (u - u_tangent).cwiseQuotient(model->input_scales).norm() > options.ik.max_input_step) {
        ok = false;
        return false;
      }
      if (S_tangent.size() > 0) starts.push_back(x_tangent + S_tangent * (u - u_tangent));
      const bool predicted = !starts.empty();
      starts.push_back(x_warm);
      if (x_start != x_warm) starts.push_back(x_start);
      for (size_t k = 0; k < starts.size(); ++k) {
        const VecX& start = starts[k];
        if (start.size() == 0 || !start.allFinite()) continue;
        x = start;
        for (int i = 0; i < num_inputs(); ++i) x[model->input_offsets[i]] = u[i];  // the fixed inputs
        const int limit = predicted && k == 0 ? 8 : (converged_once ? 25 : options.max_iterations);
        const SolveSummary s = newton->solve(x, std::min(options.max_iterations, limit));
        ++fk_solves;
        newton_iterations += s.iterations;
        fk_jacobians += s.jacobian_evaluations;
        if (s.converged() && x.allFinite()) {
          ok = true;
          break;
        }
      }
      if (ok) {
        x_warm = x;
        converged_once = true;
      }
    }
    if (ok && derivatives && !have_sensitivity) ok = sensitivity();
    return ok;
  }

  /// S = dx/du: rows of the free variables from J_free S_free = -J_u, input rows the identity.
  bool sensitivity() {
    VecX c;
    Eigen::SparseMatrix<double, Eigen::RowMajor> J;
    model->forward.evaluate_residuals_and_jacobian(x, c, J);
    const FreeJacobian Jf = free_jacobian(model->forward, J);
    MatX rhs(J.rows(), num_inputs());
    for (int i = 0; i < num_inputs(); ++i) rhs.col(i) = -J.col(model->input_offsets[i]);
    if (!pattern_analysed) {
      lu.analyze_pattern(Jf.matrix);
      pattern_analysed = true;
    }
    if (!lu.factorize(Jf.matrix)) return false;
    const MatX dfree = lu.solve(rhs);
    if (!dfree.allFinite()) return false;
    S.setZero(model->forward.num_variables(), num_inputs());
    for (size_t k = 0; k < Jf.columns.size(); ++k) S.row(Jf.columns[k]) = dfree.row(k);
    for (int i = 0; i < num_inputs(); ++i) S(model->input_offsets[i], i) = 1.0;
    have_sensitivity = true;
    x_tangent = x;
    u_tangent = u_cached;
    S_tangent = S;
    return true;
  }

  double distance(const VecX& u, VecX* gradient) const {
    const VecX d = (u - reference).cwiseQuotient(model->input_scales);
    if (gradient) *gradient = d.cwiseQuotient(model->input_scales);
    return 0.5 * d.squaredNorm();
  }

  /// f(u); gradient df/du when asked. Call after at(u, gradient != nullptr) succeeded.
  double objective(const VecX& u, VecX* gradient) {
    const IkOptions& o = options.ik;
    VecX g_dist;
    double f = 0.0;
    if (o.objective == IkObjective::InputDistance) return distance(u, gradient);
    VecX g_x;
    if (o.objective == IkObjective::ActuationEffort) {
      f = actuation_effort(assembly, x, gradient ? &g_x : nullptr);
    } else {
      const double M0 = assembly.moment_scale();
      f = elastic_energy(assembly, x, gradient ? &g_x : nullptr) / M0;
      if (gradient) g_x /= M0;
    }
    if (gradient) *gradient = S.transpose() * g_x;
    if (o.distance_weight > 0.0) {
      f += o.distance_weight * distance(u, gradient ? &g_dist : nullptr);
      if (gradient) *gradient += o.distance_weight * g_dist;
    }
    return f;
  }
};

namespace {

using EvaluatorPtr = std::shared_ptr<ReducedIk::Evaluator>;

class ReducedObjective final : public ObjectiveTerm {
 public:
  ReducedObjective(VariableId u, EvaluatorPtr e)
      : ObjectiveTerm("ik.reduced_objective", {u}), e_(std::move(e)) {}
  double evaluate(const double* const* values, double* const* gradients) const override {
    const VecX u = Eigen::Map<const VecX>(values[0], e_->num_inputs());
    const bool grad = gradients && gradients[0];
    if (!e_->at(u, grad)) return std::numeric_limits<double>::quiet_NaN();  // failed evaluation
    VecX g;
    const double f = e_->objective(u, grad ? &g : nullptr);
    if (grad) Eigen::Map<VecX>(gradients[0], g.size()) = g;
    return f;
  }

 private:
  EvaluatorPtr e_;
};

/// Solves FK at the block's inputs u = values (with dx/du when derivatives); a failed FK leaves the
/// rows NaN, a failed evaluation for Ipopt, which then shortens its step.
bool solve_at_inputs(ReducedIk::Evaluator& e, const double* values, double* residual, int rows,
                     bool derivatives) {
  if (e.at(Eigen::Map<const VecX>(values, e.num_inputs()), derivatives)) return true;
  Eigen::Map<VecX>(residual, rows).setConstant(std::numeric_limits<double>::quiet_NaN());
  return false;
}

/// Rows g(x(u)) of the target blocks (dimensionless, as in the full-space IK).
class ReducedTargets final : public ResidualBlock {
 public:
  ReducedTargets(VariableId u, int rows, EvaluatorPtr e)
      : ResidualBlock("ik.target", "targets", rows, {u}), e_(std::move(e)) {}
  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override {
    const bool jac = jacobians && jacobians[0];
    if (!solve_at_inputs(*e_, values[0], residual, num_rows(), jac)) return;
    Eigen::Map<VecX> r(residual, num_rows());
    VecX c;
    Eigen::SparseMatrix<double, Eigen::RowMajor> G;
    e_->model->targets.evaluate_residuals_and_jacobian(e_->x, c, G);
    r = c;
    if (jac) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          jacobians[0], num_rows(), e_->num_inputs()) = G * e_->S;
    }
  }

 private:
  EvaluatorPtr e_;
};

/// sigma_j(x(u)) / sigma_max <= 1.
class ReducedStress final : public ResidualBlock {
 public:
  ReducedStress(VariableId u, int rows, double sigma_max, EvaluatorPtr e)
      : ResidualBlock("ik.rod_stress", "rod stress / limit", rows, {u}),
        sigma_max_(sigma_max),
        e_(std::move(e)) {
    set_row_bounds(VecX::Constant(rows, -INFINITY), VecX::Ones(rows));
  }
  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override {
    const bool jac = jacobians && jacobians[0];
    if (!solve_at_inputs(*e_, values[0], residual, num_rows(), jac)) return;
    Eigen::Map<VecX> r(residual, num_rows());
    MatX H;
    r = rod_stresses(e_->assembly, e_->x, e_->model->stress_at, jac ? &H : nullptr) / sigma_max_;
    if (jac) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          jacobians[0], num_rows(), e_->num_inputs()) = H * e_->S / sigma_max_;
    }
  }

 private:
  double sigma_max_;
  EvaluatorPtr e_;
};

}  // namespace

struct ReducedIk::Solver {
  Problem problem;
  VariableId u = -1;
  std::unique_ptr<IpoptSolver> ipopt;
};

ReducedIk::ReducedIk(std::shared_ptr<const ReducedIkModel> model)
    : evaluator_(std::make_shared<Evaluator>(std::move(model))), solver_(std::make_unique<Solver>()) {
  const ReducedIkModel& rm = *evaluator_->model;
  const IkOptions& o = rm.options.ik;
  Solver& s = *solver_;
  const RobotModel& m = rm.assembly->model();
  const int n_in = rm.num_inputs();
  VecX lower(n_in), upper(n_in);
  for (int i = 0; i < n_in; ++i) {
    lower[i] = m.inputs()[i].lower;
    upper[i] = m.inputs()[i].upper;
  }
  s.u = s.problem.add_variable_block("inputs", m.default_input_values(), lower, upper);
  s.problem.add_objective_term(std::make_shared<ReducedObjective>(s.u, evaluator_));
  s.problem.add_residual_block(std::make_shared<ReducedTargets>(s.u, rm.targets.num_rows(), evaluator_));
  if (o.max_rod_stress)
    s.problem.add_residual_block(std::make_shared<ReducedStress>(s.u, static_cast<int>(rm.stress_at.size()),
                                                                 *o.max_rod_stress, evaluator_));
  IpoptOptions io;
  io.tol = o.optimality_tolerance;
  io.constraint_tolerance = o.target_tolerance;
  io.max_iterations = o.max_iterations;
  io.hessian = IpoptHessian::LimitedMemory;
  s.ipopt = std::make_unique<IpoptSolver>(s.problem, io);
}

ReducedIk::~ReducedIk() = default;

void ReducedIk::prepare(const VecX& x, const VecX& reference) {
  Evaluator& e = *evaluator_;
  require(x.size() == e.model->forward.num_variables(), "reduced IK: state has size ", x.size(),
          ", expected ", e.model->forward.num_variables());
  require(reference.size() == e.num_inputs(), "reduced IK: reference has size ", reference.size(),
          ", expected ", e.num_inputs());
  e.reference = reference;
  e.valid = false;
  e.x_warm = x;
  e.x_start = x;
  e.S_tangent.resize(0, 0);
  e.converged_once = false;
  e.fk_solves = 0;
  e.newton_iterations = 0;
  e.fk_jacobians = 0;
}

const Problem& ReducedIk::problem() const {
  return solver_->problem;
}

SolveSummary ReducedIk::solve(VecX& x, const VecX& reference) {
  prepare(x, reference);
  Evaluator& e = *evaluator_;
  VecX u(e.num_inputs());
  for (int i = 0; i < e.num_inputs(); ++i) u[i] = x[e.model->input_offsets[i]];
  const RobotModel& m = e.assembly.model();
  for (int i = 0; i < u.size(); ++i)
    u[i] = std::min(std::max(u[i], m.inputs()[i].lower), m.inputs()[i].upper);
  SolveSummary summary;
  if (!e.at(u, false)) {
    summary.status = SolveStatus::Failed;
    summary.solver = "ipopt (reduced)";
    summary.message = "forward kinematics failed at the start inputs";
    return summary;
  }
  summary = solver_->ipopt->solve(u);
  summary.solver = "ipopt (reduced)";
  summary.jacobian_evaluations += e.fk_jacobians;  // Ipopt's (of the reduced problem) and the FK solves'
  const bool final_ok = u.allFinite() && e.at(u, false);
  if (final_ok) {
    x = e.x;
  } else {
    x = e.x_warm;  // the last equilibrium reached
    if (summary.converged()) {
      summary.status = SolveStatus::Failed;
      summary.message = "forward kinematics failed at the optimum";
    }
  }
  summary.message += (summary.message.empty() ? "" : "; ") + std::string("objective ") +
                     to_string(e.options.ik.objective) + ", " + std::to_string(e.fk_solves) + " FK solves, " +
                     std::to_string(e.newton_iterations) + " Newton iterations";
  return summary;
}

}  // namespace pcr::kinematics
