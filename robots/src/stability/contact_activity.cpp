// Whether rods touch obstacles at a state (robot_stability_parts.hpp touching_contact).
#include <sstream>

#include "pcr/rods/rod_contact.hpp"
#include "robot_stability_parts.hpp"

namespace pcr::stability {

namespace {

/// A contact row is open when its gap g exceeds this fraction of L0, the gap at which read_rod_contact
/// counts a cell as touching. There the complementarity row phi(a, b) (a = g / L0 >= 1e-6, b = lambda L0 /
/// F0 at the solver's residual tolerance, ~1e-10) has d phi / d a ~ b^2 / (2 a^2) < 1e-8 (Fischer-
/// Burmeister) or 0 (min): it reads d lambda = 0 and decouples from the rod's variation, and variations
/// small enough for the second variation keep the contact open.
constexpr double kOpenGap = 1e-6;

}  // namespace

std::string touching_contact(const RobotAssembly& assembly, const VecX& x) {
  const double open = kOpenGap * assembly.length_scale();
  for (int i = 0; i < assembly.num_rods(); ++i) {
    const RodContactVariables* contact = assembly.rod_contact(i);
    if (!contact) continue;
    const std::vector<ObstacleContact> contacts =
        read_rod_contact(assembly.rod(i), assembly.rod_variables(i), *contact, x);
    for (const ObstacleContact& c : contacts)
      for (std::size_t j = 0; j < c.gaps.size(); ++j) {
        if (c.gaps[j] > open) continue;
        std::ostringstream msg;
        msg << "rod '" << c.rod << "' touches obstacle '" << c.obstacle << "' (gap " << c.gaps[j]
            << " m at s = " << c.arc_lengths[j] << " m)";
        return msg.str();
      }
  }
  return "";
}

}  // namespace pcr::stability
