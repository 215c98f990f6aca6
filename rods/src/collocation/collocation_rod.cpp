#include "pcr/rods/collocation_rod.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "form_builder.hpp"
#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/solve/sparse_lu.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr {
using namespace collocation;

double rod_memory_estimate(int degree, int elements) {
  const double unknowns = 13.0 * (static_cast<double>(elements) + degree);  // n = E + p control points
  return unknowns * 13.0 * (degree + 1) * 8.0 * 8.0;
}

std::string rod_memory_excess(int degree, int elements) {
  const double bytes = rod_memory_estimate(degree, elements), GiB = 1024.0 * 1024.0 * 1024.0;
  if (bytes <= kMaxRodMemoryBytes) return {};
  std::ostringstream message;
  message.precision(3);
  message << elements << " elements of degree " << degree << " would take an estimated " << bytes / GiB
          << " GiB for one rod, more than the limit of " << kMaxRodMemoryBytes / GiB
          << " GiB per rod (rod_memory_estimate; fewer elements or a lower degree fit)";
  return message.str();
}

const char* to_string(RodFormulation formulation) {
  switch (formulation) {
    case RodFormulation::Primal: return "primal";
    case RodFormulation::Mixed: return "mixed";
    case RodFormulation::Condensed: return "condensed";
  }
  return "?";
}

const char* to_string(MixedPoints points) {
  return points == MixedPoints::Midpoints ? "midpoints" : "greville";
}

CollocationRod::CollocationRod(RodModel model, RodDiscretization discretization)
    : model_(std::move(model)), discretization_(discretization) {
  model_.validate();
  require(discretization.degree >= 2 && discretization.degree <= 9, "rod '", model_.name,
          "': collocation degree must be in [2, 9] (second derivatives are collocated), got ",
          discretization.degree);
  require(discretization.elements >= 1, "rod '", model_.name, "': number of elements must be >= 1, got ",
          discretization.elements);
  const std::string excess = rod_memory_excess(discretization.degree, discretization.elements);
  require(excess.empty(), "rod '", model_.name, "': ", excess);
  loaded_condensed_ = discretization.formulation == RodFormulation::Condensed &&
                      !(model_.distributed_force().isZero(0.0) && model_.loads.moment_per_length.isZero(0.0));
  switch (discretization.formulation) {
    case RodFormulation::Primal: form_ = &primal_form(); break;
    case RodFormulation::Mixed:
      form_ = discretization.mixed_points == MixedPoints::Midpoints ? &mixed_midpoint_form()
                                                                    : &mixed_greville_form();
      break;
    case RodFormulation::Condensed:
      // With loads: the running integrals where the rod leaves the band (kMaxBandedCondensedPoints).
      if (!loaded_condensed_)
        form_ = &condensed_form();
      else if (discretization.elements + discretization.degree > kMaxBandedCondensedPoints)
        form_ = &condensed_loaded_form();
      else
        form_ = &condensed_summed_form();
      break;
  }
  require(form_ != nullptr, "rod '", model_.name, "': unknown formulation");
  require(!discretization.contact_forces || form_ == &mixed_midpoint_form(), "rod '", model_.name,
          "': contact forces need the mixed form at the midpoints (formulation ",
          to_string(discretization.formulation), ", points ", to_string(discretization.mixed_points), ")");
  knots_ = std::make_shared<const KnotVector>(
      KnotVector::open_uniform(discretization.degree, discretization.elements));
  if (loaded_condensed_) integral_weights_ = basis_integrals(*knots_, 1.0);  // also integrals_at()
  const double L = model_.length;
  const double kb = model_.bending_torsion_stiffness.maxCoeff();
  force_scale_ = kb / (L * L);
  moment_scale_ = kb / L;
}

int CollocationRod::num_control_points() const {
  return knots_->num_basis();
}

const PointLayout& CollocationRod::point_layout() const {
  return form_->layout();
}

int CollocationRod::control_point_size() const {
  return point_layout().size;
}

int CollocationRod::configuration_size() const {
  const bool condensed = discretization_.formulation == RodFormulation::Condensed;
  return num_control_points() * control_point_size() + (condensed ? kWrenchSize : 0);
}

int CollocationRod::num_equations(const RodEndOptions& ends) const {
  return form_->field_rows(num_control_points()) + (ends.base ? 7 : 0) + (ends.tip ? 7 : 0);
}

VecX CollocationRod::straight_configuration() const {
  const bool from_base = model_.base.kind == RodEndKind::Clamped || model_.tip.kind != RodEndKind::Clamped;
  const RodEnd& end = from_base ? model_.base : model_.tip;
  const Quat q = end.orientation.normalized();
  const Vec3 d3 = rotation_matrix(q).col(2);
  const std::vector<double> tau = knots_->greville();
  const int n = num_control_points(), cp = control_point_size();
  const double L = model_.length;
  VecX x = VecX::Zero(configuration_size());
  for (int i = 0; i < n; ++i) {
    // Greville abscissae reproduce linear functions: sum_i N_i(u) tau_i = u, so P_i = p0 + L tau_i d3.
    const Vec3 p =
        from_base ? Vec3(end.position + L * tau[i] * d3) : Vec3(end.position - L * (1.0 - tau[i]) * d3);
    x.segment<3>(i * cp + point_layout().p) = p;
    x.segment<4>(i * cp + point_layout().q) = q;
  }
  return x;
}

VecX CollocationRod::stress_free_configuration() const {
  if (model_.base.kind != RodEndKind::Clamped || model_.intrinsic.is_zero()) return straight_configuration();
  // Second-order Lie midpoint steps, fine enough that the shape error (O(h^2)) is far below what an
  // initial guess needs: p(s + h) = p + h R(s + h/2) v(s + h/2), R(s + h) = R exp(h hat(kappa0(s + h/2))).
  const double L = model_.length;
  const std::vector<double> tau = knots_->greville();
  const int n = num_control_points(), cp = control_point_size();
  const int steps_per_point = 64;
  MatX values = MatX::Zero(n, cp);
  Vec3 p = model_.base.position;
  Mat3 R = rotation_matrix(model_.base.orientation.normalized());
  Quat q_previous = model_.base.orientation.normalized();
  double s = 0.0;
  for (int i = 0; i < n; ++i) {
    const double s_target = tau[i] * L;
    const double h = (s_target - s) / steps_per_point;
    for (int k = 0; k < steps_per_point && h > 0.0; ++k) {
      Vec3 eps0, kappa0;
      model_.intrinsic.at(s + 0.5 * h, eps0, kappa0);
      const Mat3 R_mid = R * so3_exp(0.5 * h * kappa0);
      p += h * R_mid * (Vec3::UnitZ() + eps0);
      R = R * so3_exp(h * kappa0);
      s += h;
    }
    s = s_target;
    Quat q = quat_from_rotation(R);
    if (q.dot(q_previous) < 0.0) q = -q;  // continuous sign along the rod
    q_previous = q;
    values.block<1, 3>(i, point_layout().p) = p.transpose();
    values.block<1, 4>(i, point_layout().q) = q.transpose();
  }
  // Control points interpolating these values at the Greville abscissae.
  SparseLu lu;
  require(lu.compute(collocation_matrix(*knots_, tau, 0)), "rod '", model_.name,
          "': Greville interpolation matrix is singular");
  const MatX points = lu.solve(values);
  VecX x = VecX::Zero(configuration_size());
  for (int i = 0; i < n; ++i) x.segment(i * cp, cp) = points.row(i).transpose();
  return x;
}

RodVariables CollocationRod::add_to_problem(Problem& problem, const RodEndOptions& ends, double load_factor,
                                            bool free_length, int group, const VecX* initial) const {
  const RodVariables vars = add_variables(problem, free_length, group, initial);
  form_->add_blocks(FormBuilder(*this, problem, vars, ends, load_factor));
  return vars;
}

RodVariables CollocationRod::add_variables(Problem& problem, bool free_length, int group,
                                           const VecX* initial) const {
  const int n = num_control_points(), cp = control_point_size();
  const std::string& name = model_.name;
  VecX init = initial ? *initial : straight_configuration();
  require(init.size() == configuration_size(), "rod '", name, "': initial guess has ", init.size(),
          " values, expected ", configuration_size());
  require(init.allFinite(), "rod '", name, "': initial guess is not finite");
  set_running_integrals(init);

  // Natural magnitudes of the unknowns (Problem::set_variable_scale): P and T against L0, N against F0,
  // M and h against M0, contact force densities against F0 / L0. A round-off stall of rows balancing
  // forces far above F0 is judged against them (residuals_within_round_off).
  const PointLayout& z = point_layout();
  const double L0 = length_scale();
  VecX cp_scale = VecX::Ones(cp);
  cp_scale.segment<3>(z.p).setConstant(L0);
  if (z.n >= 0) cp_scale.segment<3>(z.n).setConstant(force_scale_);
  if (z.m >= 0) cp_scale.segment<3>(z.m).setConstant(moment_scale_);
  if (z.integral >= 0) cp_scale.segment<3>(z.integral).setConstant(L0);
  RodVariables vars;
  for (int i = 0; i < n; ++i) {
    vars.control_points.push_back(
        problem.add_variable_block(name + ".cp" + std::to_string(i), init.segment(i * cp, cp)));
    problem.set_variable_scale(vars.control_points.back(), cp_scale);
    if (group >= 0) problem.set_variable_group(vars.control_points.back(), group);
  }
  if (discretization_.formulation == RodFormulation::Condensed) {
    vars.wrench = problem.add_variable_block(name + ".wrench", init.tail(kWrenchSize));
    VecX wrench_scale(kWrenchSize);
    wrench_scale << Vec3::Constant(force_scale_), Vec3::Constant(moment_scale_);
    problem.set_variable_scale(vars.wrench, wrench_scale);
    if (group >= 0) problem.set_variable_group(vars.wrench, group);
    vars.wrench_offset = problem.variable(vars.wrench).offset;
  }
  vars.length = problem.add_variable_block(name + ".length", VecX::Constant(1, model_.length));
  if (group >= 0) problem.set_variable_group(vars.length, group);
  if (!free_length) problem.fix_variable(vars.length, VecX::Constant(1, model_.length));
  if (discretization_.contact_forces) {
    for (int j = 0; j + 1 < n; ++j) {
      vars.contact_forces.push_back(
          problem.add_variable_block(name + ".contact_force" + std::to_string(j), VecX::Zero(3)));
      problem.set_variable_scale(vars.contact_forces.back(), VecX::Constant(3, force_scale_ / L0));
      if (group >= 0) problem.set_variable_group(vars.contact_forces.back(), group);
    }
  }
  vars.control_point_offset = problem.variable(vars.control_points[0]).offset;
  vars.length_offset = problem.variable(vars.length).offset;
  return vars;
}

void CollocationRod::set_running_integrals(VecX& configuration) const {
  const int t = point_layout().integral, cp = control_point_size(), p = point_layout().p;
  if (t < 0) return;
  Vec3 T = Vec3::Zero();  // T_0 = 0, T_{i+1} = T_i + w_i P_i
  for (int i = 0; i < num_control_points(); ++i) {
    configuration.segment<3>(i * cp + t) = T;
    T += integral_weights_[i] * configuration.segment<3>(i * cp + p);
  }
}

double CollocationRod::length(const VecX& x, const RodVariables& vars) const {
  return x[vars.length_offset];
}

}  // namespace pcr
