// The rows of a roller with the adhesion law (no slip) touching a rod (rod_contact.hpp, docs/contact.md
// "Rollers"). Unknowns [u_c, lambda, G] as a sharp obstacle (edge_contact_block.cpp: the contact section,
// the normal force magnitude and the force vector per unit of u), the tangential force mu per unit of u
// (signed, along the rod's unit tangent t = p' / |p'| at u_c) and the rod's length L (read only). With p,
// p', p'' at u_c (extended along the end tangent beyond [0, 1]), the roller's gap g and normal nu
// (obstacle_gap), the offset v = (I - a a^T)(p - x0) of the centerline from the roller's axis a, the
// rolling direction e = a x nu (where a rotation of the roller about a moves its surface at the contact)
// and the angle psi = atan2(a . (nu_0 x nu), nu_0 . nu) of the contact direction about a from the
// reference one nu_0:
//   rows 0..2:  (G - lambda nu - mu t) L0 / F0                  (normal plus tangential force, through p)
//   row 3:      (u_c L - sigma_0 - R (psi - theta) t . e) / L0   (no slip, below)
//   row 4:      phi(g / L0, lambda L0 / F0)                      (complementarity of the normal force)
//   row 5:      closed: v . p' / |p'|^2                          (the section u_c is where the rod
//                                                                  touches: the tangency row of an edge;
//                                                                  mu is its multiplier)
//               open:   mu L0 / F0                               (no tangential force without contact)
// No slip: the rod's surface and the roller's roll on each other, so the material arc that passes the
// contact is the same on both, R times the roller's rotation relative to the contact direction, psi -
// theta (theta: the roller's rotation about a, right-handed); along the rod it counts with t . e = +-1 for
// a rod normal to the axis (its sign says whether e points toward the rod's tip). A roller at rest under
// a rod that tilts by psi at the contact lets it roll over (the section moves by R psi); a turning roller
// feeds R theta of material past the contact.
// closed / open is the active set of the complementarity, as the min function reads it: closed when
// g / L0 <= lambda L0 / F0 (row 4 then enforces g = 0), open otherwise (it enforces lambda = 0). The
// switch is a semismooth selection like min itself; at g = lambda = 0 the contact counts as closed.
// Jacobians by hand: with q = |p'|^2 and s = v . p' / q, N = d nu / d p,
//   ds/dp = J_v^T p' / q,  ds/dp' = v / q - 2 (v . p') p' / q^2,  dt/dp' = (I - t t^T) / |p'|,
//   d psi / d p = N^T (x (a x nu_0) - y nu_0) / (x^2 + y^2) with y = nu . (a x nu_0), x = nu . nu_0,
//   d (t . e) / d p = N^T (t x a),  d (t . e) / d p' = dt/dp'^T e.
#include <algorithm>
#include <cmath>

#include "edge_contact.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr::contact {
namespace {

// The rolled arc R (psi - theta) (t . e) of row 3 and its gradients in p and p'.
struct RolledArc {
  double value = 0.0;
  Vec3 d_p = Vec3::Zero(), d_p1 = Vec3::Zero();
};

RolledArc rolled_arc(const Obstacle& roller, const Vec3& reference_normal, const ObstacleGap& g,
                     const Vec3& t, const Mat3& dt) {
  const Vec3& a = roller.direction;
  const Vec3 across = a.cross(reference_normal), e = a.cross(g.normal);
  const double y = g.normal.dot(across), x = g.normal.dot(reference_normal);
  const double psi = std::atan2(y, x), rho2 = x * x + y * y;
  const Vec3 dpsi_dnu = rho2 > 0.0 ? Vec3((x * across - y * reference_normal) / rho2) : Vec3::Zero();
  const double turn = psi - roller.angle, along = t.dot(e);
  RolledArc out;
  out.value = roller.radius * turn * along;
  out.d_p = roller.radius * (along * g.normal_derivative.transpose() * dpsi_dnu +
                             turn * g.normal_derivative.transpose() * t.cross(a));
  out.d_p1 = roller.radius * turn * dt.transpose() * e;
  return out;
}

class AdhesiveContactBlock final : public ResidualBlock {
 public:
  AdhesiveContactBlock(std::string name, std::vector<VariableId> variables, const KnotVector& knots,
                       int point_size, int p_offset, const Obstacle& roller, const Vec3& reference_normal,
                       double radius, ComplementarityFunction function, double length_scale,
                       double force_scale)
      : ResidualBlock("rod.adhesive_contact", std::move(name), 6, std::move(variables)),
        knots_(knots),
        point_size_(point_size),
        p_offset_(p_offset),
        roller_(roller),
        axis_(roller),
        reference_normal_(reference_normal),
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
    if (k < num_points()) return column >= p_offset_ && column < p_offset_ + 3;
    if (k == num_points() + 1) return row < 3 || row == 5;  // mu
    if (k == num_points() + 2) return row == 3;             // L
    if (row < 3) return column == 0 || column == 1 || column == 2 + row;
    return row == 4 ? column <= 1 : column == 0;
  }

  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override;

 private:
  KnotVector knots_;
  int point_size_, p_offset_;
  Obstacle roller_, axis_;  // the roller, and the infinite cylinder of its side
  Vec3 reference_normal_;   // nu_0
  double radius_;
  ComplementarityFunction function_;
  double length_scale_, density_scale_;
};

void AdhesiveContactBlock::evaluate(const double* const* values, double* residual,
                                    double* const* jacobians) const {
  const double* e = values[num_points()];
  const double u = e[0], lambda = e[1], mu = values[num_points() + 1][0], L = values[num_points() + 2][0];
  const Eigen::Map<const Vec3> G(e + 2);
  const ContactSection cs = contact_section(knots_, values, p_offset_, u);
  const BasisDerivatives& b = cs.basis;
  const int active = cs.active;
  const VecX &a = cs.a, &b1 = cs.b1;  // dp/dP_i and dp'/dP_i
  const Vec3 &p = cs.p, &p1 = cs.p1, &p2 = cs.p2;
  const ObstacleGap g = obstacle_gap(roller_, p, radius_);
  const ObstacleOffset v = obstacle_offset(axis_, p);
  const double q = p1.squaredNorm(), speed = std::sqrt(q);
  const Vec3 t = p1 / speed;
  const Mat3 dt = (Mat3::Identity() - t * t.transpose()) / speed;  // dt/dp'
  const RolledArc arc = rolled_arc(roller_, reference_normal_, g, t, dt);
  double phi_a = 0.0, phi_b = 0.0;
  const double gap = g.gap / length_scale_, force = lambda * density_scale_;
  const bool closed = gap <= force;
  for (int r = 0; r < 3; ++r) residual[r] = (G[r] - lambda * g.normal[r] - mu * t[r]) * density_scale_;
  residual[3] = (u * L - roller_.stuck_section - arc.value) / length_scale_;
  complementarity(function_, gap, force, residual[4], phi_a, phi_b);
  const NearestSectionStep step = nearest_section_step(v, p1);
  residual[5] = closed ? step.value : mu * density_scale_;
  if (jacobians == nullptr) return;
  const Vec3 &ds_dp = step.d_p, &ds_dp1 = step.d_p1;
  for (int k = 0; k < num_points(); ++k)
    if (jacobians[k] != nullptr) std::fill(jacobians[k], jacobians[k] + 6 * point_size_, 0.0);
  for (int i = 0; i < active; ++i) {
    double* J = jacobians[b.first + i];
    if (J == nullptr) continue;
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r)
        J[r * point_size_ + p_offset_ + c] =
            -(lambda * g.normal_derivative(r, c) * a[i] + mu * dt(r, c) * b1[i]) * density_scale_;
      J[3 * point_size_ + p_offset_ + c] = -(arc.d_p[c] * a[i] + arc.d_p1[c] * b1[i]) / length_scale_;
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
    J[15] = (L - arc.d_p.dot(p1) - arc.d_p1.dot(p2)) / length_scale_;
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

}  // namespace

std::shared_ptr<ResidualBlock> make_adhesive_contact_block(
    std::string name, std::vector<VariableId> variables, const KnotVector& knots, int point_size,
    int p_offset, const Obstacle& roller, const Vec3& reference_normal, double radius,
    ComplementarityFunction function, double length_scale, double force_scale) {
  return std::make_shared<AdhesiveContactBlock>(std::move(name), std::move(variables), knots, point_size,
                                                p_offset, roller, reference_normal, radius, function,
                                                length_scale, force_scale);
}

}  // namespace pcr::contact
