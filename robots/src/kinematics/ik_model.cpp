// The problems of an inverse kinematics (ik_data.hpp), built once per IK model from the assembly's FK
// system: the target blocks added, the inputs freed, then the optimisation, FK-at-solution and
// reduced-space variants.
#include <algorithm>
#include <cmath>

#include "../assembly/robot_blocks.hpp"
#include "ik_data.hpp"
#include "input_objective.hpp"
#include "pcr/core/error.hpp"

namespace pcr::kinematics {

namespace {

/// The pose components a target selects (its mode and its component switches); at least one.
assembly::PoseComponents selected_components(const LinkTarget& t) {
  assembly::PoseComponents components = t.components;
  for (int i = 0; i < 3; ++i) {
    components[i] = components[i] && t.mode != LinkTarget::Mode::Orientation;
    components[3 + i] = components[3 + i] && t.mode != LinkTarget::Mode::Position;
  }
  require(std::count(components.begin(), components.end(), true) > 0, "inverse kinematics: target for '",
          t.link, "' selects no pose component");
  return components;
}

/// Adds per target a fixed pose block (initial value: the target's pose) and its PoseTargetBlock on the
/// carrying platform.
void add_targets(IkModel& ik, Problem& problem) {
  const RobotAssembly& a = *ik.assembly;
  const RobotModel& m = a.model();
  const std::vector<Pose> identity(m.platforms().size());
  const VecX q0 = m.default_joint_values();
  for (const LinkTarget& t : ik.targets) {
    const int link = m.link_index(t.link);
    const int platform = m.carrying_platform(link);
    require(platform >= 0, "inverse kinematics: target link '", t.link, "' is not carried by a platform");
    const Pose offset = m.link_pose(link, q0, identity);
    VecX z(7);
    z << t.pose.position, t.pose.orientation.normalized();
    const VariableId tv = problem.add_variable_block("target." + t.link, z);
    problem.fix_variable(tv, z);
    ik.target_variables.push_back(tv);
    ik.target_residuals.push_back(problem.add_residual_block(
        std::make_shared<assembly::PoseTargetBlock>("target." + t.link, a.platform_variable(platform), tv,
                                                    offset, selected_components(t), a.length_scale())));
  }
}

int free_unknowns(const Problem& problem) {
  int n = 0;
  for (int v = 0; v < problem.num_variable_blocks(); ++v)
    if (!problem.variable_fixed(v)) n += problem.variable(v).size;
  return n;
}

/// The optimisation problem: square with the input bounds, the reference inputs (a fixed block, initial
/// value the default inputs) and the input-distance objective; returns it, the reference block in
/// `reference`.
Problem optimisation_problem(const Problem& square, const RobotAssembly& a, VariableId& reference) {
  const RobotModel& m = a.model();
  const int n_in = static_cast<int>(m.inputs().size());
  Problem opt = square;
  std::vector<VariableId> inputs;
  VecX scales(n_in);
  for (int i = 0; i < n_in; ++i) {
    const ActuationInput& in = m.inputs()[i];
    opt.set_variable_bounds(a.input_variable(i), VecX::Constant(1, in.lower), VecX::Constant(1, in.upper));
    inputs.push_back(a.input_variable(i));
    scales[i] = in.kind == ActuationInput::Kind::RodLength ? a.length_scale() : 1.0;
  }
  reference = opt.add_variable_block("ik.reference", m.default_input_values());
  opt.fix_variable(reference, m.default_input_values());
  opt.add_objective_term(std::make_shared<InputDistance>(inputs, reference, scales));
  return opt;
}

}  // namespace

IkModel::IkModel(std::shared_ptr<const RobotAssembly> a, const std::vector<LinkTarget>& t,
                 const KinematicsOptions& o)
    : assembly(std::move(a)), options(o), targets(t) {
  require(assembly != nullptr, "InverseKinematics: no assembly");
  require(!targets.empty(), "inverse kinematics: no target given");
  for (int i = 0; i < assembly->num_rods(); ++i) {
    const RodContactVariables* c = assembly->rod_contact(i);
    require(c == nullptr || c->relaxation < 0,
            "inverse kinematics: contact_method ipopt is for forward kinematics only (use semismooth)");
  }
  square = assembly->problem();
  add_targets(*this, square);
  // Square problem: inputs free (no bounds: Newton checks them afterwards).
  for (size_t i = 0; i < assembly->model().inputs().size(); ++i)
    square.set_variable_bounds(assembly->input_variable(static_cast<int>(i)), VecX::Constant(1, -INFINITY),
                               VecX::Constant(1, INFINITY));
  const int free = free_unknowns(square);
  square_system = free == square.num_rows();
  // Reduced space (Ipopt over the inputs): other objectives and stress limits always; the input
  // distance when the targets leave inputs free, unless asked for the full space (IkOptions).
  reduced_space = uses_reduced_space(options.ik) || (free > square.num_rows() && !options.ik.full_space);
  if (options.check_stability) forward = forward_problem_of(square, *assembly, target_residuals);
  optimised = optimisation_problem(square, *assembly, reference);
  sample_bases = pcr::sample_bases(*assembly, options.centerline_points);
  if (reduced_space)  // validates the IK options
    reduced = std::make_shared<const ReducedIkModel>(assembly, square, target_residuals, options);
}

}  // namespace pcr::kinematics
