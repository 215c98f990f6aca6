#pragma once
// Private to pcr_robots: what the assembly needs for rods that may touch obstacles (docs/contact.md).
#include <vector>

#include "pcr/robots/robot_assembly.hpp"
#include "pcr/rods/rod_contact.hpp"
#include "platform_contact.hpp"

namespace pcr::assembly {

/// A rod with obstacles is discretised in the mixed form at the midpoints with contact forces (the only
/// formulation with contact rows; the condensed default is the same discrete scheme with n, m eliminated).
/// Throws InputError when the model asks for the primal form by name.
void set_contact_discretization(const RodElement& rod, bool use_model_hints, RodDiscretization& d);

/// The rod's obstacles in the world frame for the given joint values and platform poses (in the order of
/// RodElement::obstacles): an obstacle on a link is placed with the link's pose.
std::vector<Obstacle> rod_obstacles_at(const RobotModel& model, const RodElement& rod,
                                       const VecX& joint_values, const std::vector<Pose>& platform_poses);

/// The rod's obstacles in the world frame at the default joint values and initial platform poses, its
/// contact radius, and the wrapper of its contact blocks. Obstacles on a link that actuated joints move
/// or that a platform carries (docs/contact.md, "Obstacles on moving links") follow the link: the contact
/// blocks are wrapped (moving_obstacle_block.hpp) with the link's frame of the assembly's joint or
/// platform variables; p_offset is the rod's centerline offset in a control point. The reaction of
/// obstacles on a platform enters the platform's balance (platform_contact). Throws InputError for
/// obstacles on a link moved by a passive joint (their reaction is not in its balance), for concentrated
/// contact with obstacles on a platform, and for a rod whose obstacles are on different moving links or
/// on a moving link and the world.
struct RodContactSetup {
  RodContactOptions options;
  ContactBlockWrapper wrap_block;  ///< none unless the obstacles are on a moving link
  int platform = -1;               ///< the platform that carries the rod's obstacles, or -1
};
RodContactSetup rod_contact_setup(const RobotModel& model, const RodElement& rod,
                                  ComplementarityFunction function, int p_offset,
                                  const std::vector<VariableId>& platform_variables,
                                  const std::vector<VariableId>& joint_variables);

/// The rod's contact cells for the balance of the platform that carries its obstacles.
PlatformContact platform_contact(const CollocationRod& rod, const RodVariables& vars,
                                 const RodContactVariables& contact);

}  // namespace pcr::assembly
