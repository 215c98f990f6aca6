#pragma once
// Forward kinematics of an assembly whose contact rows are relaxed for Ipopt
// (AssemblyOptions::contact_method = Ipopt; contact_ipopt.hpp): the homotopy in the relaxation.
#include <memory>
#include <vector>

#include "pcr/robots/kinematics.hpp"
#include "pcr/rods/contact_ipopt.hpp"

namespace pcr::kinematics {

/// The relaxed contacts of the assembly's rods (empty for the semismooth treatment).
std::vector<const RodContactVariables*> relaxed_contacts(const RobotAssembly& assembly);

/// One FK solve along the homotopy (ContactIpoptOptions with the FK tolerance), with `solver` made on
/// first use and reused (warm starts). x: start in, solution out.
SolveSummary solve_relaxed_contact(const RobotAssembly& assembly, const KinematicsOptions& options,
                                   std::unique_ptr<IpoptSolver>& solver, VecX& x);

}  // namespace pcr::kinematics
