// ForwardKinematics: its model and data (fk_data.hpp), the solve (attempts: fk_strategies.cpp) and the
// derivatives at the last solution by the implicit function theorem.
#include <stdexcept>

#include "contact_ipopt_fk.hpp"
#include "fk_data.hpp"
#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/solve/free_jacobian.hpp"
#include "pcr/solve/sparse_lu.hpp"
#include "refined_verdict.hpp"
#include "solve_support.hpp"

namespace pcr {

namespace kinematics {

FkModel::FkModel(std::shared_ptr<const RobotAssembly> a, const KinematicsOptions& o)
    : assembly(std::move(a)), options(o) {
  require(assembly != nullptr, "ForwardKinematics: no assembly");
  // Relaxed contact rows (AssemblyOptions::contact_method = Ipopt) are not a square system: Ipopt only.
  if (!relaxed_contacts(*assembly).empty()) options.solver = SolverKind::Ipopt;
  sample_bases = pcr::sample_bases(*assembly, options.centerline_points);
  default_start = shared_default_equilibrium(*assembly, options);
}

FkData::FkData(std::shared_ptr<const FkModel> m) : model(std::move(m)), x(model->assembly->initial_guess()) {}

SolveSummary FkData::solve_at(const VecX& u, VecX& x_io, int max_jacobian_evaluations, bool intermediate) {
  const RobotAssembly& a = *model->assembly;
  const KinematicsOptions& o = model->options;
  a.set_inputs(x_io, u);  // the inputs are fixed variables: constants at the values x holds
  if (o.solver == SolverKind::Newton && intermediate && kIntermediateTolerance > o.tolerance) {
    if (!newton_intermediate) {
      NewtonOptions no = newton_options(o);
      no.tolerance = kIntermediateTolerance;
      newton_intermediate = std::make_unique<NewtonSolver>(a.problem(), no);
    }
    return newton_intermediate->solve(x_io, o.max_iterations, max_jacobian_evaluations);
  }
  if (o.solver == SolverKind::Newton) {
    if (!newton) newton = std::make_unique<NewtonSolver>(a.problem(), newton_options(o));
    return newton->solve(x_io, o.max_iterations, max_jacobian_evaluations);
  }
  if (!relaxed_contacts(a).empty()) return solve_relaxed_contact(a, o, ipopt, x_io);
  if (!ipopt) ipopt = std::make_unique<IpoptSolver>(a.problem(), ipopt_options(o));
  return ipopt->solve(x_io);
}

}  // namespace kinematics

namespace {

using kinematics::FkData;
using kinematics::FkModel;

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

}  // namespace

ForwardKinematics::ForwardKinematics(std::shared_ptr<const RobotModel> model,
                                     const KinematicsOptions& options)
    : ForwardKinematics(std::make_shared<const RobotAssembly>(std::move(model), options.assembly), options) {}

ForwardKinematics::ForwardKinematics(std::shared_ptr<const RobotAssembly> assembly,
                                     const KinematicsOptions& options)
    : data_(std::make_unique<FkData>(std::make_shared<const FkModel>(std::move(assembly), options))) {}

ForwardKinematics::ForwardKinematics(std::unique_ptr<FkData> data) : data_(std::move(data)) {}
ForwardKinematics::ForwardKinematics(ForwardKinematics&&) noexcept = default;
ForwardKinematics& ForwardKinematics::operator=(ForwardKinematics&&) noexcept = default;
ForwardKinematics::~ForwardKinematics() = default;

ForwardKinematics ForwardKinematics::with_fresh_state() const {
  return ForwardKinematics(std::make_unique<FkData>(data().model));
}

FkData& ForwardKinematics::data() const {
  if (!data_) throw std::logic_error("pcr::ForwardKinematics used after being moved from");
  return *data_;
}

const RobotAssembly& ForwardKinematics::assembly() const {
  return *data().model->assembly;
}
const std::shared_ptr<const RobotAssembly>& ForwardKinematics::assembly_ptr() const {
  return data().model->assembly;
}
const VecX& ForwardKinematics::state() const {
  return data().x;
}
bool ForwardKinematics::has_solution() const {
  return data().has_solution;
}
const DefaultEquilibrium& ForwardKinematics::default_equilibrium() const {
  return data().model->default_equilibrium();
}

RobotSolution ForwardKinematics::solve(const VecX& inputs) {
  const auto start = kinematics::Clock::now();
  FkData& d = data();
  const FkModel& m = *d.model;
  m.assembly->check_inputs(inputs);
  VecX x;
  std::optional<Stability> verdict;  // computed by the strategy that converged (the energy minimisation)
  SolveSummary summary = kinematics::solve_with_fallbacks(d, inputs, x, &verdict);
  kinematics::account_for_round_off(m.assembly->problem(), x, m.options.tolerance, summary);
  bool accepted = false;
  RobotSolution out = kinematics::finish_solution(*m.assembly, x, d.x, summary, start, m.sample_bases,
                                                  m.options.read_centerline, accepted);
  if (accepted) {
    d.x = x;
    d.has_solution = true;
    d.predictor.accept(d.x, inputs);
    if (m.options.check_stability)
      kinematics::monitor_stability(m.assembly->problem(), d.x, d.last_jacobian_sign, out);
    if (m.options.stability_verdict && verdict)
      out.stability_verdict = *verdict;
    else if (m.options.stability_verdict)
      kinematics::add_stability_verdict(*m.assembly, d.x, out);
    kinematics::refine_unknown_verdict(*m.assembly, d.x, m.options.tolerance, out.stability_verdict);
    d.last_unstable_modes = kinematics::definite_unstable_modes(out.stability_verdict);
  }
  return out;
}

MatX ForwardKinematics::input_jacobian() const {
  const FkData& d = data();
  require(d.has_solution, "input_jacobian: no converged forward kinematics solution yet");
  const RobotAssembly& a = *d.model->assembly;
  const Problem& problem = a.problem();
  VecX c;
  Eigen::SparseMatrix<double, Eigen::RowMajor> J;
  problem.evaluate_residuals_and_jacobian(d.x, c, J);
  const int m = static_cast<int>(a.model().inputs().size());
  MatX rhs = MatX::Zero(problem.num_rows(), m);
  for (int i = 0; i < m; ++i) rhs.col(i) = J.col(problem.variable(a.input_variable(i)).offset);
  const MatX dX = implicit_derivative(problem, J, rhs);
  const int np = static_cast<int>(a.model().platforms().size());
  MatX out(6 * np, m);
  for (int p = 0; p < np; ++p) out.middleRows(6 * p, 6) = platform_rows(a, d.x, p, dX);
  return out;
}

MatX ForwardKinematics::compliance(int platform) const {
  const FkData& d = data();
  require(d.has_solution, "compliance: no converged forward kinematics solution yet");
  const RobotAssembly& a = *d.model->assembly;
  require(platform >= 0 && platform < static_cast<int>(a.model().platforms().size()),
          "compliance: platform index ", platform, " out of range");
  const Problem& problem = a.problem();
  // The balance rows of the platform: force / F0 (3), moment / M0 (3); an external wrench (f, tau) at
  // the origin adds (f / F0, tau / M0) to them.
  const int row = problem.row_offset(a.platform_balance(platform));
  MatX dR = MatX::Zero(problem.num_rows(), 6);
  for (int k = 0; k < 3; ++k) {
    dR(row + k, k) = 1.0 / a.force_scale();
    dR(row + 3 + k, 3 + k) = 1.0 / a.moment_scale();
  }
  VecX c;
  Eigen::SparseMatrix<double, Eigen::RowMajor> J;
  problem.evaluate_residuals_and_jacobian(d.x, c, J);
  return platform_rows(a, d.x, platform, implicit_derivative(problem, J, dR));
}

}  // namespace pcr
