#pragma once
// Contact rows of a rod with obstacles on a moving link (internal header of pcr::robots; docs/contact.md,
// "Obstacles on moving links"). The rods' contact blocks (rod_contact.hpp) take their obstacles at fixed
// world poses: the placement Z0 = (x0, R0) of the link in the problem's initial configuration. When the
// link's pose Z(z) = (x, R(Q)) depends on unknowns z (joint values, a platform pose), the wrapper maps
// the world quantities the inner block reads into the frame in which the obstacles sit at Z0, by the
// rigid motion Z0 Z(z)^-1:
//   centerline control points  P' = A (P - x) + x0,   world vectors (F_j, G)  v' = A v,   A = R0 R(Q)^T,
// and evaluates the inner block there: gaps and complementarity are invariant, the force rows come out
// rotated by A (equivalent equations, A orthogonal). Jacobians by the chain rule, with dz/d(variables)
// from LinkFrame and dR/dQ from rotation_matrix_derivatives.
#include <memory>
#include <vector>

#include "link_frame.hpp"

namespace pcr::assembly {

/// What a variable of the inner block holds: a rod control point (its P components at p_offset), a
/// world force vector (3), a sharp obstacle's block [u_c, lambda, G (3)], or frame-independent values.
enum class ContactVariableRole { ControlPoint, Vector, Sharp, Plain };

/// The wrapped block: the inner block's variables, then the frame's (LinkFrame::variables).
/// `frame` is the obstacles' link frame (offset: identity attachment), z0 its value in the initial
/// configuration (where the inner block's obstacles are placed).
std::shared_ptr<ResidualBlock> make_moving_obstacle_block(std::shared_ptr<const ResidualBlock> inner,
                                                          std::vector<ContactVariableRole> roles,
                                                          int p_offset, LinkFrame frame, const Vec7& z0);

}  // namespace pcr::assembly
