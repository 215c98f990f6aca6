#pragma once
// Rotations of non-unit quaternions and strains for any scalar (double or pcr::Dual), shared by the
// energy terms (energy_terms.hpp; internal header of pcr::robots): the collocation equations' own
// R(q) = R_unit(q) / |q|^2 and body curvature u = 2 vec(conj(q) (x) q_s) / |q|^2 (equations.hpp).
#include "pcr/math/dual.hpp"
#include "pcr/rods/collocation/equations.hpp"

namespace pcr::kinematics {

using collocation::M3;
using collocation::V3;
using collocation::V4;

}  // namespace pcr::kinematics
