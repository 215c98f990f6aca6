#include "pcr/robots/kinematics.hpp"

#include <algorithm>
#include <chrono>
#include <sstream>

#include "../assembly/robot_blocks.hpp"
#include "input_continuation.hpp"
#include "input_objective.hpp"
#include "path_predictor.hpp"
#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/solve/free_jacobian.hpp"
#include "pcr/solve/ipopt_solver.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "pcr/solve/sparse_lu.hpp"
#include "reduced_ik.hpp"

namespace pcr {
namespace {

using Clock = std::chrono::steady_clock;

// Stability monitoring (KinematicsOptions::check_stability): the sign of det J of the FK system `fk` at
// the converged solution x, and whether it changed since the last checked solve (last_sign, updated).
void monitor_stability(const Problem& fk, const VecX& x, int& last_sign, RobotSolution& out) {
  out.jacobian_sign = jacobian_determinant_sign(fk, x);
  if (out.jacobian_sign == 0) return;
  out.jacobian_sign_changed = last_sign != 0 && out.jacobian_sign != last_sign;
  last_sign = out.jacobian_sign;
}

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

NewtonOptions newton_options(const KinematicsOptions& o) {
  NewtonOptions n;
  n.tolerance = o.tolerance;
  n.max_iterations = o.max_iterations;
  n.reuse_factorization = o.reuse_factorization;
  n.linear_solver = o.linear_solver;
  return n;
}

IpoptOptions ipopt_options(const KinematicsOptions& o) {
  IpoptOptions i;
  i.tol = o.tolerance;
  i.constraint_tolerance = o.tolerance;
  i.max_iterations = 3000;
  return i;
}

/// Solves J_free dX = -rhs for the free columns of the evaluated Jacobian J (implicit function theorem);
/// returns dX over all variables (zero rows for fixed ones), one column per rhs column.
MatX implicit_derivative(const Problem& problem, const Eigen::SparseMatrix<double, Eigen::RowMajor>& J_all,
                         const MatX& rhs) {
  const FreeJacobian J = free_jacobian(problem, J_all);
  SparseLu lu;
  require(lu.compute(J.matrix), "derivatives: the assembled Jacobian is singular at this configuration");
  const MatX dfree = lu.solve(MatX(-rhs));
  MatX out = MatX::Zero(problem.num_variables(), rhs.cols());
  for (size_t k = 0; k < J.columns.size(); ++k) out.row(J.columns[k]) = dfree.row(k);
  return out;
}

/// 6 rows [dx; dtheta_world] of a platform from dX (its 7 rows [dx; dQ]): dtheta = 2 vec(dQ (x) conj(Q)).
MatX platform_rows(const RobotAssembly& a, const VecX& x, int platform, const MatX& dX) {
  const int o = a.problem().variable(a.platform_variable(platform)).offset;
  const Quat Q = x.segment<4>(o + 3);
  MatX rows(6, dX.cols());
  for (int c = 0; c < dX.cols(); ++c) {
    rows.block<3, 1>(0, c) = dX.block<3, 1>(o, c);
    const Quat dQ = dX.block<4, 1>(o + 3, c);
    rows.block<3, 1>(3, c) = 2.0 * quat_multiply(dQ, quat_conjugate(Q)).tail<3>() / Q.squaredNorm();
  }
  return rows;
}

// A solver that reports convergence at a non-finite point has failed.
void mark_non_finite(const VecX& x, SolveSummary& summary) {
  if (summary.converged() && !x.allFinite()) {
    summary.status = SolveStatus::Failed;
    summary.message = "non-finite solution";
  }
}

}  // namespace

const char* to_string(IkObjective objective) {
  switch (objective) {
    case IkObjective::InputDistance: return "distance";
    case IkObjective::ActuationEffort: return "effort";
    case IkObjective::ElasticEnergy: return "energy";
  }
  return "unknown";
}

std::vector<std::vector<BasisDerivatives>> sample_bases(const RobotAssembly& a, int centerline_points) {
  std::vector<std::vector<BasisDerivatives>> bases;
  for (int i = 0; i < a.num_rods(); ++i)
    bases.push_back(a.rod(i).sample_basis(std::max(2, centerline_points)));
  return bases;
}

RobotSolution read_solution(const RobotAssembly& a, const VecX& x, int centerline_points) {
  return read_solution(a, x, sample_bases(a, centerline_points));
}

RobotSolution read_solution(const RobotAssembly& a, const VecX& x,
                            const std::vector<std::vector<BasisDerivatives>>& sample_bases) {
  require(static_cast<int>(sample_bases.size()) == a.num_rods(), "read_solution: ", sample_bases.size(),
          " sample bases for ", a.num_rods(), " rods");
  RobotSolution s;
  s.inputs = a.inputs(x);
  for (size_t p = 0; p < a.model().platforms().size(); ++p)
    s.platforms.push_back(a.platform_pose(x, static_cast<int>(p)));
  for (int i = 0; i < a.num_rods(); ++i) {
    const CollocationRod& rod = a.rod(i);
    const RodVariables& v = a.rod_variables(i);
    RodResult r;
    r.name = rod.model().name;
    r.length = rod.length(x, v);
    // Full states at the ends, the centerline and the axial stretch at every sample point (s = 0 .. L,
    // ends included).
    const std::vector<BasisDerivatives>& bases = sample_bases[i];
    const RodState b = rod.state_with_basis(x, v, 0.0, bases.front());
    const RodState t = rod.state_with_basis(x, v, r.length, bases.back());
    r.base_force = b.force;
    r.base_moment = b.moment;
    r.tip_force = t.force;
    r.tip_moment = t.moment;
    r.axial_force = b.force.dot(b.rotation.col(2));
    std::vector<double> stretches;
    rod.sample_centerline(x, v, bases, r.centerline, stretches);
    r.min_axial_stretch = *std::min_element(stretches.begin(), stretches.end());
    s.rods.push_back(std::move(r));
  }
  return s;
}

// Marks a converged solution failed when a rod is compressed to a point or inverted
// (admissible_axial_stretch; rod_solve.cpp checks single rods the same way). Returns whether the
// solution stays converged.
bool reject_inadmissible(RobotSolution& s) {
  if (!s.summary.converged()) return false;
  for (const RodResult& r : s.rods) {
    if (!admissible_axial_stretch(r.min_axial_stretch)) {
      std::ostringstream msg;
      msg << "inadmissible state: rod '" << r.name
          << "' has axial stretch v3 = 1 + eps3 = " << r.min_axial_stretch
          << " (compressed to a point or inverted; admissible: v3 > 0)"
          << (s.summary.message.empty() ? "" : "; " + s.summary.message);
      s.summary.status = SolveStatus::Failed;
      s.summary.message = msg.str();
      return false;
    }
  }
  return true;
}

// ---------------------------------------------------------------------------------------------------
struct ForwardKinematics::Solvers {
  std::vector<std::vector<BasisDerivatives>> sample_bases;  // read_solution
  std::unique_ptr<NewtonSolver> newton;
  std::unique_ptr<IpoptSolver> ipopt;
  kinematics::PathPredictor predictor;  // start point along a path of inputs
};

ForwardKinematics::ForwardKinematics(std::shared_ptr<const RobotModel> model,
                                     const KinematicsOptions& options)
    : assembly_(std::move(model), options.assembly),
      options_(options),
      solvers_(std::make_shared<Solvers>()) {
  x_ = assembly_.initial_guess();
  solvers_->sample_bases = sample_bases(assembly_, options_.centerline_points);
}

SolveSummary ForwardKinematics::solve_once(VecX& x, int max_jacobian_evaluations) {
  if (options_.solver == SolverKind::Newton) {
    if (!solvers_->newton)
      solvers_->newton = std::make_unique<NewtonSolver>(assembly_.problem(), newton_options(options_));
    return solvers_->newton->solve(x, options_.max_iterations, max_jacobian_evaluations);
  }
  if (!solvers_->ipopt)
    solvers_->ipopt = std::make_unique<IpoptSolver>(assembly_.problem(), ipopt_options(options_));
  return solvers_->ipopt->solve(x);
}

RobotSolution ForwardKinematics::solve(const VecX& inputs) {
  const auto start = Clock::now();
  assembly_.fix_inputs(inputs);  // validates size and bounds
  bool on_path = false;
  VecX x = solvers_->predictor.predict(x_, inputs, &on_path);
  if (on_path && solvers_->newton) solvers_->newton->continue_path();
  assembly_.set_inputs(x, inputs);
  SolveSummary summary = solve_once(x, kDirectJacobianEvaluations);
  int iterations = summary.iterations, jacobians = summary.jacobian_evaluations;
  if (!summary.converged() && has_solution_) {  // the extrapolated start failed: retry from the last solution
    x = x_;
    assembly_.set_inputs(x, inputs);
    summary = solve_once(x, kDirectJacobianEvaluations);
    iterations += summary.iterations;
    jacobians += summary.jacobian_evaluations;
  }
  if (!summary.converged()) {
    // Continuation in the inputs (input_continuation.hpp): first from the last converged state (if any),
    // then from the model's default inputs solved from the straight initial guess, along the straight line
    // and then one input at a time. The warm path starts in a deformed state that may be far from the new
    // inputs and fails more often than the cold one (random input sweeps), hence the attempts from the
    // default inputs after it. (Random sweeps, README "Stress tests": limited fresh Jacobians per step took
    // 5x less time per Stewart-Gough solve than full-budget steps, and more converged.)
    const kinematics::SolveAtInputs solve_at = [&](const VecX& u, VecX& xs, int max_jacobians) {
      assembly_.fix_inputs(u);
      assembly_.set_inputs(xs, u);
      return solve_once(xs, max_jacobians);
    };
    auto finish = [&](const kinematics::ContinuationResult& r, const VecX& xr, const std::string& how) {
      iterations += r.iterations;
      jacobians += r.jacobian_evaluations;
      if (!r.converged) {
        summary.message += "; " + how + " stopped at " + r.stopped_at;
        return false;
      }
      x = xr;
      summary = r.last;
      summary.message = "converged by " + how + " (" + std::to_string(r.steps) + " steps)";
      return true;
    };
    bool done = false;
    if (has_solution_) {
      VecX xs = x_;
      const kinematics::ContinuationResult r = kinematics::continue_along_line(
          solve_at, assembly_.inputs(x_), inputs, kContinuationStepJacobianEvaluations, xs);
      done = finish(r, xs, "continuation in the inputs from the last solution");
    }
    if (!done) {
      const VecX u_default = assembly_.model().default_input_values();
      assembly_.fix_inputs(u_default);
      VecX x_default = assembly_.initial_guess();
      const SolveSummary s0 = solve_once(x_default);
      iterations += s0.iterations;
      jacobians += s0.jacobian_evaluations;
      if (s0.converged()) {
        VecX xs = x_default;
        done = finish(kinematics::continue_along_line(solve_at, u_default, inputs,
                                                      kContinuationStepJacobianEvaluations, xs),
                      xs, "continuation in the inputs from the default inputs");
        if (!done) {
          xs = x_default;
          done = finish(kinematics::continue_one_input_at_a_time(
                            solve_at, u_default, inputs, kDirectJacobianEvaluations,
                            kContinuationStepJacobianEvaluations, kOneInputOrders, xs),
                        xs, "continuation from the default inputs one input at a time");
        }
      } else {
        summary.message += "; the default inputs did not converge from the straight initial guess";
      }
    }
    assembly_.fix_inputs(inputs);
  }
  summary.iterations = iterations;
  summary.jacobian_evaluations = jacobians;
  summary.wall_time_seconds = seconds_since(start);
  mark_non_finite(x, summary);
  RobotSolution out = read_solution(assembly_, x.allFinite() ? x : x_, solvers_->sample_bases);
  out.summary = summary;
  if (reject_inadmissible(out)) {
    x_ = x;
    has_solution_ = true;
    solvers_->predictor.accept(x_, inputs);
    if (options_.check_stability) monitor_stability(assembly_.problem(), x_, last_jacobian_sign_, out);
  }
  return out;
}

MatX ForwardKinematics::input_jacobian() const {
  require(has_solution_, "input_jacobian: no converged forward kinematics solution yet");
  const Problem& problem = assembly_.problem();
  VecX c;
  Eigen::SparseMatrix<double, Eigen::RowMajor> J;
  problem.evaluate_residuals_and_jacobian(x_, c, J);
  const int m = static_cast<int>(assembly_.model().inputs().size());
  MatX rhs = MatX::Zero(problem.num_rows(), m);
  for (int i = 0; i < m; ++i) rhs.col(i) = J.col(problem.variable(assembly_.input_variable(i)).offset);
  const MatX dX = implicit_derivative(problem, J, rhs);
  const int np = static_cast<int>(assembly_.model().platforms().size());
  MatX out(6 * np, m);
  for (int p = 0; p < np; ++p) out.middleRows(6 * p, 6) = platform_rows(assembly_, x_, p, dX);
  return out;
}

MatX ForwardKinematics::compliance(int platform) const {
  require(has_solution_, "compliance: no converged forward kinematics solution yet");
  require(platform >= 0 && platform < static_cast<int>(assembly_.model().platforms().size()),
          "compliance: platform index ", platform, " out of range");
  const Problem& problem = assembly_.problem();
  // The balance rows of the platform: force / F0 (3), moment / M0 (3); an external wrench (f, tau) at
  // the origin adds (f / F0, tau / M0) to them.
  int balance = -1;
  for (int b = 0; b < problem.num_residual_blocks(); ++b)
    if (problem.residual(b).kind() == "platform.balance" &&
        problem.residual(b).name() == assembly_.model().platforms()[platform].name)
      balance = b;
  require(balance >= 0, "compliance: no balance block for platform ", platform);
  const int row = problem.row_offset(balance);
  MatX dR = MatX::Zero(problem.num_rows(), 6);
  for (int k = 0; k < 3; ++k) {
    dR(row + k, k) = 1.0 / assembly_.force_scale();
    dR(row + 3 + k, 3 + k) = 1.0 / assembly_.moment_scale();
  }
  VecX c;
  Eigen::SparseMatrix<double, Eigen::RowMajor> J;
  problem.evaluate_residuals_and_jacobian(x_, c, J);
  return platform_rows(assembly_, x_, platform, implicit_derivative(problem, J, dR));
}

// ---------------------------------------------------------------------------------------------------
struct InverseKinematics::Solvers {
  std::vector<std::vector<BasisDerivatives>> sample_bases;  // read_solution
  Problem square;     // targets as equations, inputs free without bounds (Newton)
  Problem optimised;  // + bounds and the input-distance objective (Ipopt)
  Problem fk;         // check_stability: the FK system at the solution (target rows off, inputs fixed)
  std::unique_ptr<NewtonSolver> newton;
  std::unique_ptr<IpoptSolver> ipopt;
  VariableId reference = -1;
  kinematics::PathPredictor predictor;             // start point along a path of targets
  std::unique_ptr<kinematics::ReducedIk> reduced;  // other objectives, stress limits (IkOptions)
};

InverseKinematics::InverseKinematics(std::shared_ptr<const RobotModel> model,
                                     const std::vector<LinkTarget>& targets, const KinematicsOptions& options)
    : assembly_(std::move(model), options.assembly),
      options_(options),
      targets_(targets),
      solvers_(std::make_shared<Solvers>()) {
  const RobotModel& m = assembly_.model();
  require(!targets.empty(), "inverse kinematics: no target given");
  Problem& problem = assembly_.problem();
  const std::vector<Pose> identity(m.platforms().size());
  const VecX q0 = m.default_joint_values();
  for (const LinkTarget& t : targets) {
    const int link = m.link_index(t.link);
    const int platform = m.carrying_platform(link);
    require(platform >= 0, "inverse kinematics: target link '", t.link, "' is not carried by a platform");
    const Pose offset = m.link_pose(link, q0, identity);
    VecX z(7);
    z << t.pose.position, t.pose.orientation.normalized();
    const VariableId tv = problem.add_variable_block("target." + t.link, z);
    problem.fix_variable(tv, z);
    target_variables_.push_back(tv);
    assembly::PoseComponents components = t.components;
    for (int i = 0; i < 3; ++i) {
      components[i] = components[i] && t.mode != LinkTarget::Mode::Orientation;
      components[3 + i] = components[3 + i] && t.mode != LinkTarget::Mode::Position;
    }
    require(std::count(components.begin(), components.end(), true) > 0, "inverse kinematics: target for '",
            t.link, "' selects no pose component");
    problem.add_residual_block(
        std::make_shared<assembly::PoseTargetBlock>("target." + t.link, assembly_.platform_variable(platform),
                                                    tv, offset, components, assembly_.length_scale()));
  }
  // Square problem: inputs free (no bounds: Newton checks them afterwards).
  const int n_in = static_cast<int>(m.inputs().size());
  for (int i = 0; i < n_in; ++i)
    problem.set_variable_bounds(assembly_.input_variable(i), VecX::Constant(1, -INFINITY),
                                VecX::Constant(1, INFINITY));
  int free_unknowns = 0;
  for (int v = 0; v < problem.num_variable_blocks(); ++v)
    if (!problem.variable_fixed(v)) free_unknowns += problem.variable(v).size;
  square_ = free_unknowns == problem.num_rows();
  // Reduced space (Ipopt over the inputs): other objectives and stress limits always; the input
  // distance when the targets leave inputs free, unless asked for the full space (IkOptions).
  reduced_ = kinematics::uses_reduced_space(options.ik) ||
             (free_unknowns > problem.num_rows() && !options.ik.full_space);
  solvers_->square = problem;
  if (options.check_stability) solvers_->fk = kinematics::forward_problem_of(problem, assembly_);
  // Optimisation problem: bounds and objective.
  Problem& opt = solvers_->optimised;
  opt = problem;
  std::vector<VariableId> inputs;
  VecX scales(n_in);
  for (int i = 0; i < n_in; ++i) {
    const ActuationInput& in = m.inputs()[i];
    opt.set_variable_bounds(assembly_.input_variable(i), VecX::Constant(1, in.lower),
                            VecX::Constant(1, in.upper));
    inputs.push_back(assembly_.input_variable(i));
    scales[i] = in.kind == ActuationInput::Kind::RodLength ? assembly_.length_scale() : 1.0;
  }
  solvers_->reference = opt.add_variable_block("ik.reference", m.default_input_values());
  opt.fix_variable(solvers_->reference, m.default_input_values());
  opt.add_objective_term(std::make_shared<kinematics::InputDistance>(inputs, solvers_->reference, scales));
  x_ = solvers_->square.initial_values();
  solvers_->sample_bases = sample_bases(assembly_, options_.centerline_points);
  if (reduced_)  // validates the IK options
    solvers_->reduced =
        std::make_unique<kinematics::ReducedIk>(assembly_, solvers_->square, target_variables_, options);
}

RobotSolution InverseKinematics::solve(const std::vector<Pose>& target_poses, const VecX* reference) {
  const auto start = Clock::now();
  require(target_poses.size() == targets_.size(), "inverse kinematics: ", target_poses.size(),
          " target poses for ", targets_.size(), " targets");
  const RobotModel& m = assembly_.model();
  VecX all_targets(7 * targets_.size());
  for (size_t k = 0; k < targets_.size(); ++k) {
    require(target_poses[k].position.allFinite() && target_poses[k].orientation.allFinite() &&
                target_poses[k].orientation.norm() > 0,
            "inverse kinematics: target for '", targets_[k].link, "' is not a finite pose");
    VecX z(7);
    z << target_poses[k].position, target_poses[k].orientation.normalized();
    all_targets.segment(7 * k, 7) = z;
    solvers_->square.fix_variable(target_variables_[k], z);
    solvers_->optimised.fix_variable(target_variables_[k], z);
    if (solvers_->reduced) solvers_->reduced->set_target(static_cast<int>(k), z);
  }
  const VecX previous_inputs = assembly_.inputs(x_);
  const VecX ref = reference ? *reference : previous_inputs;
  require(ref.size() == static_cast<int>(m.inputs().size()), "inverse kinematics: reference has ", ref.size(),
          " values, the model has ", m.inputs().size(), " inputs");

  auto within_bounds = [&](const VecX& u) {
    for (int i = 0; i < u.size(); ++i)
      if (u[i] < m.inputs()[i].lower || u[i] > m.inputs()[i].upper) return false;
    return true;
  };
  SolveSummary summary;
  VecX x = x_;
  bool done = false;
  int iterations = 0, jacobians = 0;
  // Input distance without stress limits and a square system: Newton (fast, warm-started along paths).
  const bool newton_first = !kinematics::uses_reduced_space(options_.ik);
  if (newton_first && square_) {
    if (!solvers_->newton)
      solvers_->newton = std::make_unique<NewtonSolver>(solvers_->square, newton_options(options_));
    // Newton keeps the fixed variables' values of x: the targets' are this solve's.
    auto write_targets = [&](VecX& xt) {
      for (size_t k = 0; k < targets_.size(); ++k)
        xt.segment(solvers_->square.variable(target_variables_[k]).offset, 7) = all_targets.segment(7 * k, 7);
    };
    bool on_path = false;
    x = solvers_->predictor.predict(x_, all_targets, &on_path);
    write_targets(x);
    if (on_path) solvers_->newton->continue_path();
    summary = solvers_->newton->solve(x);
    iterations += summary.iterations;
    jacobians += summary.jacobian_evaluations;
    if (!summary.converged()) {  // the extrapolated start failed: retry from the last solution
      x = x_;
      write_targets(x);
      summary = solvers_->newton->solve(x);
      iterations += summary.iterations;
      jacobians += summary.jacobian_evaluations;
    }
    done = summary.converged() && within_bounds(assembly_.inputs(x));
  }
  if (!done) {
    // Start from Newton's solution when it converged outside the input bounds, else from the last one.
    const VecX x_start = (newton_first && square_ && summary.converged() && x.allFinite()) ? x : x_;
    if (reduced_) {
      x = x_start;
      summary = solvers_->reduced->solve(x, ref);
    } else {
      VecX xo(solvers_->optimised.num_variables());
      xo.head(x_.size()) = x_start;
      xo.tail(ref.size()) = ref;
      solvers_->optimised.fix_variable(solvers_->reference, ref);
      if (!solvers_->ipopt)
        solvers_->ipopt = std::make_unique<IpoptSolver>(solvers_->optimised, ipopt_options(options_));
      summary = solvers_->ipopt->solve(xo);
      x = xo.head(x_.size());
    }
    iterations += summary.iterations;
    jacobians += summary.jacobian_evaluations;
  }
  summary.iterations = iterations;
  summary.jacobian_evaluations = jacobians;
  summary.wall_time_seconds = seconds_since(start);
  mark_non_finite(x, summary);
  RobotSolution out = read_solution(assembly_, x.allFinite() ? x : x_, solvers_->sample_bases);
  out.summary = summary;
  if (reject_inadmissible(out)) {
    x_ = x;
    solvers_->predictor.accept(x_, all_targets);
    if (options_.check_stability)  // J at x_ with its own inputs
      monitor_stability(solvers_->fk, x_, last_jacobian_sign_, out);
  }
  return out;
}

}  // namespace pcr
