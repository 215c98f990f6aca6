#pragma once
// Structural well-posedness of an assembly (docs/design.md §3). The rod and platform equations always count
// square (7 per rod end, 7 per platform), so what can still go wrong is rank: a platform whose 6 DOF
// are not all held by the kinematic couplings of its rods (e.g. only spherical or free ends, a single
// collar) leaves the assembled Jacobian singular. The check models each rod as rigid between its
// clamped end and its other coupling; an elastic rod constrains the same relative motions, so the rank
// of this matrix is the generic rank of the platform block of the Jacobian.
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/robots/pose.hpp"

namespace pcr {

class RobotModel;

/// Rows: the kinematic constraints of every rod coupling that joins two different bodies (a body is a
/// platform or the world), evaluated at the given configuration; columns: the twist [v; w] (world
/// frame, v at the platform origin) of each platform, 6 per platform. Rows of couplings to the world
/// only are kept (they hold the platform); rows between two world-fixed links are zero.
MatX coupling_constraint_matrix(const RobotModel& model, const VecX& joint_values,
                                const std::vector<Pose>& platform_poses);

/// Throws InputError naming the platform and its rods when a platform has no rods, when its rods
/// put fewer than 6 kinematic constraints on it, or when coupling_constraint_matrix at the default
/// inputs and initial platform poses has a rank below 6 per platform (naming the free motion).
void check_platforms_held(const RobotModel& model);

}  // namespace pcr
