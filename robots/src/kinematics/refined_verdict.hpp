#pragma once
// The verdict of an equilibrium whose reduced stiffness is too asymmetric to count, taken again on a
// refined mesh (internal header of pcr::robots). The asymmetry of K_red is the collocation's
// discretisation error (docs/design.md §4): at strongly deformed states of the default mesh it can exceed
// 1e-3, and it falls fast with the elements (passive_hinge: 1.1e-4 at 8 elements per rod, 3.4e-7 at 16,
// 5.9e-9 at 32). The state is carried to twice the elements per rod (interpolation at the finer mesh's
// Greville abscissae: the same curves), Newton converges there to the same equilibrium (its platforms
// within 1e-3 of the length scale), and that equilibrium's verdict is reported, saying so.
#include "pcr/robots/robot_assembly.hpp"
#include "pcr/robots/robot_stability.hpp"

namespace pcr::kinematics {

/// Whether `s` is unknown only because the border's reduced stiffness is too asymmetric.
bool unknown_by_asymmetry(const Stability& s);

/// The verdict of the equilibrium x of `assembly` (at its inputs) on 2x the elements per rod; `s`
/// unchanged where the refined solve or its verdict does not give a count. tolerance: Newton's there.
void refine_asymmetric_verdict(const RobotAssembly& assembly, const VecX& x, double tolerance, Stability& s);

}  // namespace pcr::kinematics
