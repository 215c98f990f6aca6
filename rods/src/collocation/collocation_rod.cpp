#include "pcr/rods/collocation_rod.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "pcr/core/error.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/rods/collocation/end_equations.hpp"
#include "pcr/rods/collocation/equations.hpp"
#include "pcr/rods/collocation/point_block.hpp"
#include "pcr/solve/sparse_lu.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr {
using namespace collocation;

namespace {

// Control point layout: [P (3), Q (4)] and, in the mixed form, [N (3), M (3)].
constexpr int kP = 0, kQ = 3, kN = 7, kM = 10;

// Local variable layouts of the kernels in equations.hpp (offset, component, size, derivative order).
const std::vector<LocalGroup> kPrimalInterior = {
    {0, kQ, 4, 0}, {4, kQ, 4, 1}, {8, kQ, 4, 2}, {12, kP, 3, 1}, {15, kP, 3, 2}};
const std::vector<LocalGroup> kMixedPoint = {{0, kQ, 4, 0},  {4, kQ, 4, 1},  {8, kP, 3, 1}, {11, kN, 3, 0},
                                             {14, kN, 3, 1}, {17, kM, 3, 0}, {20, kM, 3, 1}};
const std::vector<LocalGroup> kPrimalEnd = {{0, kP, 3, 0}, {3, kQ, 4, 0}, {7, kQ, 4, 1}, {11, kP, 3, 1}};
const std::vector<LocalGroup> kMixedEnd = {{0, kP, 3, 0}, {3, kQ, 4, 0}, {7, kN, 3, 0}, {10, kM, 3, 0}};
// Condensed form: the control point part of z (condensed_field; the wrench block is read directly).
const std::vector<LocalGroup> kCondensedPoint = {{0, kQ, 4, 0}, {4, kQ, 4, 1}, {8, kP, 3, 1}, {11, kP, 3, 0}};
const std::vector<LocalGroup> kCondensedEnd = {{0, kP, 3, 0}, {3, kQ, 4, 0}};
// Condensed form with distributed loads: also I(u) = integral_0^u p (condensed_loaded_field).
const std::vector<LocalGroup> kCondensedLoadedPoint = {
    {0, kQ, 4, 0}, {4, kQ, 4, 1}, {8, kP, 3, 1}, {11, kP, 3, 0}, {21, kP, 3, kIntegral}};
const std::vector<LocalGroup> kCondensedLoadedEnd = {{0, kP, 3, 0}, {3, kQ, 4, 0}, {14, kP, 3, kIntegral}};
constexpr int kWrenchSize = 6;  // [n (3), h (3)]

// The constant frame and the prescribed loads of a model end (load factor and signs applied).
struct EndData {
  RodEndKind kind;
  EndTarget<double> target;
  EndLoads loads;
};

EndData end_data(const RodEnd& end, bool at_base, double load_factor) {
  EndData e;
  e.kind = end.kind;
  e.target.position = end.position;
  e.target.orientation = end.orientation.normalized();
  e.target.frame = rotation_matrix(e.target.orientation);
  const double sign = at_base ? -1.0 : 1.0;
  e.loads.n_bar = sign * load_factor * end.force;
  e.loads.m_bar = sign * load_factor * end.moment;
  return e;
}

template <typename T>
EndTarget<T> cast_target(const EndTarget<double>& t) {
  return {t.position.cast<T>(), t.orientation.cast<T>(), t.frame.cast<T>()};
}

}  // namespace

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
  require(discretization.elements >= 1 && discretization.elements <= 100000, "rod '", model_.name,
          "': number of elements must be in [1, 100000], got ", discretization.elements);
  loaded_condensed_ = discretization.formulation == RodFormulation::Condensed &&
                      !(model_.distributed_force().isZero(0.0) && model_.loads.moment_per_length.isZero(0.0));
  knots_ = std::make_shared<const KnotVector>(
      KnotVector::open_uniform(discretization.degree, discretization.elements));
  const double L = model_.length;
  const double kb = model_.bending_torsion_stiffness.maxCoeff();
  force_scale_ = kb / (L * L);
  moment_scale_ = kb / L;
}

int CollocationRod::num_control_points() const {
  return knots_->num_basis();
}

int CollocationRod::control_point_size() const {
  return discretization_.formulation == RodFormulation::Mixed ? 13 : 7;
}

int CollocationRod::configuration_size() const {
  const bool condensed = discretization_.formulation == RodFormulation::Condensed;
  return num_control_points() * control_point_size() + (condensed ? kWrenchSize : 0);
}

int CollocationRod::num_equations(const RodEndOptions& ends) const {
  const int n = num_control_points();
  const int interior = (n - 2) * control_point_size();
  // Mixed (either point set): 12 (n - 1) + (n - 2) = 13 (n - 2) + 12 rows; condensed: 6 (n - 1) + (n - 2).
  const int constitutive_ends = discretization_.formulation == RodFormulation::Mixed       ? 12
                                : discretization_.formulation == RodFormulation::Condensed ? 6
                                                                                           : 0;
  return interior + constitutive_ends + (ends.base ? 7 : 0) + (ends.tip ? 7 : 0);
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
    x.segment<3>(i * cp + kP) = p;
    x.segment<4>(i * cp + kQ) = q;
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
    values.block<1, 3>(i, kP) = p.transpose();
    values.block<1, 4>(i, kQ) = q.transpose();
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
  const int n = num_control_points(), cp = control_point_size(), p = discretization_.degree;
  const bool mixed = discretization_.formulation == RodFormulation::Mixed;
  const bool condensed = discretization_.formulation == RodFormulation::Condensed;
  const std::string& name = model_.name;
  const VecX init = initial ? *initial : straight_configuration();
  require(init.size() == configuration_size(), "rod '", name, "': initial guess has ", init.size(),
          " values, expected ", configuration_size());
  require(init.allFinite(), "rod '", name, "': initial guess is not finite");

  RodVariables vars;
  for (int i = 0; i < n; ++i) {
    vars.control_points.push_back(
        problem.add_variable_block(name + ".cp" + std::to_string(i), init.segment(i * cp, cp)));
    if (group >= 0) problem.set_variable_group(vars.control_points.back(), group);
  }
  if (condensed) {
    vars.wrench = problem.add_variable_block(name + ".wrench", init.tail(kWrenchSize));
    if (group >= 0) problem.set_variable_group(vars.wrench, group);
    vars.wrench_offset = problem.variable(vars.wrench).offset;
  }
  vars.length = problem.add_variable_block(name + ".length", VecX::Constant(1, model_.length));
  if (group >= 0) problem.set_variable_group(vars.length, group);
  if (!free_length) problem.fix_variable(vars.length, VecX::Constant(1, model_.length));
  vars.control_point_offset = problem.variable(vars.control_points[0]).offset;
  vars.length_offset = problem.variable(vars.length).offset;

  const double L = model_.length;
  auto constants_at = [&](double u) {
    PointConstants c;
    c.k_se = model_.shear_extension_stiffness;
    c.k_bt = model_.bending_torsion_stiffness;
    c.length_scale = L;
    c.force_scale = force_scale_;
    c.moment_scale = moment_scale_;
    const double s = u * L;
    model_.intrinsic.at(s, c.eps0, c.kappa0);
    if (model_.intrinsic.varying) {
      // s-derivatives of the intrinsic strains by central differences (h = 1e-5 L: error ~1e-10 of the
      // strain variation scale); one-sided at the ends.
      const double h = 1e-5 * L, sa = std::max(0.0, s - h), sb = std::min(L, s + h);
      Vec3 ea, ka, eb, kb;
      model_.intrinsic.at(sa, ea, ka);
      model_.intrinsic.at(sb, eb, kb);
      c.eps0_s = load_factor * (eb - ea) / (sb - sa);
      c.kappa0_s = load_factor * (kb - ka) / (sb - sa);
    }
    c.eps0 *= load_factor;
    c.kappa0 *= load_factor;
    c.f = load_factor * model_.distributed_force();
    c.l = load_factor * model_.loads.moment_per_length;
    return c;
  };
  auto basis_at = [&](double u, int max_derivative, bool end_value_only) {
    PointBasis b;
    if (end_value_only) {  // open knot vector: p(0) = P_0, p(1) = P_{n-1}
      b.first = u == 0.0 ? 0 : n - 1;
      b.count = 1;
      b.B.assign(1, {1.0, 0.0, 0.0, 0.0});
      return b;
    }
    const BasisDerivatives d = basis_derivatives(*knots_, u, max_derivative);
    b.first = d.first;
    b.count = p + 1;
    b.B.assign(p + 1, {0.0, 0.0, 0.0, 0.0});
    for (int k = 0; k <= max_derivative; ++k)
      for (int i = 0; i <= p; ++i) b.B[i][k] = d.values(k, i);
    return b;
  };
  // The basis at u widened to the control points 0 .. last active, with the integrals
  // integral_0^u N_i (kIntegral): what I(u) = integral_0^u p reads (condensed form with loads).
  auto basis_with_integrals = [&](PointBasis b, double u) {
    const VecX J = basis_integrals(*knots_, u);
    const int last = b.first + b.count - 1;
    std::vector<std::array<double, 4>> B(last + 1, {0.0, 0.0, 0.0, 0.0});
    for (int i = 0; i < b.count; ++i) B[b.first + i] = b.B[i];
    for (int i = 0; i <= last; ++i) B[i][kIntegral] = J[i];
    b.B = std::move(B);
    b.first = 0;
    b.count = last + 1;
    return b;
  };
  auto variables_of = [&](const PointBasis& b, std::initializer_list<VariableId> direct) {
    std::vector<VariableId> v(vars.control_points.begin() + b.first,
                              vars.control_points.begin() + b.first + b.count);
    v.insert(v.end(), direct);
    return v;
  };

  // Kernel sparsity patterns: detected at the first point that uses each kernel, shared by the others
  // (point_block.hpp: they do not depend on the point's constants). Detecting per point was about two
  // thirds of a Stewart-Gough assembly.
  std::optional<KernelPattern<24, 13>> mixed_interior_pattern;
  std::optional<KernelPattern<19, 7>> primal_interior_pattern;
  std::optional<KernelPattern<24, 6>> mixed_constitutive_pattern;
  const std::vector<double> tau = knots_->greville();
  const bool midpoints = condensed || (mixed && discretization_.mixed_points == MixedPoints::Midpoints);
  if (condensed && loaded_condensed_) {
    // As below, with the distributed loads: each row also reads I(u), i.e. every control point up to
    // the last active one (the rod's block fills its lower part).
    std::optional<KernelPattern<24, 6>> field_pattern;
    const Vec3 c_point = moment_point();
    for (int j = 0; j + 1 < n; ++j) {
      const double u = 0.5 * (tau[j] + tau[j + 1]);
      const PointConstants c = constants_at(u);
      const PointBasis b = basis_with_integrals(basis_at(u, 1, false), u);
      auto kernel = [c, c_point, u](const auto& z, auto* r) { condensed_loaded_field(z, c, c_point, u, r); };
      if (!field_pattern) field_pattern = detect_kernel_pattern<24, 6>(kernel);
      problem.add_residual_block(
          make_point_block<24, 6>("rod.condensed_field", name + "@u=" + std::to_string(u),
                                  variables_of(b, {vars.wrench, vars.length}), cp, b, kCondensedLoadedPoint,
                                  {{14, kWrenchSize}, {20, 1}}, kernel, *field_pattern));
    }
  } else if (condensed) {
    // 6 constitutive rows at each of the n - 1 midpoints; |q|^2 = 1 below.
    std::optional<KernelPattern<21, 6>> field_pattern;
    const Vec3 c_point = moment_point();
    for (int j = 0; j + 1 < n; ++j) {
      const double u = 0.5 * (tau[j] + tau[j + 1]);
      const PointConstants c = constants_at(u);
      const PointBasis b = basis_at(u, 1, false);
      auto kernel = [c, c_point](const auto& z, auto* r) { condensed_field(z, c, c_point, r); };
      if (!field_pattern) field_pattern = detect_kernel_pattern<21, 6>(kernel);
      problem.add_residual_block(
          make_point_block<21, 6>("rod.condensed_field", name + "@u=" + std::to_string(u),
                                  variables_of(b, {vars.wrench, vars.length}), cp, b, kCondensedPoint,
                                  {{14, kWrenchSize}, {20, 1}}, kernel, *field_pattern));
    }
  } else if (midpoints) {
    // 12 field rows at each of the n - 1 midpoints of consecutive Greville abscissae, |q|^2 = 1 at the
    // n - 2 interior ones: 12 (n - 1) + (n - 2) = 13 n - 14 rows, the same count as the Greville scheme.
    std::optional<KernelPattern<24, 12>> field_pattern;
    for (int j = 0; j + 1 < n; ++j) {
      const double u = 0.5 * (tau[j] + tau[j + 1]);
      const PointConstants c = constants_at(u);
      const PointBasis b = basis_at(u, 1, false);
      auto kernel = [c](const auto& z, auto* r) { mixed_field(z, c, r); };
      if (!field_pattern) field_pattern = detect_kernel_pattern<24, 12>(kernel);
      problem.add_residual_block(make_point_block<24, 12>("rod.mixed_field", name + "@u=" + std::to_string(u),
                                                          variables_of(b, {vars.length}), cp, b, kMixedPoint,
                                                          {{23, 1}}, kernel, *field_pattern));
    }
  }
  if (midpoints) {
    for (int j = 1; j + 1 < n; ++j) {
      const PointBasis b = basis_at(tau[j], 0, false);
      problem.add_residual_block(make_point_block<4, 1>(
          "rod.unit_quaternion", name + "@u=" + std::to_string(tau[j]), variables_of(b, {}), cp, b,
          {{0, kQ, 4, 0}}, {}, [](const auto& z, auto* r) { r[0] = z.squaredNorm() - 1.0; }));
    }
  }
  for (int j = 0; j < n; ++j) {
    const bool is_end = j == 0 || j == n - 1;
    if (midpoints && !is_end) continue;  // the interior rows are above
    const double u = tau[j];
    const PointConstants c = constants_at(u);
    const std::string where = name + "@u=" + std::to_string(u);
    if (!is_end) {
      if (mixed) {
        const PointBasis b = basis_at(u, 1, false);
        auto kernel = [c](const auto& z, auto* r) { mixed_interior(z, c, r); };
        if (!mixed_interior_pattern) mixed_interior_pattern = detect_kernel_pattern<24, 13>(kernel);
        problem.add_residual_block(
            make_point_block<24, 13>("rod.mixed_equilibrium", where, variables_of(b, {vars.length}), cp, b,
                                     kMixedPoint, {{23, 1}}, kernel, *mixed_interior_pattern));
      } else {
        const PointBasis b = basis_at(u, 2, false);
        auto kernel = [c](const auto& z, auto* r) { primal_interior(z, c, r); };
        if (!primal_interior_pattern) primal_interior_pattern = detect_kernel_pattern<19, 7>(kernel);
        problem.add_residual_block(
            make_point_block<19, 7>("rod.primal_equilibrium", where, variables_of(b, {vars.length}), cp, b,
                                    kPrimalInterior, {{18, 1}}, kernel, *primal_interior_pattern));
      }
      continue;
    }
    const bool at_base = j == 0;
    if (mixed && !midpoints) {
      const PointBasis b = basis_at(u, 1, false);
      auto kernel = [c](const auto& z, auto* r) { mixed_constitutive(z, c, r); };
      if (!mixed_constitutive_pattern) mixed_constitutive_pattern = detect_kernel_pattern<24, 6>(kernel);
      problem.add_residual_block(make_point_block<24, 6>("rod.mixed_constitutive", where,
                                                         variables_of(b, {vars.length}), cp, b, kMixedPoint,
                                                         {{23, 1}}, kernel, *mixed_constitutive_pattern));
    }
    if (!(at_base ? ends.base : ends.tip)) continue;
    const EndData e = end_data(at_base ? model_.base : model_.tip, at_base, load_factor);
    const std::string kind = std::string("rod.end_") + to_string(e.kind);
    if (condensed && loaded_condensed_) {
      // z = [p (3), q (4), n (3), h (3), L (1), I (3)]; n, m at the end as in condensed_loaded_field.
      const PointBasis b = at_base ? basis_at(u, 0, true) : basis_with_integrals(basis_at(u, 0, true), u);
      const Vec3 c_point = moment_point();
      problem.add_residual_block(make_point_block<17, 7>(
          kind, where, variables_of(b, {vars.wrench, vars.length}), cp, b, kCondensedLoadedEnd,
          {{7, kWrenchSize}, {13, 1}}, [c, e, c_point, u](const auto& z, auto* r) {
            using T = typename std::decay_t<decltype(z)>::Scalar;
            const V3<T> p = z.template segment<3>(0);
            const T L = z[13];
            const V3<T> n = z.template segment<3>(7) - c.f.cast<T>() * (u * L);
            const V3<T> m = condensed_moment<T>(p, n, z.template segment<3>(10), L, z.template segment<3>(14),
                                                c, c_point, u);
            end_conditions<T>(e.kind, cast_target<T>(e.target), e.loads, c, p, z.template segment<4>(3), n, m,
                              r);
          }));
    } else if (condensed) {
      // z = [p (3), q (4), n (3), h (3)]; m = h - (p - c) x n at the end.
      const PointBasis b = basis_at(u, 0, true);
      const Vec3 c_point = moment_point();
      problem.add_residual_block(make_point_block<13, 7>(
          kind, where, variables_of(b, {vars.wrench}), cp, b, kCondensedEnd, {{7, kWrenchSize}},
          [c, e, c_point](const auto& z, auto* r) {
            using T = typename std::decay_t<decltype(z)>::Scalar;
            const V3<T> p = z.template segment<3>(0), n = z.template segment<3>(7);
            const V3<T> m = z.template segment<3>(10) - (p - c_point.cast<T>()).cross(n);
            end_conditions<T>(e.kind, cast_target<T>(e.target), e.loads, c, p, z.template segment<4>(3), n, m,
                              r);
          }));
    } else if (mixed) {
      const PointBasis b = basis_at(u, 0, true);
      problem.add_residual_block(make_point_block<13, 7>(
          kind, where, variables_of(b, {}), cp, b, kMixedEnd, {}, [c, e](const auto& z, auto* r) {
            using T = typename std::decay_t<decltype(z)>::Scalar;
            end_conditions<T>(e.kind, cast_target<T>(e.target), e.loads, c, z.template segment<3>(0),
                              z.template segment<4>(3), z.template segment<3>(7), z.template segment<3>(10),
                              r);
          }));
    } else {
      const PointBasis b = basis_at(u, 1, false);
      problem.add_residual_block(make_point_block<15, 7>(
          kind, where, variables_of(b, {vars.length}), cp, b, kPrimalEnd, {{14, 1}},
          [c, e](const auto& z, auto* r) {
            using T = typename std::decay_t<decltype(z)>::Scalar;
            Eigen::Matrix<T, 12, 1> w;
            w << z.template segment<4>(3), z.template segment<4>(7), z.template segment<3>(11), z[14];
            V3<T> nn, mm;
            primal_wrench(w, c, nn, mm);
            end_conditions<T>(e.kind, cast_target<T>(e.target), e.loads, c, z.template segment<3>(0),
                              z.template segment<4>(3), nn, mm, r);
          }));
    }
  }
  return vars;
}

double CollocationRod::length(const VecX& x, const RodVariables& vars) const {
  return x[vars.length_offset];
}

RodState CollocationRod::state_at(const VecX& x, const RodVariables& vars, double s) const {
  const double L = length(x, vars);
  const double u = checked_arc_length(s, L, model_.name) / L;
  BasisDerivatives d = basis_derivatives(*knots_, u, 1);
  if (loaded_condensed_) d.integrals = basis_integrals(*knots_, u);
  return state_with_basis(x, vars, s, d);
}

RodState CollocationRod::state_with_basis(const VecX& x, const RodVariables& vars, double s,
                                          const BasisDerivatives& d) const {
  const double L = length(x, vars);
  const int cp = control_point_size();
  using ControlPoint = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 13, 1>;  // 7 or 13 values, no heap
  ControlPoint value = ControlPoint::Zero(cp), du = ControlPoint::Zero(cp);
  for (int i = 0; i <= discretization_.degree; ++i) {
    const auto c = x.segment(vars.control_point_offset + (d.first + i) * cp, cp);
    value += d.values(0, i) * c;
    du += d.values(1, i) * c;
  }
  RodState st;
  st.s = s;
  st.position = value.segment<3>(kP);
  st.quaternion = value.segment<4>(kQ);
  st.rotation = rotation_matrix(st.quaternion);
  const Quat q_s = du.segment<4>(kQ) / L;
  const Vec3 p_s = du.segment<3>(kP) / L;
  st.curvature_body = body_curvature<double>(st.quaternion, q_s);
  st.shear_extension_body = st.rotation.transpose() * p_s - Vec3::UnitZ();
  if (discretization_.formulation == RodFormulation::Mixed) {
    st.force = value.segment<3>(kN);
    st.moment = value.segment<3>(kM);
  } else if (discretization_.formulation == RodFormulation::Condensed) {
    // condensed_loaded_field at u = s / L with the model's loads (zero for a load-free rod, where the
    // integral I of p is not needed).
    Vec3 I = Vec3::Zero();
    if (loaded_condensed_) {
      require(d.integrals.size() == num_control_points(), "rod '", model_.name,
              "': sample basis without the basis integrals the condensed form with loads needs");
      for (int j = 0; j < num_control_points(); ++j)
        if (d.integrals[j] != 0.0)
          I += d.integrals[j] * x.segment<3>(vars.control_point_offset + j * cp + kP);
    }
    PointConstants loads;
    loads.f = model_.distributed_force();
    loads.l = model_.loads.moment_per_length;
    const double u = s / L;
    st.force = x.segment<3>(vars.wrench_offset) - loads.f * (u * L);
    st.moment = condensed_moment<double>(st.position, st.force, x.segment<3>(vars.wrench_offset + 3), L, I,
                                         loads, moment_point(), u);
  } else {
    Vec3 eps0, kappa0;
    model_.intrinsic.at(s, eps0, kappa0);
    st.force = st.rotation * model_.shear_extension_stiffness.cwiseProduct(st.shear_extension_body - eps0);
    st.moment = st.rotation * model_.bending_torsion_stiffness.cwiseProduct(st.curvature_body - kappa0);
  }
  return st;
}

std::vector<RodState> CollocationRod::sample(const VecX& x, const RodVariables& vars, int num_points) const {
  return sample(x, vars, sample_basis(num_points));
}

std::vector<BasisDerivatives> CollocationRod::sample_basis(int num_points) const {
  require(num_points >= 2, "sample: need at least 2 points, got ", num_points);
  std::vector<BasisDerivatives> basis;
  basis.reserve(num_points);
  for (int i = 0; i < num_points; ++i) {
    const double u = static_cast<double>(i) / (num_points - 1);
    basis.push_back(basis_derivatives(*knots_, u, 1));
    if (loaded_condensed_) basis.back().integrals = basis_integrals(*knots_, u);
  }
  return basis;
}

std::vector<RodState> CollocationRod::sample(const VecX& x, const RodVariables& vars,
                                             const std::vector<BasisDerivatives>& basis) const {
  const int num_points = static_cast<int>(basis.size());
  require(num_points >= 2, "sample: need at least 2 points, got ", num_points);
  const double L = length(x, vars);
  require(std::isfinite(L) && L > 0.0, "rod '", model_.name, "': length ", L, " is not positive");
  std::vector<RodState> out;
  out.reserve(num_points);
  for (int i = 0; i < num_points; ++i)
    out.push_back(state_with_basis(x, vars, L * i / (num_points - 1), basis[i]));
  return out;
}

void CollocationRod::sample_centerline(const VecX& x, const RodVariables& vars,
                                       const std::vector<BasisDerivatives>& basis,
                                       std::vector<Vec3>& positions,
                                       std::vector<double>& axial_stretches) const {
  const double L = length(x, vars);
  require(std::isfinite(L) && L > 0.0, "rod '", model_.name, "': length ", L, " is not positive");
  const int cp = control_point_size();
  positions.resize(basis.size());
  axial_stretches.resize(basis.size());
  for (size_t k = 0; k < basis.size(); ++k) {
    const BasisDerivatives& d = basis[k];
    // p, q and dp/du from the p + 1 active control points ([p (3), q (4), ...] in every formulation)
    Vec3 p = Vec3::Zero(), p_u = Vec3::Zero();
    Quat q = Quat::Zero();
    for (int i = 0; i <= discretization_.degree; ++i) {
      const double* c = x.data() + vars.control_point_offset + (d.first + i) * cp;
      p += d.values(0, i) * Eigen::Map<const Vec3>(c + kP);
      p_u += d.values(1, i) * Eigen::Map<const Vec3>(c + kP);
      q += d.values(0, i) * Eigen::Map<const Quat>(c + kQ);
    }
    positions[k] = p;
    // v3 = 1 + (R^T p_s - e3)_3 = d3 . p_s (state_with_basis and axial_stretch)
    axial_stretches[k] = rotation_matrix(q).col(2).dot(p_u / L);
  }
}

}  // namespace pcr
