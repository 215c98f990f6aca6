// The rows of a sharp obstacle (edge or point) touching a rod at one section u_c (rod_contact.hpp).
// Unknowns [u_c, lambda, G]: the contact section, the force magnitude and the force vector, both per
// unit of u (lambda = |F| / L, G = F / L with the rod length L, so that no row needs L). With p, p' and
// p'' the centerline and its u-derivatives at u_c (beyond [0, 1] the centerline is extended along its end
// tangent: p(u) = p(ub) + p'(ub) (u - ub), ub = clamp(u, 0, 1)), v = p - c(p) the offset from the
// obstacle's nearest point (obstacle_offset), nu = v / |v| and g = |v| - r:
//   rows 0..2:  (G - lambda nu) L0 / F0                              (the force is normal, through p)
//   row 3:      u_c - clamp(u_c - v . p' / |p'|^2, 0, 1)             (u_c is the section nearest to the
//               obstacle: v . p' = 0 inside the rod, or an end of the rod; a projected step, semismooth)
//   row 4:      phi(g / L0, lambda L0 / F0)                          (complementarity)
// Jacobians by hand: with q = |p'|^2 and s = v . p' / q,
//   ds/dp = J_v^T p' / q,  ds/dp' = v / q - 2 (v . p') p' / q^2,  dp/du = p', dp'/du = p'' (0 beyond).
#include <algorithm>

#include "edge_contact.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr::contact {

HatWeight midpoint_share(const std::vector<double>& midpoints, int j, double u) {
  const int M = static_cast<int>(midpoints.size());
  int m = static_cast<int>(std::upper_bound(midpoints.begin(), midpoints.end(), u) - midpoints.begin()) - 1;
  m = std::clamp(m, 0, M - 2);
  const double width = midpoints[m + 1] - midpoints[m], t = (u - midpoints[m]) / width;
  if (j == m) return {1.0 - t, -1.0 / width};
  if (j == m + 1) return {t, 1.0 / width};
  return {};
}

NearestSectionStep nearest_section_step(const ObstacleOffset& v, const Vec3& p1) {
  const double q = p1.squaredNorm();
  NearestSectionStep s;
  s.value = v.offset.dot(p1) / q;
  s.d_p = v.jacobian.transpose() * p1 / q;
  s.d_p1 = v.offset / q - 2.0 * s.value * p1 / q;
  return s;
}

namespace {

class SharpContactBlock final : public ResidualBlock {
 public:
  SharpContactBlock(std::string name, std::vector<VariableId> variables, const KnotVector& knots,
                    int point_size, int p_offset, const Obstacle& obstacle, double radius,
                    ComplementarityFunction function, double length_scale, double force_scale)
      : ResidualBlock("rod.sharp_contact", std::move(name), 5, std::move(variables)),
        knots_(knots),
        point_size_(point_size),
        p_offset_(p_offset),
        obstacle_(obstacle),
        radius_(radius),
        function_(function),
        length_scale_(length_scale),
        density_scale_(length_scale / force_scale) {}

  int num_points() const { return static_cast<int>(variables().size()) - 1; }

  int expected_variable_size(int k) const override { return k < num_points() ? point_size_ : 5; }

  bool structural_nonzero(int k, int row, int column) const override {
    if (k < num_points()) return column >= p_offset_ && column < p_offset_ + 3;
    if (row < 3) return column == 0 || column == 1 || column == 2 + row;
    return row == 3 ? column == 0 : column <= 1;
  }

  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override {
    const double* e = values[num_points()];
    const double u = e[0], lambda = e[1];
    const Eigen::Map<const Vec3> G(e + 2);
    const ContactSection cs = contact_section(knots_, values, p_offset_, u);
    const BasisDerivatives& b = cs.basis;
    const int active = cs.active;
    const VecX &a = cs.a, &b1 = cs.b1;  // dp/dP_i and dp'/dP_i
    const Vec3 &p = cs.p, &p1 = cs.p1, &p2 = cs.p2;
    const ObstacleGap g = obstacle_gap(obstacle_, p, radius_);
    const ObstacleOffset v = obstacle_offset(obstacle_, p);
    const NearestSectionStep step = nearest_section_step(v, p1);
    const double z = u - step.value;
    const bool clamped = z <= 0.0 || z >= 1.0;
    double phi_a = 0.0, phi_b = 0.0;
    for (int r = 0; r < 3; ++r) residual[r] = (G[r] - lambda * g.normal[r]) * density_scale_;
    residual[3] = z <= 0.0 ? u : z >= 1.0 ? u - 1.0 : step.value;
    complementarity(function_, g.gap / length_scale_, lambda * density_scale_, residual[4], phi_a, phi_b);
    if (jacobians == nullptr) return;
    const Vec3 &ds_dp = step.d_p, &ds_dp1 = step.d_p1;
    for (int k = 0; k < num_points(); ++k)
      if (jacobians[k] != nullptr) std::fill(jacobians[k], jacobians[k] + 5 * point_size_, 0.0);
    for (int i = 0; i < active; ++i) {
      double* J = jacobians[b.first + i];
      if (J == nullptr) continue;
      for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r)
          J[r * point_size_ + p_offset_ + c] = -lambda * g.normal_derivative(r, c) * a[i] * density_scale_;
        if (!clamped) J[3 * point_size_ + p_offset_ + c] = ds_dp[c] * a[i] + ds_dp1[c] * b1[i];
        J[4 * point_size_ + p_offset_ + c] = phi_a * g.normal[c] * a[i] / length_scale_;
      }
    }
    if (double* J = jacobians[num_points()]) {
      std::fill(J, J + 25, 0.0);
      const Vec3 dnu_du = g.normal_derivative * p1;
      for (int r = 0; r < 3; ++r) {
        J[r * 5 + 0] = -lambda * dnu_du[r] * density_scale_;
        J[r * 5 + 1] = -g.normal[r] * density_scale_;
        J[r * 5 + 2 + r] = density_scale_;
      }
      J[15] = clamped ? 1.0 : ds_dp.dot(p1) + ds_dp1.dot(p2);
      J[20] = phi_a * g.normal.dot(p1) / length_scale_;
      J[21] = phi_b * density_scale_;
    }
  }

 private:
  KnotVector knots_;
  int point_size_, p_offset_;
  Obstacle obstacle_;
  double radius_;
  ComplementarityFunction function_;
  double length_scale_, density_scale_;
};

}  // namespace

std::shared_ptr<ResidualBlock> make_sharp_contact_block(std::string name, std::vector<VariableId> variables,
                                                        const KnotVector& knots, int point_size, int p_offset,
                                                        const Obstacle& obstacle, double radius,
                                                        ComplementarityFunction function, double length_scale,
                                                        double force_scale) {
  return std::make_shared<SharpContactBlock>(std::move(name), std::move(variables), knots, point_size,
                                             p_offset, obstacle, radius, function, length_scale, force_scale);
}

ContactSection contact_section(const KnotVector& knots, const double* const* values, int p_offset, double u) {
  ContactSection s;
  const double ub = std::clamp(u, 0.0, 1.0);
  s.inside = u == ub;
  s.basis = basis_derivatives(knots, ub, 2);
  const BasisDerivatives& b = s.basis;
  s.active = static_cast<int>(b.values.cols());
  s.a.resize(s.active);
  s.b1.resize(s.active);
  for (int i = 0; i < s.active; ++i) {
    const Eigen::Map<const Vec3> P(values[b.first + i] + p_offset);
    s.a[i] = b.values(0, i) + b.values(1, i) * (u - ub);
    s.b1[i] = b.values(1, i);
    s.p += s.a[i] * P;
    s.p1 += s.b1[i] * P;
    if (s.inside) s.p2 += b.values(2, i) * P;
  }
  return s;
}

}  // namespace pcr::contact
