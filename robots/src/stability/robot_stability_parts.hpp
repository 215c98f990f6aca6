#pragma once
// The parts of robot_stability (robot_stability.hpp; internal header of pcr::robots): the model's
// assumptions, each rod's count with its links held, and the platforms' reduced stiffness.
#include <string>
#include <vector>

#include "pcr/robots/robot_assembly.hpp"
#include "pcr/rods/stability/held_rod.hpp"

namespace pcr::stability {

/// Why the criterion does not apply to the model (empty when it does): non-conservative loads
/// (rod_stability.hpp nonconservative_loads; a dead torque on a link carried by a platform) or passive
/// joints (their coordinates are not in the reduced stiffness yet).
std::string robot_assumption_failure(const RobotModel& model);

/// Rod i's Morse index with its couplings held in their link frames at the state x.
HeldRodIndex held_rod_in_robot(const RobotAssembly& assembly, const VecX& x, int rod);

/// The platforms' reduced stiffness in the dimensionless form K_hat = D K_red D / M0 (robot_stability.hpp),
/// from the full compliance at x (before symmetrising), or a failure.
struct PlatformStiffness {
  bool ok = false;
  std::string failure;
  MatX stiffness;  ///< K_hat, 6 rows and columns per platform [dx / L0 (3), dtheta (3)]
};
PlatformStiffness platform_stiffness(const RobotAssembly& assembly, const VecX& x);

}  // namespace pcr::stability
