#pragma once
// The last FK strategy (fk_strategies.cpp): minimise the total potential energy at the requested inputs
// (energy_model.hpp) with Ipopt, then Newton on the collocation equations from the minimiser; accepted
// only when Newton converges to the full tolerance and the stability verdict (robot_stability.hpp; on twice
// the elements where the requested mesh cannot count, refined_verdict.hpp) is `stable`, or `unknown` only
// because a rod touches an obstacle (docs/design.md "Energy minimisation (the
// last FK strategy)"). Internal header of pcr::robots.
#include <string>
#include <vector>

#include "fk_data.hpp"
#include "pcr/rods/stability/stability.hpp"

namespace pcr::kinematics {

struct EnergyFallback {
  bool converged = false;             ///< Newton converged from a minimiser to an accepted verdict
  VecX x;                             ///< the equilibrium (converged only)
  SolveSummary summary;               ///< Newton's from the accepted minimiser
  Stability verdict;                  ///< of x (converged only): stable, or unknown (contact)
  std::string message;                ///< what each start reached, or why the model was skipped
  int iterations = 0, jacobians = 0;  ///< Newton's and Ipopt's, over all starts
};

/// A start: a collocation state (its inputs are overwritten by the requested ones) and what it is.
struct EnergyStart {
  const VecX* x;
  const char* name;
};

/// Tries the starts in order until one gives a stable equilibrium at the inputs; where none does, each
/// equilibrium Newton reached from a start's minimiser and the verdict refused, as one more start.
EnergyFallback minimise_energy_then_newton(FkData& data, const VecX& inputs,
                                           const std::vector<EnergyStart>& starts);

}  // namespace pcr::kinematics
