#pragma once
// Set-ups and independent references of the IK objective tests: the strain-form elastic energy, the
// stress of a circular section, central-difference gradients, R5a's position target and the FK values of
// the objectives, and the projection of inputs onto the target.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "pcr/robots/kinematics.hpp"

namespace pcr::test {

inline constexpr double kPi = 3.14159265358979323846;

/// Elastic energy in the strain form, 1/2 int (kappa^T K_BT kappa + eps^T K_SE eps) ds (the test
/// models have no intrinsic strains), by Simpson's rule on 2000 intervals per rod.
inline double strain_energy(const RobotAssembly& a, const VecX& x) {
  double energy = 0.0;
  for (int r = 0; r < a.num_rods(); ++r) {
    const CollocationRod& rod = a.rod(r);
    BOOST_REQUIRE(rod.model().intrinsic.is_zero());
    const double L = rod.length(x, a.rod_variables(r));
    const int n = 2000;
    for (int i = 0; i <= n; ++i) {
      const RodState st = rod.state_at(x, a.rod_variables(r), L * i / n);
      const double e =
          0.5 *
          (st.curvature_body.dot(rod.model().bending_torsion_stiffness.cwiseProduct(st.curvature_body)) +
           st.shear_extension_body.dot(
               rod.model().shear_extension_stiffness.cwiseProduct(st.shear_extension_body)));
      const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      energy += w * e * L / (3.0 * n);
    }
  }
  return energy;
}

/// Outer-fibre stress of a solid circle of radius c: |N| / (pi c^2) + |M_perp| c / (pi c^4 / 4).
inline double circle_stress(const RodState& st, double c) {
  const Vec3 d3 = st.rotation.col(2);
  const double N = st.force.dot(d3);
  const Vec3 m_perp = st.moment - st.moment.dot(d3) * d3;
  return std::abs(N) / (kPi * c * c) + m_perp.norm() * c / (kPi * std::pow(c, 4) / 4.0);
}

/// Max stress at points_per_rod equally spaced points of every rod (radius 1 mm: stewart_gough).
inline double max_stress(const RobotAssembly& a, const VecX& x, int points_per_rod, double radius) {
  double s = 0.0;
  for (int r = 0; r < a.num_rods(); ++r) {
    const double L = a.rod(r).length(x, a.rod_variables(r));
    for (int j = 0; j < points_per_rod; ++j)
      s = std::max(
          s, circle_stress(a.rod(r).state_at(x, a.rod_variables(r), L * j / (points_per_rod - 1)), radius));
  }
  return s;
}

/// Central differences of f over every entry of x, h = 1e-6 (1 + |x_i|).
template <class F>
inline VecX numeric_gradient(F f, VecX x) {
  VecX g(x.size());
  for (int i = 0; i < x.size(); ++i) {
    const double xi = x[i], h = 1e-6 * (1.0 + std::abs(xi));
    x[i] = xi + h;
    const double fp = f(x);
    x[i] = xi - h;
    const double fm = f(x);
    x[i] = xi;
    g[i] = (fp - fm) / (2.0 * h);
  }
  return g;
}

inline LinkTarget position_target(const Vec3& p) {
  LinkTarget t;
  t.link = "platform";
  t.mode = LinkTarget::Mode::Position;
  t.pose.position = p;
  return t;
}

/// A position-only target near R5a's (3 of 6 inputs redundant), off the symmetry axis: at the
/// symmetric point (0, 0, 0.4) every objective is stationary by symmetry and Ipopt started from equal
/// inputs stays on equal inputs (a saddle of the distance).
inline const Vec3 kTarget(0.01, -0.015, 0.41);

/// Effort and energy of the FK solution at u (independent of the IK code): sum of squared axial
/// forces at the feed points [N^2] from read_solution, strain-form energy [J].
struct FkObjectives {
  bool converged = false;
  Vec3 position = Vec3::Zero();
  double effort = 0.0, energy = 0.0;
};
inline FkObjectives fk_objectives(ForwardKinematics& fk, const VecX& u) {
  FkObjectives o;
  const RobotSolution s = fk.solve(u);
  o.converged = s.summary.converged();
  o.position = s.platforms[0].position;
  for (const RodResult& r : s.rods) o.effort += r.axial_force * r.axial_force;
  o.energy = strain_energy(fk.assembly(), fk.state());
  return o;
}

/// Projects u onto {u : platform position(u) = target} by Gauss-Newton with the minimum-norm step
/// u <- u - J^+ (p(u) - target) (J: position rows of FK's input Jacobian); false if FK fails.
inline bool project_onto_target(ForwardKinematics& fk, VecX& u, const Vec3& target) {
  for (int it = 0; it < 30; ++it) {
    const RobotSolution s = fk.solve(u);
    if (!s.summary.converged()) return false;
    const Vec3 d = s.platforms[0].position - target;
    if (d.norm() < 1e-13) return true;  // 1e-13 m: round-off level of positions ~0.4 m
    const MatX J = fk.input_jacobian().topRows(3);
    u -= J.transpose() * (J * J.transpose()).ldlt().solve(d);
  }
  return false;
}

}  // namespace pcr::test
