#include "pcr/robots/robot_assembly.hpp"

#include <algorithm>
#include <cmath>

#include "contact_assembly.hpp"
#include "link_frame.hpp"
#include "passive_joint_block.hpp"
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
  assembly::set_contact_discretization(e, o.use_model_hints, d);
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

bool operator==(const AssemblyOptions& a, const AssemblyOptions& b) {
  const RodDiscretization &d = a.discretization, &e = b.discretization;
  return d.formulation == e.formulation && d.degree == e.degree && d.elements == e.elements &&
         d.mixed_points == e.mixed_points && d.contact_forces == e.contact_forces &&
         a.use_model_hints == b.use_model_hints &&
         a.formulation_by_slenderness == b.formulation_by_slenderness &&
         a.primal_min_gyration_ratio == b.primal_min_gyration_ratio &&
         a.condense_mixed_rods == b.condense_mixed_rods && a.contact_function == b.contact_function &&
         a.contact_method == b.contact_method;
}
bool operator!=(const AssemblyOptions& a, const AssemblyOptions& b) {
  return !(a == b);
}

// Builds a RobotAssembly's problem step by step (the constructor's parts).
struct RobotAssembly::Builder {
  RobotAssembly& a;
  const RobotModel& m;
  const AssemblyOptions& options;
  const VecX q0;                      // default joint values
  const std::vector<Pose> platform0;  // initial platform poses
  std::vector<std::vector<assembly::PlatformRodEnd>> platform_ends;
  std::vector<std::vector<assembly::PlatformContact>> platform_contacts;  // rods touching their obstacles

  Builder(RobotAssembly& assembly, const AssemblyOptions& o)
      : a(assembly),
        m(*assembly.model_),
        options(o),
        q0(m.default_joint_values()),
        platform0(m.initial_platform_poses()),
        platform_ends(m.platforms().size()),
        platform_contacts(m.platforms().size()) {}

  /// Platform poses and joint values.
  void add_pose_and_joint_variables() {
    for (size_t p = 0; p < m.platforms().size(); ++p) {
      VecX z(7);
      z << platform0[p].position, platform0[p].orientation.normalized();
      a.platform_variables_.push_back(a.problem_.add_variable_block("platform." + m.platforms()[p].name, z));
    }
    a.joint_variables_.assign(m.joint_value_count(), -1);
    for (const Joint& j : m.joints())
      if (j.value_index >= 0)
        a.joint_variables_[j.value_index] =
            a.problem_.add_variable_block("joint." + j.name, VecX::Constant(1, q0[j.value_index]));
  }

  /// Rod i with its couplings (its ends on platforms noted for their balances).
  void add_rod(int i) {
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
    const RodVariables vars =
        rod->add_to_problem(a.problem_, {!start_attached, !end_attached}, 1.0, e.length_actuated, i, &guess);
    a.length_scale_ = std::max(a.length_scale_, rod->length_scale());
    a.force_scale_ = std::max(a.force_scale_, rod->force_scale());
    a.moment_scale_ = std::max(a.moment_scale_, rod->moment_scale());
    a.rod_contacts_.emplace_back();
    if (!e.obstacles.empty()) {
      const bool relaxed = options.contact_method == ContactMethod::Ipopt;  // contact_ipopt.hpp
      const assembly::RodContactSetup contact = assembly::rod_contact_setup(
          m, e, relaxed ? ComplementarityFunction::GapOnly : options.contact_function, rod->point_layout().p,
          a.platform_variables_, a.joint_variables_);
      require(!relaxed || !contact.wrap_block, "rod '", e.name,
              "': contact_method = ipopt with obstacles on a moving link is not supported (use semismooth)");
      a.rod_contacts_.back() = add_rod_contact(a.problem_, *rod, vars, contact.options, contact.wrap_block);
      if (relaxed) relax_rod_contact(a.problem_, *rod, a.rod_contacts_.back());
      if (contact.platform >= 0)
        platform_contacts[contact.platform].push_back(
            assembly::platform_contact(*rod, vars, a.rod_contacts_.back()));
    }
    a.rod_couplings_.push_back({-1, -1});
    for (bool at_tip : {false, true})
      if (attached(at_tip ? e.end : e.start)) add_coupling(e, *rod, vars, at_tip);
    a.rods_.push_back(rod);
    a.rod_variables_.push_back(vars);
  }

  void add_coupling(const RodElement& e, const CollocationRod& rod, const RodVariables& vars, bool at_tip) {
    const RodAttachment& at = at_tip ? e.end : e.start;
    collocation::PointConstants scales;
    scales.length_scale = rod.length_scale();
    scales.force_scale = rod.force_scale();
    scales.moment_scale = rod.moment_scale();
    RodEndEvaluator end(rod, vars, at_tip);
    LinkFrame frame = LinkFrame::of(m, at.link, at.frame, a.platform_variables_, a.joint_variables_);
    a.rod_couplings_.back()[at_tip ? 1 : 0] =
        a.problem_.add_residual_block(std::make_shared<assembly::CouplingBlock>(
            e.name + (at_tip ? ".end" : ".start"), end, frame, at.coupling, at.axis, scales));
    const int platform = m.carrying_platform(at.link);
    if (platform >= 0) platform_ends[platform].push_back({end, at_tip ? 1.0 : -1.0});
  }

  /// Platform balances (loads on platform-carried links are moved to the platform frame).
  void add_platform_balances() {
    const std::vector<Pose> identity(m.platforms().size());
    for (size_t p = 0; p < m.platforms().size(); ++p) {
      const Platform& pl = m.platforms()[p];
      std::vector<assembly::PlatformLoad> loads;
      for (const ExternalLoad& l : m.loads()) {
        if (m.carrying_platform(l.link) != static_cast<int>(p)) continue;
        const Pose link_in_platform = m.link_pose(l.link, q0, identity);
        loads.push_back({link_in_platform.transform_point(l.point), l.force, l.torque});
      }
      const Vec3 com = m.link_pose(pl.link, q0, identity).transform_point(pl.center_of_mass);
      require(!platform_ends[p].empty(), "platform '", pl.name, "': no rod is attached to it");
      a.platform_balances_.push_back(
          a.problem_.add_residual_block(std::make_shared<assembly::PlatformBalanceBlock>(
              pl.name, a.platform_variables_[p], platform_ends[p], loads, pl.mass, com, m.gravity(),
              a.force_scale_, a.moment_scale_, platform_contacts[p])));
    }
  }

  /// Passive joint balances: the rod ends, loads and link weights on the links each joint moves.
  void add_passive_joint_balances() {
    for (int j : m.passive_joints()) {
      std::vector<assembly::PlatformRodEnd> ends;
      for (int r = 0; r < a.num_rods(); ++r) {
        const RodElement& e = m.rods()[r];
        for (bool at_tip : {false, true}) {
          const RodAttachment& at = at_tip ? e.end : e.start;
          if (attached(at) && m.joint_moves_link(j, at.link))
            ends.push_back({RodEndEvaluator(*a.rods_[r], a.rod_variables_[r], at_tip), at_tip ? 1.0 : -1.0});
        }
      }
      std::vector<assembly::LinkLoad> loads;
      for (const ExternalLoad& l : m.loads())
        if (m.joint_moves_link(j, l.link)) loads.push_back({l.link, l.point, l.force, l.torque});
      for (int l = 0; l < static_cast<int>(m.links().size()); ++l) {
        const Link& link = m.links()[l];
        if (link.mass > 0.0 && m.joint_moves_link(j, l))
          loads.push_back({l, link.center_of_mass, link.mass * m.gravity(), Vec3::Zero()});
      }
      a.passive_joint_balances_.push_back(
          a.problem_.add_residual_block(std::make_shared<assembly::PassiveJointBlock>(
              m, j, a.joint_variables_, std::move(ends), std::move(loads), a.force_scale_, a.moment_scale_)));
    }
  }

  /// Inputs (rod lengths and joint values) fixed, initial values their defaults; the other joints fixed
  /// at their defaults, except the passive ones (unknowns).
  void fix_inputs_and_joints() {
    for (const ActuationInput& in : m.inputs()) {
      a.input_variables_.push_back(in.kind == ActuationInput::Kind::RodLength
                                       ? a.rod_variables_[in.index].length
                                       : a.joint_variables_[m.joints()[in.index].value_index]);
    }
    const VecX u0 = m.default_input_values();
    a.check_inputs(u0);
    for (size_t i = 0; i < a.input_variables_.size(); ++i)
      a.problem_.fix_variable(a.input_variables_[i], VecX::Constant(1, u0[i]));
    for (const Joint& j : m.joints())
      if (j.value_index >= 0 && !j.passive && !a.problem_.variable_fixed(a.joint_variables_[j.value_index]))
        a.problem_.fix_variable(a.joint_variables_[j.value_index], VecX::Constant(1, q0[j.value_index]));
  }
};

RobotAssembly::RobotAssembly(std::shared_ptr<const RobotModel> model, const AssemblyOptions& options)
    : model_(std::move(model)), options_(options) {
  require(model_ != nullptr, "RobotAssembly: no model");
  Builder build(*this, options);
  build.add_pose_and_joint_variables();
  length_scale_ = force_scale_ = moment_scale_ = 0.0;
  for (size_t i = 0; i < model_->rods().size(); ++i) build.add_rod(static_cast<int>(i));
  build.add_platform_balances();
  build.add_passive_joint_balances();
  build.fix_inputs_and_joints();
  int free_unknowns = 0;
  for (int v = 0; v < problem_.num_variable_blocks(); ++v)
    if (!problem_.variable_fixed(v)) free_unknowns += problem_.variable(v).size;
  // Relaxed contact (contact_ipopt.hpp) adds one inequality row a b <= mu per contact pair.
  int product_rows = 0;
  for (const RodContactVariables& c : rod_contacts_)
    if (c.relaxation >= 0)
      product_rows += static_cast<int>(c.multipliers.size() * c.distributed.size() + c.sharp.size());
  require(free_unknowns == problem_.num_rows() - product_rows, "robot '", model_->name(),
          "': the assembly has ", problem_.num_rows() - product_rows, " equations for ", free_unknowns,
          " unknowns (with inputs fixed); check the rod couplings");
}

const RodContactVariables* RobotAssembly::rod_contact(int i) const {
  require(i >= 0 && i < num_rods(), "rod_contact: rod ", i, " out of range [0, ", num_rods(), ")");
  return rod_contacts_[i].blocks.empty() ? nullptr : &rod_contacts_[i];
}

ResidualId RobotAssembly::platform_balance(int platform) const {
  require(platform >= 0 && platform < static_cast<int>(platform_balances_.size()),
          "platform_balance: platform ", platform, " out of range [0, ", platform_balances_.size(), ")");
  return platform_balances_[platform];
}

VariableId RobotAssembly::passive_joint_variable(int passive) const {
  const std::vector<int>& passive_joints = model_->passive_joints();
  require(passive >= 0 && passive < static_cast<int>(passive_joints.size()),
          "passive_joint_variable: ", passive, " out of range [0, ", passive_joints.size(), ")");
  return joint_variables_[model_->joints()[passive_joints[passive]].value_index];
}

ResidualId RobotAssembly::passive_joint_balance(int passive) const {
  require(passive >= 0 && passive < static_cast<int>(passive_joint_balances_.size()),
          "passive_joint_balance: ", passive, " out of range [0, ", passive_joint_balances_.size(), ")");
  return passive_joint_balances_[passive];
}

ResidualId RobotAssembly::rod_coupling(int rod, bool at_tip) const {
  require(rod >= 0 && rod < num_rods(), "rod_coupling: rod ", rod, " out of range [0, ", num_rods(), ")");
  return rod_couplings_[rod][at_tip ? 1 : 0];
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

void RobotAssembly::check_inputs(const VecX& inputs) const {
  require(inputs.size() == static_cast<int>(input_variables_.size()), "robot '", model_->name(),
          "': ", inputs.size(), " input values given, the model has ", input_variables_.size());
  for (size_t i = 0; i < input_variables_.size(); ++i) {
    const ActuationInput& in = model_->inputs()[i];
    require(std::isfinite(inputs[i]), "input '", in.name, "': value is not finite");
    require(inputs[i] >= in.lower && inputs[i] <= in.upper, "input '", in.name, "' = ", inputs[i],
            " is outside its bounds [", in.lower, ", ", in.upper, "]");
  }
}

}  // namespace pcr
