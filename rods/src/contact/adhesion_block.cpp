// The rows of a roller with the adhesion law (no slip) touching a rod at the prescribed material section
// sigma_c = Obstacle::adhesive_section() (rod_contact.hpp, docs/contact.md "Rollers").
// Unknowns [u_c, lambda, G] as a sharp obstacle (edge_contact_block.cpp: the contact section, the normal
// force magnitude and the force vector per unit of u), the tangential force mu per unit of u (signed,
// along the rod's unit tangent t = p' / |p'| at u_c) and the rod's length L (read only). With p, p', p''
// at u_c (extended along the end tangent beyond [0, 1]), the roller's gap g and normal nu (obstacle_gap)
// and the offset v = (I - a a^T)(p - x0) of the centerline from the roller's axis:
//   rows 0..2:  (G - lambda nu - mu t) L0 / F0        (normal force plus tangential force, through p)
//   row 3:      (u_c L - sigma_c) / L0                 (no slip: the stuck section is at the contact)
//   row 4:      phi(g / L0, lambda L0 / F0)            (complementarity of the normal force)
//   row 5:      closed: v . p' / |p'|^2                (the stuck section is where the rod touches:
//                                                       the tangency row of an edge; mu its multiplier)
//               open:   mu L0 / F0                     (no tangential force without contact)
// closed / open is the active set of the complementarity, as the min function reads it: closed when
// g / L0 <= lambda L0 / F0 (row 4 then enforces g = 0), open otherwise (it enforces lambda = 0). The
// switch is a semismooth selection like min itself; at g = lambda = 0 the contact counts as closed.
// Jacobians by hand: with q = |p'|^2 and s = v . p' / q,
//   ds/dp = J_v^T p' / q,  ds/dp' = v / q - 2 (v . p') p' / q^2,  dt/dp' = (I - t t^T) / |p'|.
#include <algorithm>
#include <cmath>

#include "edge_contact.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr::contact {
namespace {

class AdhesiveContactBlock final : public ResidualBlock {
 public:
  AdhesiveContactBlock(std::string name, std::vector<VariableId> variables, const KnotVector& knots,
                       int point_size, int p_offset, const Obstacle& roller, double radius,
                       ComplementarityFunction function, double length_scale, double force_scale)
      : ResidualBlock("rod.adhesive_contact", std::move(name), 6, std::move(variables)),
        knots_(knots),
        point_size_(point_size),
        p_offset_(p_offset),
        roller_(roller),
        axis_(roller),
        radius_(radius),
        function_(function),
        length_scale_(length_scale),
        density_scale_(length_scale / force_scale) {
    axis_.shape = ObstacleShape::Cylinder;  // its offset is the radial one of the roller's side
  }

  int num_points() const { return static_cast<int>(variables().size()) - 3; }

  int expected_variable_size(int k) const override {
    return k < num_points() ? point_size_ : k == num_points() ? 5 : 1;
  }

  bool structural_nonzero(int k, int row, int column) const override {
    if (k < num_points()) return row != 3 && column >= p_offset_ && column < p_offset_ + 3;
    if (k == num_points() + 1) return row < 3 || row == 5;  // mu
    if (k == num_points() + 2) return row == 3;             // L
    if (row < 3) return column == 0 || column == 1 || column == 2 + row;
    return row == 4 ? column <= 1 : column == 0;
  }

  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override {
    const double* e = values[num_points()];
    const double u = e[0], lambda = e[1], mu = values[num_points() + 1][0], L = values[num_points() + 2][0];
    const Eigen::Map<const Vec3> G(e + 2);
    const double ub = std::clamp(u, 0.0, 1.0);
    const bool inside = u == ub;
    const BasisDerivatives b = basis_derivatives(knots_, ub, 2);
    const int active = static_cast<int>(b.values.cols());
    VecX a(active), b1(active);  // dp/dP_i and dp'/dP_i
    Vec3 p = Vec3::Zero(), p1 = Vec3::Zero(), p2 = Vec3::Zero();
    for (int i = 0; i < active; ++i) {
      const Eigen::Map<const Vec3> P(values[b.first + i] + p_offset_);
      a[i] = b.values(0, i) + b.values(1, i) * (u - ub);
      b1[i] = b.values(1, i);
      p += a[i] * P;
      p1 += b1[i] * P;
      if (inside) p2 += b.values(2, i) * P;
    }
    const ObstacleGap g = obstacle_gap(roller_, p, radius_);
    const ObstacleOffset v = obstacle_offset(axis_, p);
    const double q = p1.squaredNorm(), speed = std::sqrt(q);
    const Vec3 t = p1 / speed;
    const Mat3 dt = (Mat3::Identity() - t * t.transpose()) / speed;  // dt/dp'
    double phi_a = 0.0, phi_b = 0.0;
    const double gap = g.gap / length_scale_, force = lambda * density_scale_;
    const bool closed = gap <= force;
    for (int r = 0; r < 3; ++r) residual[r] = (G[r] - lambda * g.normal[r] - mu * t[r]) * density_scale_;
    const double sigma = roller_.adhesive_section();
    residual[3] = (u * L - sigma) / length_scale_;
    complementarity(function_, gap, force, residual[4], phi_a, phi_b);
    residual[5] = closed ? v.offset.dot(p1) / q : mu * density_scale_;
    if (jacobians == nullptr) return;
    const Vec3 ds_dp = v.jacobian.transpose() * p1 / q;
    const Vec3 ds_dp1 = v.offset / q - 2.0 * v.offset.dot(p1) * p1 / (q * q);
    for (int k = 0; k < num_points(); ++k)
      if (jacobians[k] != nullptr) std::fill(jacobians[k], jacobians[k] + 6 * point_size_, 0.0);
    for (int i = 0; i < active; ++i) {
      double* J = jacobians[b.first + i];
      if (J == nullptr) continue;
      for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < 3; ++r)
          J[r * point_size_ + p_offset_ + c] =
              -(lambda * g.normal_derivative(r, c) * a[i] + mu * dt(r, c) * b1[i]) * density_scale_;
        J[4 * point_size_ + p_offset_ + c] = phi_a * g.normal[c] * a[i] / length_scale_;
        if (closed) J[5 * point_size_ + p_offset_ + c] = ds_dp[c] * a[i] + ds_dp1[c] * b1[i];
      }
    }
    if (double* J = jacobians[num_points()]) {
      std::fill(J, J + 30, 0.0);
      const Vec3 dnu_du = g.normal_derivative * p1, dt_du = dt * p2;
      for (int r = 0; r < 3; ++r) {
        J[r * 5 + 0] = -(lambda * dnu_du[r] + mu * dt_du[r]) * density_scale_;
        J[r * 5 + 1] = -g.normal[r] * density_scale_;
        J[r * 5 + 2 + r] = density_scale_;
      }
      J[15] = L / length_scale_;
      J[20] = phi_a * g.normal.dot(p1) / length_scale_;
      J[21] = phi_b * density_scale_;
      if (closed) J[25] = ds_dp.dot(p1) + ds_dp1.dot(p2);
    }
    if (double* J = jacobians[num_points() + 1]) {
      for (int r = 0; r < 3; ++r) J[r] = -t[r] * density_scale_;
      J[3] = J[4] = 0.0;
      J[5] = closed ? 0.0 : density_scale_;
    }
    if (double* J = jacobians[num_points() + 2]) {
      std::fill(J, J + 6, 0.0);
      J[3] = u / length_scale_;
    }
  }

 private:
  KnotVector knots_;
  int point_size_, p_offset_;
  Obstacle roller_, axis_;  // the roller, and the infinite cylinder of its side
  double radius_;
  ComplementarityFunction function_;
  double length_scale_, density_scale_;
};

}  // namespace

std::shared_ptr<ResidualBlock> make_adhesive_contact_block(std::string name,
                                                           std::vector<VariableId> variables,
                                                           const KnotVector& knots, int point_size,
                                                           int p_offset, const Obstacle& roller,
                                                           double radius, ComplementarityFunction function,
                                                           double length_scale, double force_scale) {
  return std::make_shared<AdhesiveContactBlock>(std::move(name), std::move(variables), knots, point_size,
                                                p_offset, roller, radius, function, length_scale,
                                                force_scale);
}

}  // namespace pcr::contact
