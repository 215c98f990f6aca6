#pragma once
// The independent discrete energy model (discrete_rods.hpp) of a robot's FK equilibrium: rods clamped at
// their start in the world or on a link turned by one passive revolute joint (a hinge on a fixed link,
// with its spring, link weights and loads), their end on a platform (clamped, collar or spherical) or
// free with a dead force, dead loads (rod and platform gravity, external forces on platforms), started
// from the collocation state and relaxed.
#include "pcr/robots/robot_assembly.hpp"
#include "stability/discrete_rods.hpp"

namespace pcr::test {

/// The discrete model of the assembly at the state x (segments per rod), relaxed to its own equilibrium;
/// its inertia. Requires (BOOST_TEST_REQUIRE) that the model fits: clamped starts on fixed links or hinge
/// links, ends on platform links with clamped, collar or spherical couplings or free, no intrinsic strains,
/// no dead torques or couples.
DiscreteRods::Inertia discrete_robot_inertia(const RobotAssembly& assembly, const VecX& x, int segments);

}  // namespace pcr::test
