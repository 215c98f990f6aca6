#pragma once
// Private to pcr_rods: an initial guess for a cold collocation solve from a coarse shooting solve.
#include <optional>

#include "pcr/rods/collocation_rod.hpp"

namespace pcr::collocation {

/// A rod configuration (CollocationRod::configuration_size) interpolating, at the Greville abscissae, a
/// shooting solution of the rod's model at loose tolerances (shooting_start.cpp); empty when that
/// solve does not converge or the model is one the start does not serve (drawn rods).
std::optional<VecX> shooting_start(const CollocationRod& rod);

}  // namespace pcr::collocation
