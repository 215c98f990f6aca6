#pragma once
// Structural well-posedness of an assembly (docs/design.md §3). The rod, platform and passive-joint
// equations always count square (7 per rod end, 7 per platform, 1 per passive joint), so what can still go
// wrong is rank: a platform or a passive joint whose motion no coupling resists (e.g. only spherical or
// free ends, a single collar, a passive hinge carrying only a pinned rod) leaves the assembled Jacobian
// singular. The check treats the rods as rigid: a rod with a clamped end moves with that end's link, a
// rod without one is a rigid body of its own; an elastic rod constrains the same relative motions, so
// the rank of this matrix is the generic rank of the Jacobian's rigid-motion part.
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/robots/pose.hpp"

namespace pcr {

class RobotModel;

/// Rows: the kinematic constraints of every rod coupling on the relative twist at its attachment frame
/// (clamped 6, collar 5, revolute 5, universal 4, spherical 3, free 0; for a rod with a clamped end only
/// its other end's, between the two links; for a rod without one both ends', between link and rod),
/// evaluated at the given configuration. Columns, in this order: the twist [v; w] (world frame, v at the
/// platform origin) of each platform (6 each); the rate of each passive joint without a spring (1 each,
/// in RobotModel::passive_joints() order; a spring holds the others); the twist [v; w] (v at its start
/// attachment, or its end's when the start is free) of each rod without a clamped end (6 each, rod
/// order). Links fixed to the world or moved only by actuated joints do not move.
MatX coupling_constraint_matrix(const RobotModel& model, const VecX& joint_values,
                                const std::vector<Pose>& platform_poses);

/// Throws InputError naming the platform and its rods when a platform has no rods, when its rods
/// put fewer than 6 kinematic constraints on it, or when coupling_constraint_matrix at the default
/// inputs and initial platform poses has a null motion: naming the platform, passive joint or rod that
/// moves most in it, the free motion, and what else moves with it.
void check_platforms_held(const RobotModel& model);

}  // namespace pcr
