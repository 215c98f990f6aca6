#include "pcr/robots/robot_assembly.hpp"

#include <algorithm>

#include "link_frame.hpp"
#include "pcr/core/error.hpp"
#include "pcr/rods/rod_end.hpp"
#include "robot_blocks.hpp"

namespace pcr {
using assembly::LinkFrame;

namespace {

RodDiscretization discretization_for(const RodElement& e, const AssemblyOptions& o) {
  RodDiscretization d = o.discretization;
  if (o.formulation_by_slenderness)
    d.formulation = formulation_by_slenderness(e, o.primal_min_gyration_ratio);
  if (o.use_model_hints) {
    if (e.formulation == RodFormulationHint::Primal) d.formulation = RodFormulation::Primal;
    if (e.formulation == RodFormulationHint::Mixed) d.formulation = RodFormulation::Mixed;
    if (e.degree > 0) d.degree = e.degree;
    if (e.elements > 0) d.elements = e.elements;
  }
  // The condensed form is the mixed midpoint scheme with n, m from the closed-form balance (CollocationRod);
  // a model that asks for the mixed form by name gets it.
  const bool hinted_mixed = o.use_model_hints && e.formulation == RodFormulationHint::Mixed;
  if (o.condense_mixed_rods && !hinted_mixed && d.formulation == RodFormulation::Mixed &&
      d.mixed_points == MixedPoints::Midpoints)
    d.formulation = RodFormulation::Condensed;
  return d;
}

bool attached(const RodAttachment& a) {
  return a.link >= 0 && a.coupling != RodEndKind::Free;
}

// Control points of an initial rod shape: cubic Hermite from the start frame to the end frame
// (tangents L d3), orientations by normalised linear interpolation (sign-aligned).
VecX hermite_guess(const CollocationRod& rod, const Pose& start, const Pose* end, bool from_end) {
  const std::vector<double> tau = rod.knots().greville();
  const int n = rod.num_control_points(), cp = rod.control_point_size();
  const double L = rod.model().length;
  VecX x = VecX::Zero(rod.configuration_size());  // a condensed rod's wrench starts at zero
  const Vec3 ts = start.rotation().col(2);
  for (int i = 0; i < n; ++i) {
    const double u = tau[i];
    Vec3 p;
    Quat q = start.orientation;
    if (end == nullptr) {
      p = from_end ? Vec3(start.position - L * (1.0 - u) * ts) : Vec3(start.position + L * u * ts);
    } else {
      const Vec3 te = end->rotation().col(2);
      const double h00 = 2 * u * u * u - 3 * u * u + 1, h10 = u * u * u - 2 * u * u + u;
      const double h01 = -2 * u * u * u + 3 * u * u, h11 = u * u * u - u * u;
      p = h00 * start.position + h10 * L * ts + h01 * end->position + h11 * L * te;
      Quat qe = end->orientation;
      if (qe.dot(q) < 0) qe = -qe;
      q = ((1.0 - u) * q + u * qe).normalized();
    }
    x.segment<3>(i * cp) = p;
    x.segment<4>(i * cp + 3) = q;
  }
  return x;
}

}  // namespace

RobotAssembly::RobotAssembly(std::shared_ptr<const RobotModel> model, const AssemblyOptions& options)
    : model_(std::move(model)) {
  require(model_ != nullptr, "RobotAssembly: no model");
  const RobotModel& m = *model_;
  const VecX q0 = m.default_joint_values();
  const std::vector<Pose> platform0 = m.initial_platform_poses();

  // Platform poses and joint values.
  for (size_t p = 0; p < m.platforms().size(); ++p) {
    VecX z(7);
    z << platform0[p].position, platform0[p].orientation.normalized();
    platform_variables_.push_back(problem_.add_variable_block("platform." + m.platforms()[p].name, z));
  }
  joint_variables_.assign(m.joint_value_count(), -1);
  for (const Joint& j : m.joints())
    if (j.value_index >= 0)
      joint_variables_[j.value_index] =
          problem_.add_variable_block("joint." + j.name, VecX::Constant(1, q0[j.value_index]));

  // Rods with their couplings.
  std::vector<std::vector<assembly::PlatformRodEnd>> platform_ends(m.platforms().size());
  length_scale_ = 0.0;
  force_scale_ = 0.0;
  moment_scale_ = 0.0;
  for (size_t i = 0; i < m.rods().size(); ++i) {
    const RodElement& e = m.rods()[i];
    RodModel rm = e.rod;
    rm.base.kind = e.start.coupling;
    rm.tip.kind = e.end.coupling;
    rm.length = e.length_actuated ? e.length_default : e.rod.length;
    const bool start_attached = attached(e.start), end_attached = attached(e.end);
    const Pose start = start_attached ? m.attachment_pose(e.start, q0, platform0) : Pose{};
    const Pose finish = end_attached ? m.attachment_pose(e.end, q0, platform0) : Pose{};
    // The rod's base frame at the initial configuration (the couplings hold the ends; the condensed
    // form takes its moment unknown about this point, CollocationRod::moment_point).
    if (start_attached) {
      rm.base.position = start.position;
      rm.base.orientation = start.orientation;
    }
    auto rod = std::make_shared<const CollocationRod>(rm, discretization_for(e, options));
    const VecX guess = start_attached ? hermite_guess(*rod, start, end_attached ? &finish : nullptr, false)
                                      : hermite_guess(*rod, finish, nullptr, true);
    const RodVariables vars = rod->add_to_problem(problem_, {!start_attached, !end_attached}, 1.0,
                                                  e.length_actuated, static_cast<int>(i), &guess);
    collocation::PointConstants scales;
    scales.length_scale = rod->length_scale();
    scales.force_scale = rod->force_scale();
    scales.moment_scale = rod->moment_scale();
    length_scale_ = std::max(length_scale_, rod->length_scale());
    force_scale_ = std::max(force_scale_, rod->force_scale());
    moment_scale_ = std::max(moment_scale_, rod->moment_scale());
    for (bool at_tip : {false, true}) {
      const RodAttachment& a = at_tip ? e.end : e.start;
      if (!attached(a)) continue;
      RodEndEvaluator end(*rod, vars, at_tip);
      LinkFrame frame = LinkFrame::of(m, a.link, a.frame, platform_variables_, joint_variables_);
      problem_.add_residual_block(std::make_shared<assembly::CouplingBlock>(
          e.name + (at_tip ? ".end" : ".start"), end, frame, a.coupling, scales));
      const int platform = m.carrying_platform(a.link);
      if (platform >= 0) platform_ends[platform].push_back({end, at_tip ? 1.0 : -1.0});
    }
    rods_.push_back(rod);
    rod_variables_.push_back(vars);
  }

  // Platform balances (loads on platform-carried links are moved to the platform frame).
  for (size_t p = 0; p < m.platforms().size(); ++p) {
    const Platform& pl = m.platforms()[p];
    std::vector<Pose> identity(m.platforms().size());
    std::vector<assembly::PlatformLoad> loads;
    for (const ExternalLoad& l : m.loads()) {
      if (m.carrying_platform(l.link) != static_cast<int>(p)) continue;
      const Pose link_in_platform = m.link_pose(l.link, q0, identity);
      loads.push_back({link_in_platform.transform_point(l.point), l.force, l.torque});
    }
    const Vec3 com = m.link_pose(pl.link, q0, identity).transform_point(pl.center_of_mass);
    require(!platform_ends[p].empty(), "platform '", pl.name, "': no rod is attached to it");
    problem_.add_residual_block(std::make_shared<assembly::PlatformBalanceBlock>(
        pl.name, platform_variables_[p], platform_ends[p], loads, pl.mass, com, m.gravity(), force_scale_,
        moment_scale_));
  }

  // Inputs: rod lengths and joint values; fixed at their defaults until told otherwise.
  for (const ActuationInput& in : m.inputs()) {
    input_variables_.push_back(in.kind == ActuationInput::Kind::RodLength
                                   ? rod_variables_[in.index].length
                                   : joint_variables_[m.joints()[in.index].value_index]);
  }
  fix_inputs(m.default_input_values());
  // Joints that are not inputs stay at their defaults.
  for (const Joint& j : m.joints())
    if (j.value_index >= 0 && !problem_.variable_fixed(joint_variables_[j.value_index]))
      problem_.fix_variable(joint_variables_[j.value_index], VecX::Constant(1, q0[j.value_index]));

  int free_unknowns = 0;
  for (int v = 0; v < problem_.num_variable_blocks(); ++v)
    if (!problem_.variable_fixed(v)) free_unknowns += problem_.variable(v).size;
  require(free_unknowns == problem_.num_rows(), "robot '", m.name(), "': the assembly has ",
          problem_.num_rows(), " equations for ", free_unknowns,
          " unknowns (with inputs fixed); check the rod couplings");
}

VecX RobotAssembly::initial_guess() const {
  return problem_.initial_values();
}

VecX RobotAssembly::inputs(const VecX& x) const {
  VecX u(input_variables_.size());
  for (size_t i = 0; i < input_variables_.size(); ++i)
    u[i] = x[problem_.variable(input_variables_[i]).offset];
  return u;
}

void RobotAssembly::set_inputs(VecX& x, const VecX& inputs) const {
  require(inputs.size() == static_cast<int>(input_variables_.size()), "robot '", model_->name(),
          "': ", inputs.size(), " input values given, the model has ", input_variables_.size());
  for (size_t i = 0; i < input_variables_.size(); ++i)
    x[problem_.variable(input_variables_[i]).offset] = inputs[i];
}

Pose RobotAssembly::platform_pose(const VecX& x, int platform) const {
  const int o = problem_.variable(platform_variables_[platform]).offset;
  Pose pose;
  pose.position = x.segment<3>(o);
  pose.orientation = x.segment<4>(o + 3).normalized();
  return pose;
}

void RobotAssembly::fix_inputs(const VecX& inputs) {
  require(inputs.size() == static_cast<int>(input_variables_.size()), "robot '", model_->name(),
          "': ", inputs.size(), " input values given, the model has ", input_variables_.size());
  for (size_t i = 0; i < input_variables_.size(); ++i) {
    const ActuationInput& in = model_->inputs()[i];
    require(std::isfinite(inputs[i]), "input '", in.name, "': value is not finite");
    require(inputs[i] >= in.lower && inputs[i] <= in.upper, "input '", in.name, "' = ", inputs[i],
            " is outside its bounds [", in.lower, ", ", in.upper, "]");
    problem_.fix_variable(input_variables_[i], VecX::Constant(1, inputs[i]));
  }
}

void RobotAssembly::free_inputs() {
  for (size_t i = 0; i < input_variables_.size(); ++i) {
    const ActuationInput& in = model_->inputs()[i];
    problem_.set_variable_bounds(input_variables_[i], VecX::Constant(1, in.lower),
                                 VecX::Constant(1, in.upper));
  }
}

}  // namespace pcr
