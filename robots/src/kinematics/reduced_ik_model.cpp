// The immutable part of the reduced-space IK (reduced_ik.hpp): option checks, the FK system and the
// target rows of an IK problem, the inputs' layout and scales, the stress points.
#include <algorithm>
#include <cmath>

#include "pcr/core/error.hpp"
#include "reduced_ik.hpp"

namespace pcr::kinematics {

namespace {

void check_options(const IkOptions& o) {
  require(std::isfinite(o.distance_weight) && o.distance_weight >= 0.0,
          "IK options: distance_weight = ", o.distance_weight, " (must be finite and >= 0)");
  require(!o.max_rod_stress || (std::isfinite(*o.max_rod_stress) && *o.max_rod_stress > 0.0),
          "IK options: max_rod_stress = ", o.max_rod_stress.value_or(0.0), " Pa (must be finite and > 0)");
  require(o.max_input_step > 0.0, "IK options: max_input_step = ", o.max_input_step,
          " (must be > 0; infinity for no limit)");
  require(o.stress_points_per_rod == 0 || o.stress_points_per_rod >= 2,
          "IK options: stress_points_per_rod = ", o.stress_points_per_rod, " (0 for the default or >= 2)");
  require(o.optimality_tolerance > 0.0 && o.target_tolerance > 0.0,
          "IK options: optimality_tolerance = ", o.optimality_tolerance,
          ", target_tolerance = ", o.target_tolerance, " (must be > 0)");
  require(o.max_iterations > 0, "IK options: max_iterations = ", o.max_iterations, " (must be > 0)");
}

/// The problem with only the given residual blocks active.
Problem only_rows(const Problem& problem, const std::vector<ResidualId>& keep) {
  Problem out = problem;
  std::vector<ResidualId> others;
  for (ResidualId b = 0; b < problem.num_residual_blocks(); ++b)
    if (std::find(keep.begin(), keep.end(), b) == keep.end()) others.push_back(b);
  out.set_residual_active(others, false);
  out.set_residual_active(keep, true);
  return out;
}

/// Stress points per rod: the option, or 2 elements + 1 (element ends and midpoints) of the finest rod.
int stress_points_per_rod(const RobotAssembly& a, const IkOptions& o) {
  if (o.stress_points_per_rod != 0) return o.stress_points_per_rod;
  int max_elements = 1;
  for (int r = 0; r < a.num_rods(); ++r)
    max_elements = std::max(max_elements, a.rod(r).discretization().elements);
  return 2 * max_elements + 1;
}

}  // namespace

Problem forward_problem_of(const Problem& ik_problem, const RobotAssembly& assembly,
                           const std::vector<ResidualId>& target_residuals) {
  Problem fk = ik_problem;
  fk.set_residual_active(target_residuals, false);
  for (size_t i = 0; i < assembly.model().inputs().size(); ++i) {
    const VariableId v = assembly.input_variable(static_cast<int>(i));
    fk.fix_variable(v, ik_problem.variable(v).initial);
  }
  return fk;
}

bool uses_reduced_space(const IkOptions& o) {
  return o.objective != IkObjective::InputDistance || o.max_rod_stress.has_value();
}

ReducedIkModel::ReducedIkModel(std::shared_ptr<const RobotAssembly> a, const Problem& ik_problem,
                               const std::vector<ResidualId>& target_residuals, const KinematicsOptions& o)
    : assembly(std::move(a)), options(o) {
  check_options(o.ik);
  require(assembly != nullptr, "reduced IK: no assembly");
  forward = forward_problem_of(ik_problem, *assembly, target_residuals);
  targets = only_rows(ik_problem, target_residuals);
  require(targets.num_rows() > 0, "reduced IK: the problem has no target rows");
  const RobotModel& m = assembly->model();
  const int n_in = static_cast<int>(m.inputs().size());
  input_scales.resize(n_in);
  for (int i = 0; i < n_in; ++i) {
    input_offsets.push_back(ik_problem.variable(assembly->input_variable(i)).offset);
    input_scales[i] = m.inputs()[i].kind == ActuationInput::Kind::RodLength ? assembly->length_scale() : 1.0;
  }
  if (o.ik.max_rod_stress) {
    check_stress_data(*assembly);
    stress_at = stress_points(*assembly, stress_points_per_rod(*assembly, o.ik));
  }
  if (o.ik.objective == IkObjective::ActuationEffort)
    actuation_effort(*assembly, ik_problem.initial_values(), nullptr);  // throws if no rod is fed
}

}  // namespace pcr::kinematics
