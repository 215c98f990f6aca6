// Forward kinematics with contact relaxed for Ipopt (contact_ipopt_fk.hpp).
#include "contact_ipopt_fk.hpp"

namespace pcr::kinematics {

std::vector<const RodContactVariables*> relaxed_contacts(const RobotAssembly& assembly) {
  std::vector<const RodContactVariables*> out;
  for (int i = 0; i < assembly.num_rods(); ++i) {
    const RodContactVariables* c = assembly.rod_contact(i);
    if (c != nullptr && c->relaxation >= 0) out.push_back(c);
  }
  return out;
}

SolveSummary solve_relaxed_contact(const RobotAssembly& assembly, const KinematicsOptions& options,
                                   std::unique_ptr<IpoptSolver>& solver, VecX& x) {
  ContactIpoptOptions o;
  o.tolerance = options.tolerance;
  if (!solver) solver = std::make_unique<IpoptSolver>(assembly.problem(), contact_ipopt_options(o));
  return solve_contact_homotopy(assembly.problem(), relaxed_contacts(assembly), *solver, o, x);
}

}  // namespace pcr::kinematics
