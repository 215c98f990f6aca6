// Whether rods touch obstacles at a state (robot_stability_parts.hpp touching_contact).
#include <sstream>

#include "pcr/rods/rod_contact.hpp"
#include "robot_stability_parts.hpp"

namespace pcr::stability {

std::string touching_contact(const RobotAssembly& assembly, const VecX& x) {
  const double open = kTouchingGap * assembly.length_scale();
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
