#pragma once
// Internal pieces of the contact rows shared by the midpoint blocks (contact_block.cpp) and the blocks of
// sharp obstacles (edge_contact_block.cpp); rod_contact.hpp describes the discretisation.
#include <memory>
#include <string>
#include <vector>

#include "pcr/rods/rod_contact.hpp"
#include "pcr/splines/basis.hpp"
#include "pcr/splines/knot_vector.hpp"

namespace pcr::contact {

/// phi(a, b) of the complementarity function and its (generalised) partial derivatives.
void complementarity(ComplementarityFunction f, double a, double b, double& phi, double& phi_a,
                     double& phi_b);

/// The share w_j(u) of a concentrated force at u carried by midpoint j, and dw_j / du: the piecewise
/// linear interpolation between the two midpoints u_m <= u < u_{m+1} that bracket u (the first or last
/// pair beyond them, extrapolated), w_m = 1 - t, w_{m+1} = t, t = (u - u_m) / (u_{m+1} - u_m). Sum and
/// first moment are exact: sum_j w_j = 1, sum_j w_j u_j = u.
struct HatWeight {
  double weight = 0.0, derivative = 0.0;
};
HatWeight midpoint_share(const std::vector<double>& midpoints, int j, double u);

/// The centerline at the contact section u of a concentrated contact: p(u), p'(u) and p''(u) from the
/// rod's control points (values[i] + p_offset), with dp/dP_i = a_i and dp'/dP_i = b1_i for the active
/// control points basis.first + i. Beyond [0, 1] the centerline is extended along the end tangent,
/// p(u) = p(ub) + p'(ub) (u - ub) with ub = clamp(u, 0, 1), and p'' = 0 there (inside = false).
struct ContactSection {
  BasisDerivatives basis;  // at ub, up to the second derivative
  bool inside = true;
  int active = 0;
  VecX a, b1;
  Vec3 p = Vec3::Zero(), p1 = Vec3::Zero(), p2 = Vec3::Zero();
};
ContactSection contact_section(const KnotVector& knots, const double* const* values, int p_offset, double u);

/// The step s = v . p' / |p'|^2 from a section towards the section nearest to an obstacle (v = p - c(p),
/// obstacle_offset; s = 0 where p' is normal to v) and its derivatives ds/dp = J_v^T p' / |p'|^2 and
/// ds/dp' = v / |p'|^2 - 2 (v . p') p' / |p'|^4.
struct NearestSectionStep {
  double value = 0.0;
  Vec3 d_p = Vec3::Zero(), d_p1 = Vec3::Zero();
};
NearestSectionStep nearest_section_step(const ObstacleOffset& v, const Vec3& p1);

/// The rows of one sharp obstacle (edge, point) touching a rod (rod_contact.hpp). Variables: all the rod's
/// control points (the contact section moves along the rod), then the obstacle's block
/// [u_c, lambda, G (3)].
std::shared_ptr<ResidualBlock> make_sharp_contact_block(std::string name, std::vector<VariableId> variables,
                                                        const KnotVector& knots, int point_size, int p_offset,
                                                        const Obstacle& obstacle, double radius,
                                                        ComplementarityFunction function, double length_scale,
                                                        double force_scale);

/// The rows of a roller with the adhesion law touching a rod (rod_contact.hpp, adhesion_block.cpp).
/// Variables: all the rod's control points, the obstacle's block [u_c, lambda, G (3)], its tangential
/// force [mu] and the rod's length [L]. reference_normal: the roller's unit normal nu_0 at the stuck
/// section in the reference state (the contact direction from which the roller's rolling is counted).
std::shared_ptr<ResidualBlock> make_adhesive_contact_block(
    std::string name, std::vector<VariableId> variables, const KnotVector& knots, int point_size,
    int p_offset, const Obstacle& roller, const Vec3& reference_normal, double radius,
    ComplementarityFunction function, double length_scale, double force_scale);

}  // namespace pcr::contact
