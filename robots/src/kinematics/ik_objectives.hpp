#pragma once
// IK objectives and rod stresses as functions of the assembly's variables x, with gradients d/dx
// (internal header of pcr::robots; the reduced-space IK chains them with dx/du).
//  - actuation effort: 1/2 sum over fed rods of (n(0) . d3(0) / F0)^2;
//  - elastic energy [J]: int_0^L 1/2 (m_b^T K_BT^-1 m_b + n_b^T K_SE^-1 n_b) ds over all rods, with
//    n_b = R^T n, m_b = R^T m: with n = R K_SE (eps - eps0), m = R K_BT (kappa - kappa0) this is
//    1/2 (eps - eps0)^T K_SE (eps - eps0) + 1/2 (kappa - kappa0)^T K_BT (kappa - kappa0), intrinsic
//    strains included. Gauss-Legendre, degree + 1 points per knot span, ds = L du.
//  - outer-fibre stress [Pa] at u: E (|N| / EA + |M_perp| c / min(EI1, EI2)), N = n_b3,
//    M_perp = (m_b1, m_b2), c = outer radius; exact for a circle, an upper bound for a rectangle (c is
//    the half diagonal). |.| is smoothed as sqrt(. ^2 + delta^2), delta = 1e-9 F0 (force) and 1e-9 M0
//    (moment), so the bound stays differentiable at zero; it overestimates by at most that delta.
// Mixed rods: n, m, q are interpolated control points, gradients analytic. Primal rods (n, m from the
// strains): gradients by central differences of the point state over the rod's control points.
#include <vector>

#include "pcr/robots/robot_assembly.hpp"

namespace pcr::kinematics {

/// Dimensionless actuation effort; gradient (size x) when asked. Throws InputError if no rod is fed.
double actuation_effort(const RobotAssembly& assembly, const VecX& x, VecX* gradient);

/// Elastic energy of all rods [J]; gradient when asked.
double elastic_energy(const RobotAssembly& assembly, const VecX& x, VecX* gradient);

struct StressPoint {
  int rod = 0;
  double u = 0.0;  ///< in [0, 1], s = u L
};
/// points_per_rod equally spaced points on every rod (u = 0 .. 1).
std::vector<StressPoint> stress_points(const RobotAssembly& assembly, int points_per_rod);
/// Throws InputError naming the rod when its Young's modulus or outer radius is unknown.
void check_stress_data(const RobotAssembly& assembly);
/// Outer-fibre stress [Pa] at each point; jacobian (points x size x) when asked.
VecX rod_stresses(const RobotAssembly& assembly, const VecX& x, const std::vector<StressPoint>& points,
                  MatX* jacobian);

}  // namespace pcr::kinematics
