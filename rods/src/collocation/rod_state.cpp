// Post-processing of a collocation rod: states (p, R, n, m, strains) at arc lengths from a solution.
#include <algorithm>
#include <cmath>
#include <limits>

#include "form_builder.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/rods/collocation_rod.hpp"
#include "pcr/rods/drawn_rod.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr {
using namespace collocation;

RodState CollocationRod::state_at(const VecX& x, const RodVariables& vars, double s) const {
  const double L = length(x, vars);
  const double u = checked_arc_length(s, L, model_.name) / L;
  BasisDerivatives d = basis_derivatives(*knots_, u, 1);
  if (loaded_condensed_) d.integrals = integrals_at(u);
  return state_with_basis(x, vars, s, d);
}

VecX CollocationRod::integrals_at(double u) const {
  // basis_integrals(knots, u) without integrating every span below u: the functions before the active
  // ones have their whole support below u (w_j), those after it none.
  const int p = discretization_.degree;
  int first = 0;
  VecX active(p + 1);
  active_basis_integrals(*knots_, u, first, active);
  VecX J = VecX::Zero(num_control_points());
  J.head(first) = integral_weights_.head(first);
  J.segment(first, p + 1) = active;
  return J;
}

RodState CollocationRod::state_with_basis(const VecX& x, const RodVariables& vars, double s,
                                          const BasisDerivatives& d) const {
  const double L = length(x, vars);
  const int cp = control_point_size();
  PointValues value = PointValues::Zero(cp), du = PointValues::Zero(cp);
  for (int i = 0; i <= discretization_.degree; ++i) {
    const auto c = x.segment(vars.control_point_offset + (d.first + i) * cp, cp);
    value += d.values(0, i) * c;
    du += d.values(1, i) * c;
  }
  RodState st;
  st.s = s;
  const PointLayout& layout = point_layout();
  st.position = value.segment<3>(layout.p);
  st.quaternion = value.segment<4>(layout.q);
  st.rotation = rotation_matrix(st.quaternion);
  const Quat q_s = du.segment<4>(layout.q) / L;
  const Vec3 p_s = du.segment<3>(layout.p) / L;
  st.curvature_body = body_curvature<double>(st.quaternion, q_s);
  st.shear_extension_body = st.rotation.transpose() * p_s - Vec3::UnitZ();
  form_->internal_wrench(*this, x, vars, d, value, st);
  if (model_.drawing_speed != 0.0) {
    // Drawn rods: the unknowns are the effective N, M (drawn_rod.hpp); report the section's n, m.
    Vec3 eps0, kappa0, n, m;
    model_.intrinsic.at(s, eps0, kappa0);
    section_wrench(drawn_constants(model_, eps0, kappa0), st.rotation, st.force, st.moment, n, m);
    st.force = n;
    st.moment = m;
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
    if (loaded_condensed_) basis.back().integrals = integrals_at(u);
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

namespace {

/// v3 = d3 . p_s with d3 = R(q) e3 = A(q) e3 / |q|^2 (the third column of rotation_matrix, the same
/// operations) and p_s = p_u / L.
double axial_stretch(const Quat& q, const Vec3& p_u, double L) {
  const double S = q.squaredNorm();
  require(S > 0.0 && std::isfinite(S),
          "rotation_matrix: quaternion must be finite and non-zero, got |q|^2 = ", S);
  const double w = q[0], qx = q[1], qy = q[2], qz = q[3];
  const Vec3 d3 =
      Vec3(2 * (qx * qz + w * qy), 2 * (qy * qz - w * qx), w * w - qx * qx - qy * qy + qz * qz) / S;
  return d3.dot(p_u / L);
}

}  // namespace

void CollocationRod::sample_centerline(const VecX& x, const RodVariables& vars,
                                       const std::vector<BasisDerivatives>& basis,
                                       std::vector<Vec3>& positions,
                                       std::vector<double>& axial_stretches) const {
  const double L = length(x, vars);
  require(std::isfinite(L) && L > 0.0, "rod '", model_.name, "': length ", L, " is not positive");
  const int cp = control_point_size(), kP = point_layout().p, kQ = point_layout().q;
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
    axial_stretches[k] = axial_stretch(q, p_u, L);
  }
}

double CollocationRod::min_axial_stretch(const VecX& x, const RodVariables& vars,
                                         const std::vector<BasisDerivatives>& basis) const {
  const double L = length(x, vars);
  require(std::isfinite(L) && L > 0.0, "rod '", model_.name, "': length ", L, " is not positive");
  require(!basis.empty() && basis.front().values.rows() >= 2,
          "min_axial_stretch: no sample points with "
          "first derivatives");
  const int cp = control_point_size(), kP = point_layout().p, kQ = point_layout().q;
  double least = std::numeric_limits<double>::infinity();
  for (const BasisDerivatives& d : basis) {
    // q and dp/du in scalars (the sums of sample_centerline in the same order): B(0, i), B(1, i) are
    // b[2 i], b[2 i + 1] of the column-major 2 x (p + 1) values.
    const double* b = d.values.data();
    const double* c = x.data() + vars.control_point_offset + d.first * cp;
    double q0 = 0.0, q1 = 0.0, q2 = 0.0, q3 = 0.0, u0 = 0.0, u1 = 0.0, u2 = 0.0;
    for (int i = 0; i <= discretization_.degree; ++i, c += cp) {
      const double b0 = b[2 * i], b1 = b[2 * i + 1];
      u0 += b1 * c[kP], u1 += b1 * c[kP + 1], u2 += b1 * c[kP + 2];
      q0 += b0 * c[kQ], q1 += b0 * c[kQ + 1], q2 += b0 * c[kQ + 2], q3 += b0 * c[kQ + 3];
    }
    least = std::min(least, axial_stretch(Quat(q0, q1, q2, q3), Vec3(u0, u1, u2), L));
  }
  return least;
}

}  // namespace pcr
