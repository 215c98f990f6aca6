#pragma once
// The verdict of an equilibrium that the requested mesh cannot count, taken again on a refined mesh
// (internal header of pcr::robots). Two `unknown` verdicts are discretisation errors that fall with the
// elements:
//  - the reduced stiffness K_red too asymmetric to count (docs/design.md §4): at strongly deformed states
//    of the default mesh the asymmetry can exceed 1e-3 (passive_hinge: 1.1e-4 at 8 elements per rod,
//    3.4e-7 at 16, 5.9e-9 at 32);
//  - a rod touching an obstacle whose energy's Ritz form (on which contact is counted) has no equilibrium
//    next to the collocation's: a rod curled at few elements, where the two discretisations of the same
//    knots differ by more than Newton on the Ritz form bridges (planar_post);
//  - the same for a rod counted at a conjugate point with its links held because its probe eigenvalue lies
//    within the mesh's neutral tolerance, which grows with the state's strain mismatch (universal_pair:
//    8.9e-6 within 1.9e-5 at 8 elements per rod, 3.4e-5 clear of 1e-5 at 16).
// The state is carried to twice the elements per rod (rods whose model gives no element count;
// interpolation at the finer mesh's Greville abscissae: the same curves), Newton converges there to the
// same equilibrium (its platforms within 1e-3 of the length scale), and that equilibrium's verdict is
// reported, saying so.
#include "pcr/robots/robot_assembly.hpp"
#include "pcr/robots/robot_stability.hpp"

namespace pcr::kinematics {

/// The verdict of the equilibrium x of `assembly` (at its inputs) on 2x the elements per rod where `s` is
/// unknown for a reason a finer mesh can resolve (above); `s` unchanged where the refined solve or its
/// verdict does not give a count.
/// tolerance: Newton's there.
void refine_unknown_verdict(const RobotAssembly& assembly, const VecX& x, double tolerance, Stability& s);

}  // namespace pcr::kinematics
