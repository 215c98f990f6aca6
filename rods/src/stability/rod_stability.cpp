// Stability verdict of single rods (rod_stability.hpp): collocation and shooting solutions.
#include "pcr/rods/stability/rod_stability.hpp"

#include <algorithm>
#include <sstream>

#include "pcr/math/quaternion.hpp"
#include "pcr/rods/drawn_rod.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr {

namespace {

/// The Jacobi state at s from the rotation and the section force and moment there: p' = R (K_SE^-1 R^T n +
/// e3 + eps0), u = K_BT^-1 R^T m + kappa0 (rod_ode.hpp). A drawn rod's steady problem is the static problem
/// of the effective rod (drawn_rod.hpp: N, M and the constants of (M4)), whose energy the verdict tests.
JacobiState jacobi_state(const RodModel& model, double s, const Mat3& R, const Vec3& n, const Vec3& m) {
  Vec3 eps0, kappa0;
  model.intrinsic.at(s, eps0, kappa0);
  const DrawnConstants d = drawn_constants(model, eps0, kappa0);
  JacobiState y;
  y.rotation = R;
  y.force = n;
  y.moment = m;
  if (d.drawn()) effective_wrench(d, R, n, m, y.force, y.moment);
  y.tangent = R * (d.k_se.cwiseInverse().cwiseProduct(R.transpose() * y.force) + Vec3::UnitZ() + d.eps0);
  y.curvature = (d.k_bt.cwiseInverse().cwiseProduct(R.transpose() * y.moment) + d.kappa0).norm();
  return y;
}

/// Stable / unstable / critical / unknown of one rod from its model and its Jacobi states.
Stability verdict(const RodModel& model, double length, const JacobiStateAt& states, int min_segments) {
  const std::string not_conservative = nonconservative_loads(model);
  if (!not_conservative.empty()) return unknown_stability(not_conservative);
  RodModel held_model = model;
  held_model.length = length;
  const HeldRod rod = held_rod(held_model, states(0.0).rotation, states(length).rotation);
  const std::string joint_state = drawn_joint_state_problem(model, rod, states);
  if (!joint_state.empty()) return unknown_stability("rod '" + model.name + "': " + joint_state);
  HeldRodOptions options;
  options.min_segments = std::max(options.min_segments, min_segments);
  return held_rod_stability(held_rod_index(rod, states, options));
}

}  // namespace

std::string nonconservative_loads(const RodModel& model) {
  std::ostringstream msg;
  if (!model.loads.moment_per_length.isZero(0.0))
    msg << "rod '" << model.name << "': distributed couple (moment_per_length) has no potential";
  const RodEnd* ends[2] = {&model.base, &model.tip};
  const char* names[2] = {"base", "tip"};
  for (int k = 0; k < 2; ++k) {
    const RodEndKind kind = ends[k]->kind;
    const bool turns_freely =
        kind == RodEndKind::Free || kind == RodEndKind::Spherical || kind == RodEndKind::Universal;
    if (turns_freely && !ends[k]->moment.isZero(0.0))
      msg << (msg.tellp() > 0 ? "; " : "") << "rod '" << model.name << "': dead couple at the " << names[k]
          << " (" << to_string(kind) << " end) has no potential";
  }
  const std::string drawn = drawn_end_problem(model);
  if (!drawn.empty()) msg << (msg.tellp() > 0 ? "; " : "") << drawn;
  return msg.str();
}

HeldEnd held_end(RodEndKind kind, const Mat3& end_frame, const Vec3& axis, const Mat3& rod_rotation) {
  HeldEnd e;
  e.kind = kind;
  e.axis = end_frame * axis.normalized();
  if (kind == RodEndKind::Universal) {
    // The second axis is fixed in the rod: b = e3 x a / |e3 x a| in the rod's body frame (rod_model.hpp).
    const Vec3 b = Vec3::UnitZ().cross(axis);
    e.second_axis = rod_rotation * (b.norm() > 0.0 ? Vec3(b.normalized()) : Vec3::UnitY());
  }
  return e;
}

HeldRod held_rod(const RodModel& model, const Mat3& base_rotation, const Mat3& tip_rotation) {
  HeldRod rod;
  rod.length = model.length;
  // Drawn rods: the effective stiffnesses (M4); the model's own otherwise.
  const DrawnConstants d = drawn_constants(model, model.intrinsic.shear_extension, model.intrinsic.curvature);
  rod.shear_extension_stiffness = d.k_se;
  rod.bending_torsion_stiffness = d.k_bt;
  rod.base =
      held_end(model.base.kind, rotation_matrix(model.base.orientation), model.base.axis, base_rotation);
  rod.tip = held_end(model.tip.kind, rotation_matrix(model.tip.orientation), model.tip.axis, tip_rotation);
  return rod;
}

namespace {

/// J_j(u) = integral_0^u N_j for every basis function j of the rod's knots t (degree p, n functions), in
/// closed form: with the degree p + 1 B-splines M_i on the knots T = (0, t, 1) (one more knot at each end),
/// integral_0^u N_j = (t_{j+p+1} - t_j) / (p + 1) sum_{i > j} M_i(u) (de Boor, "A Practical Guide to
/// Splines" (1978), chapter X: the derivative of a B-spline telescopes in the sum). One evaluation of the
/// p + 2 functions M active at u (Cox-de Boor, The NURBS Book A2.2) instead of the Gauss quadrature of
/// CollocationRod::state_at on every span below u: the same values to round-off, at about a tenth of the
/// cost of the verdict's thousands of states per rod.
VecX basis_integrals_at(const KnotVector& knots, const VecX& full_weights, double u) {
  const std::vector<double>& t = knots.knots();
  const int p = knots.degree(), q = p + 1, n = knots.num_basis();
  const int span = knots.find_span(u), first = span - p;  // N_first .. N_span active at u
  auto T = [&t](int k) { return t[k - 1]; };              // k >= 1 here: T_k = t_{k-1}
  const int s = span + 1;                                 // the span of u in T
  std::vector<double> M(q + 1), left(q + 1), right(q + 1);
  M[0] = 1.0;
  for (int j = 1; j <= q; ++j) {
    left[j] = u - T(s + 1 - j);
    right[j] = T(s + j) - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = M[r] / (right[r + 1] + left[j - r]);
      M[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    M[j] = saved;
  }
  // M[r] = M_{s - q + r} = M_{first + r}, r = 0 .. p + 1.
  VecX J = VecX::Zero(n);
  J.head(first) = full_weights.head(first);
  double above = 0.0;  // sum_{i > j} M_i(u), from the top
  for (int r = q; r >= 1; --r) {
    above += M[r];
    const int j = first + r - 1;
    if (j < n) J[j] = (t[j + p + 1] - t[j]) / q * above;
  }
  return J;
}

}  // namespace

JacobiStateAt jacobi_states(const CollocationRod& rod, const VecX& x, const RodVariables& vars) {
  return [&rod, &x, &vars](double s) {
    const double L = rod.length(x, vars);
    const double at = std::clamp(s / L, 0.0, 1.0);
    BasisDerivatives basis = basis_derivatives(rod.knots(), at, 1);
    if (rod.condensed_with_loads())
      basis.integrals = basis_integrals_at(rod.knots(), rod.integral_weights(), at);
    const RodState st = rod.state_with_basis(x, vars, s, basis);
    JacobiState y = jacobi_state(rod.model(), s, st.rotation, st.force, st.moment);
    // The state's strains against the constitutive law's (jacobi_state: v = R^T p', u from m).
    const Vec3 v = st.rotation.transpose() * y.tangent;
    Vec3 eps0, kappa0;
    rod.model().intrinsic.at(s, eps0, kappa0);
    const DrawnConstants d = drawn_constants(rod.model(), eps0, kappa0);
    const Vec3 u = d.k_bt.cwiseInverse().cwiseProduct(st.rotation.transpose() * y.moment) + d.kappa0;
    y.strain_mismatch = std::max((v - Vec3::UnitZ() - st.shear_extension_body).norm(),
                                 (u - st.curvature_body).norm() * rod.length(x, vars));
    return y;
  };
}

Stability held_rod_stability(const HeldRodIndex& index) {
  if (!index.ok) return unknown_stability(index.failure);
  Stability out;
  out.unstable_modes = index.unstable_modes;
  out.neutral_modes = index.neutral_modes;
  out.margin = index.margin;
  out.length_scale = index.length_scale;
  out.energy_scale = index.energy_scale;
  out.asymmetry = index.asymmetry;
  // A conservative model's segment stiffnesses are symmetric but for the integration error; more than
  // 1e-4 means the state is not an accurate equilibrium (or the model breaks an assumption).
  constexpr double kMaxAsymmetry = 1e-4;
  if (index.asymmetry > kMaxAsymmetry) {
    std::ostringstream msg;
    msg << "stiffness not symmetric: relative asymmetry " << index.asymmetry << " > " << kMaxAsymmetry;
    return unknown_stability(msg.str());
  }
  out.verdict = verdict_of(out.unstable_modes, out.neutral_modes);
  if (out.verdict == StabilityVerdict::Critical)
    out.reason =
        "zero eigenvalue of the rod's stiffness: a fold or bifurcation point, or a continuous symmetry of "
        "the "
        "model (e.g. a round rod's buckled shape turned about the load line)";
  return out;
}

Stability rod_stability(const CollocationRod& rod, const VecX& x, const RodVariables& vars) {
  return verdict(rod.model(), rod.length(x, vars), jacobi_states(rod, x, vars),
                 rod.discretization().elements);
}

Stability rod_stability(const RodModel& model, const ShootingSolution& solution) {
  if (!solution.summary.converged()) return {};
  if (solution.states.empty()) return unknown_stability("shooting solution without its trajectory");
  const JacobiStateAt states = [&model, &solution](double s) {
    const ShootingState st = solution.at(s);
    return jacobi_state(model, s, st.R(), st.n, st.m);
  };
  return verdict(model, model.length, states, 1);
}

const char* to_string(StabilityVerdict verdict) {
  switch (verdict) {
    case StabilityVerdict::Stable: return "stable";
    case StabilityVerdict::Unstable: return "unstable";
    case StabilityVerdict::Critical: return "critical";
    case StabilityVerdict::Unknown: return "unknown";
    case StabilityVerdict::NotChecked: break;
  }
  return "not_checked";
}

StabilityVerdict verdict_of(int unstable_modes, int neutral_modes) {
  if (unstable_modes > 0) return StabilityVerdict::Unstable;
  if (neutral_modes > 0) return StabilityVerdict::Critical;
  return StabilityVerdict::Stable;
}

bool is_counted(const Stability& s) {
  return s.verdict == StabilityVerdict::Stable || s.verdict == StabilityVerdict::Unstable ||
         s.verdict == StabilityVerdict::Critical;
}

Stability unknown_stability(std::string reason) {
  Stability s;
  s.verdict = StabilityVerdict::Unknown;
  s.reason = std::move(reason);
  return s;
}

std::string unstable_modes_text(int n) {
  return std::to_string(n) + (n == 1 ? " unstable mode" : " unstable modes");
}

}  // namespace pcr
