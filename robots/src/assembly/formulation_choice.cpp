#include <algorithm>
#include <cmath>

#include "pcr/core/error.hpp"
#include "pcr/robots/robot_assembly.hpp"

namespace pcr {

double gyration_ratio(const RodElement& rod) {
  const RodModel& m = rod.rod;
  const double EI = std::min(m.bending_torsion_stiffness[0], m.bending_torsion_stiffness[1]);
  const double EA = m.shear_extension_stiffness[2];
  const double L = rod.length_actuated ? std::max(rod.length_upper, m.length) : m.length;
  require(EI > 0.0 && EA > 0.0 && L > 0.0 && std::isfinite(EI / EA / L), "rod '", rod.name,
          "': cannot compute its slenderness (EI = ", EI, ", EA = ", EA, ", L = ", L, ")");
  return std::sqrt(EI / EA) / L;
}

RodFormulation formulation_by_slenderness(const RodElement& rod, double primal_min_gyration_ratio) {
  require(primal_min_gyration_ratio > 0.0,
          "AssemblyOptions: primal_min_gyration_ratio = ", primal_min_gyration_ratio,
          " (must be > 0; +infinity: always mixed)");
  return gyration_ratio(rod) >= primal_min_gyration_ratio ? RodFormulation::Primal : RodFormulation::Mixed;
}

}  // namespace pcr
