// InverseKinematics: Newton on the square system along paths of targets, else Ipopt (reduced space or
// all variables); the problems are built once (ik_model.cpp), the solve state is per object (ik_data.hpp).
#include <stdexcept>

#include "default_equilibrium.hpp"
#include "ik_data.hpp"
#include "pcr/core/error.hpp"
#include "solve_support.hpp"

namespace pcr {

const char* to_string(IkObjective objective) {
  switch (objective) {
    case IkObjective::InputDistance: return "distance";
    case IkObjective::ActuationEffort: return "effort";
    case IkObjective::ElasticEnergy: return "energy";
  }
  return "unknown";
}

namespace kinematics {

IkData::IkData(std::shared_ptr<const IkModel> m) : model(std::move(m)), x(model->square.initial_values()) {
  if (model->reduced) reduced = std::make_unique<ReducedIk>(model->reduced);
}

}  // namespace kinematics

namespace {

using kinematics::IkData;
using kinematics::IkModel;

/// The target poses stacked [x (3), Q (4)] per target (Q normalised); InputError for a wrong count or a
/// non-finite pose.
VecX stacked_targets(const IkModel& m, const std::vector<Pose>& poses) {
  require(poses.size() == m.targets.size(), "inverse kinematics: ", poses.size(), " target poses for ",
          m.targets.size(), " targets");
  VecX z(7 * poses.size());
  for (size_t k = 0; k < poses.size(); ++k) {
    require(
        poses[k].position.allFinite() && poses[k].orientation.allFinite() && poses[k].orientation.norm() > 0,
        "inverse kinematics: target for '", m.targets[k].link, "' is not a finite pose");
    z.segment<3>(7 * k) = poses[k].position;
    z.segment<4>(7 * k + 3) = poses[k].orientation.normalized();
  }
  return z;
}

/// x with the target blocks set to the stacked targets z (they are fixed: constants at the values x holds).
VecX with_targets(const IkModel& m, VecX x, const VecX& z) {
  for (size_t k = 0; k < m.target_variables.size(); ++k)
    x.segment<7>(m.square.variable(m.target_variables[k]).offset) = z.segment<7>(7 * k);
  return x;
}

bool within_bounds(const RobotModel& model, const VecX& u) {
  for (int i = 0; i < u.size(); ++i)
    if (u[i] < model.inputs()[i].lower || u[i] > model.inputs()[i].upper) return false;
  return true;
}

/// One IK solve in progress: the result x, the summary of the last solver run, counts of all runs.
struct IkAttempt {
  VecX x;
  SolveSummary summary;
  int iterations = 0, jacobians = 0;
  void take(const SolveSummary& s) {
    summary = s;
    iterations += s.iterations;
    jacobians += s.jacobian_evaluations;
  }
};

/// The start of the first Newton solve of the square system: the model's default equilibrium (shared with
/// forward kinematics: solved once per model and the options that shape it, default_equilibrium.hpp), in
/// the square system's layout (its head is the assembly's variables; the targets follow); false where it
/// did not converge. On R5a (rods under gravity) the cold IK then takes one fresh Jacobian instead of two
/// (docs/benchmarks.md, "Time split of a warm R5b solve"). The retry and the Ipopt solves keep the
/// straight start.
bool default_equilibrium_start(const IkData& d, VecX& x) {
  const IkModel& m = *d.model;
  const DefaultEquilibrium& e =
      kinematics::shared_default_equilibrium(*m.assembly, m.options)->get(*m.assembly, m.options);
  if (!e.converged || e.x.size() > d.x.size()) return false;
  x = d.x;
  x.head(e.x.size()) = e.x;
  return true;
}

/// Newton on the square system from the path predictor's start (the first solve: the default equilibrium),
/// then from the last solution. True when it converged inside the input bounds.
bool solve_square(IkData& d, const VecX& z, IkAttempt& a, bool first) {
  const IkModel& m = *d.model;
  if (!d.newton) d.newton = std::make_unique<NewtonSolver>(m.square, kinematics::newton_options(m.options));
  bool on_path = false;
  VecX equilibrium;
  const bool from_equilibrium = first && default_equilibrium_start(d, equilibrium);
  a.x = with_targets(m, from_equilibrium ? equilibrium : d.predictor.predict(d.x, z, &on_path), z);
  if (on_path) d.newton->continue_path();
  a.take(d.newton->solve(a.x));
  if (!a.summary.converged()) {  // the extrapolated start failed: retry from the last solution
    a.x = with_targets(m, d.x, z);
    a.take(d.newton->solve(a.x));
  }
  return a.summary.converged() && within_bounds(m.assembly->model(), m.assembly->inputs(a.x));
}

/// Ipopt from x_start: over the inputs (reduced space) or over all variables with the input-distance
/// objective to the reference inputs.
void optimise(IkData& d, const VecX& x_start, const VecX& reference, IkAttempt& a) {
  const IkModel& m = *d.model;
  if (m.reduced_space) {
    a.x = x_start;
    a.take(d.reduced->solve(a.x, reference));
    return;
  }
  VecX xo(m.optimised.num_variables());
  xo.head(x_start.size()) = x_start;
  xo.segment(m.optimised.variable(m.reference).offset, reference.size()) = reference;
  if (!d.ipopt) d.ipopt = std::make_unique<IpoptSolver>(m.optimised, kinematics::ipopt_options(m.options));
  a.take(d.ipopt->solve(xo));
  a.x = xo.head(x_start.size());
}

}  // namespace

InverseKinematics::InverseKinematics(std::shared_ptr<const RobotModel> model,
                                     const std::vector<LinkTarget>& targets, const KinematicsOptions& options)
    : InverseKinematics(std::make_shared<const RobotAssembly>(std::move(model), options.assembly), targets,
                        options) {}

InverseKinematics::InverseKinematics(std::shared_ptr<const RobotAssembly> assembly,
                                     const std::vector<LinkTarget>& targets, const KinematicsOptions& options)
    : data_(
          std::make_unique<IkData>(std::make_shared<const IkModel>(std::move(assembly), targets, options))) {}

InverseKinematics::InverseKinematics(std::unique_ptr<IkData> data) : data_(std::move(data)) {}
InverseKinematics::InverseKinematics(InverseKinematics&&) noexcept = default;
InverseKinematics& InverseKinematics::operator=(InverseKinematics&&) noexcept = default;
InverseKinematics::~InverseKinematics() = default;

InverseKinematics InverseKinematics::with_fresh_state() const {
  return InverseKinematics(std::make_unique<IkData>(data().model));
}

IkData& InverseKinematics::data() const {
  if (!data_) throw std::logic_error("pcr::InverseKinematics used after being moved from");
  return *data_;
}

const RobotAssembly& InverseKinematics::assembly() const {
  return *data().model->assembly;
}
const std::shared_ptr<const RobotAssembly>& InverseKinematics::assembly_ptr() const {
  return data().model->assembly;
}
const Problem& InverseKinematics::problem() const {
  return data().model->square;
}
VariableId InverseKinematics::target_variable(int target) const {
  const IkModel& m = *data().model;
  require(target >= 0 && target < static_cast<int>(m.targets.size()), "target_variable: target ", target,
          " out of range [0, ", m.targets.size(), ")");
  return m.target_variables[target];
}
ResidualId InverseKinematics::target_residual(int target) const {
  const IkModel& m = *data().model;
  require(target >= 0 && target < static_cast<int>(m.targets.size()), "target_residual: target ", target,
          " out of range [0, ", m.targets.size(), ")");
  return m.target_residuals[target];
}
const VecX& InverseKinematics::state() const {
  return data().x;
}
bool InverseKinematics::square() const {
  return data().model->square_system;
}

RobotSolution InverseKinematics::solve(const std::vector<Pose>& target_poses, const VecX* reference) {
  const auto start = kinematics::Clock::now();
  IkData& d = data();
  const IkModel& m = *d.model;
  const RobotAssembly& assembly = *m.assembly;
  const VecX z = stacked_targets(m, target_poses);
  const VecX ref = reference ? *reference : assembly.inputs(d.x);
  require(ref.size() == static_cast<int>(assembly.model().inputs().size()),
          "inverse kinematics: reference has ", ref.size(), " values, the model has ",
          assembly.model().inputs().size(), " inputs");
  IkAttempt a;
  a.x = d.x;
  // Input distance without stress limits and a square system: Newton (fast, warm-started along paths).
  const bool newton_first = !kinematics::uses_reduced_space(m.options.ik) && m.square_system;
  const bool first = !d.started;
  d.started = true;
  if (!(newton_first && solve_square(d, z, a, first))) {
    // Start from Newton's solution when it converged outside the input bounds, else from the last one.
    const bool from_newton = newton_first && a.summary.converged() && a.x.allFinite();
    optimise(d, with_targets(m, from_newton ? a.x : d.x, z), ref, a);
  }
  a.summary.iterations = a.iterations;
  a.summary.jacobian_evaluations = a.jacobians;
  bool accepted = false;
  RobotSolution out = kinematics::finish_solution(assembly, a.x, d.x, a.summary, start, m.sample_bases,
                                                  m.options.read_centerline, accepted);
  if (accepted) {
    d.x = a.x;
    d.predictor.accept(d.x, z);
    if (m.options.check_stability)  // J at the solution with its own inputs
      kinematics::monitor_stability(m.forward, d.x, d.last_jacobian_sign, out);
    if (m.options.stability_verdict)  // the FK system at the solution's own inputs
      kinematics::add_stability_verdict(assembly, d.x, out);
  }
  return out;
}

}  // namespace pcr
