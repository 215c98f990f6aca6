#pragma once
// The independent discrete energy model (discrete_rods.hpp) of a robot's FK equilibrium: rods clamped in
// the world at their start, their end on a platform (clamped, collar or spherical), dead loads (rod and
// platform gravity, external forces on platforms), started from the collocation state and relaxed.
#include "pcr/robots/robot_assembly.hpp"
#include "stability/discrete_rods.hpp"

namespace pcr::test {

/// The discrete model of the assembly at the state x (segments per rod), relaxed to its own equilibrium;
/// its inertia. Requires (BOOST_TEST_REQUIRE) that the model fits: clamped starts on fixed links, ends on
/// platform links with clamped, collar or spherical couplings, no intrinsic strains, no dead torques.
DiscreteRods::Inertia discrete_robot_inertia(const RobotAssembly& assembly, const VecX& x, int segments);

}  // namespace pcr::test
