#pragma once
// Private to pcr_robots: what the assembly needs for rods that may touch obstacles (docs/contact.md).
#include "pcr/robots/robot_assembly.hpp"
#include "pcr/rods/rod_contact.hpp"

namespace pcr::assembly {

/// A rod with obstacles is discretised in the mixed form at the midpoints with contact forces (the only
/// formulation with contact rows; the condensed default is the same discrete scheme with n, m eliminated).
/// Throws InputError when the model asks for the primal form by name.
void set_contact_discretization(const RodElement& rod, bool use_model_hints, RodDiscretization& d);

/// The rod's obstacles in the world frame and its contact radius. Obstacles on links that a joint or a
/// platform moves are rejected (InputError): their reaction on the link is not modelled.
RodContactOptions rod_contact_options(const RobotModel& model, const RodElement& rod,
                                      ComplementarityFunction function);

}  // namespace pcr::assembly
