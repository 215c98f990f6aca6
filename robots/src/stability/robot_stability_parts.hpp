#pragma once
// The parts of robot_stability (robot_stability.hpp; internal header of pcr::robots): the model's
// assumptions and each rod's count with its links held (the border's reduced stiffness is public:
// robot_border_stiffness).
#include <string>
#include <vector>

#include "pcr/robots/robot_assembly.hpp"
#include "pcr/rods/stability/held_rod.hpp"
#include "pcr/rods/stability/stability.hpp"

namespace pcr::stability {

/// Why the criterion does not apply to the model (empty when it does): non-conservative loads
/// (rod_stability.hpp nonconservative_loads; a dead torque on a link carried by a platform or moved by
/// passive joints).
std::string robot_assumption_failure(const RobotModel& model);

/// A contact row touches when its gap is below this fraction of L0 (read_rod_contact's threshold). Above
/// it the complementarity row phi(a, b) (a = g / L0, b = lambda L0 / F0 at the solver's residual
/// tolerance, ~1e-10) has d phi / d a ~ b^2 / (2 a^2) < 1e-8 (Fischer-Burmeister) or 0 (min): it reads
/// d lambda = 0 and decouples from the rod's variation, and variations small enough for the second
/// variation keep the contact open.
inline constexpr double kTouchingGap = 1e-6;

/// The reasons of the two `unknown` verdicts a finer mesh can resolve (refined_verdict.hpp): the border's
/// reduced stiffness too asymmetric (the reason starts with it), and a touching rod whose Ritz form has no
/// equilibrium next to the state (the reason contains it).
inline constexpr const char* kAsymmetricBorder =
    "reduced stiffness of the platforms and passive joints not symmetric";
inline constexpr const char* kNoRitzEquilibrium = "the energy's Ritz form has no equilibrium next to it";

/// The first rod touching an obstacle at one of its contact rows at the state x (gap below kTouchingGap
/// L0): "rod 'a' touches obstacle 'b' (gap g m at s = s m)", or "" when every
/// contact is open. Then the equilibrium is one of the robot without obstacles, and variations small
/// enough for the second variation keep the contacts open: the criterion applies unchanged.
std::string touching_contact(const RobotAssembly& assembly, const VecX& x);

/// The verdict at a state x counted on the energy's Ritz form (energy_model.hpp): the second variation at
/// its equilibrium next to x, with the touching contacts held, on the tangent space of the held
/// constraints (docs/design.md §4). For rods touching obstacles, and for a rod at a conjugate point with
/// its links held (where the split into held rods and border does not apply); why: which, for the reason.
Stability ritz_stability(const RobotAssembly& assembly, const VecX& x, const std::string& why);

/// Rod i's Morse index with its couplings held in their link frames at the state x (the link poses at the
/// state's inputs, passive joint values and platform poses).
HeldRodIndex held_rod_in_robot(const RobotAssembly& assembly, const VecX& x, int rod);

/// The border's count (negative eigenvalues of the symmetrised reduced stiffness K below -tolerance,
/// neutral ones within it, in a balanced scaling) and margin (smallest eigenvalue of K's symmetric part),
/// added to s; false with s Unknown where K's asymmetry is too large to trust the count.
bool count_border(const MatX& K, Stability& s);

}  // namespace pcr::stability
