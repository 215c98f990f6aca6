// The shared default equilibrium and its registry (default_equilibrium.hpp).
#include "default_equilibrium.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "contact_ipopt_fk.hpp"
#include "pcr/robots/robot_stability.hpp"
#include "solve_support.hpp"

namespace pcr::kinematics {

namespace {

/// The fields of KinematicsOptions that the default equilibrium's solve reads (newton_options,
/// ipopt_options, solve_relaxed_contact): equal in both, the solve is the same.
bool equal_solver_options(const KinematicsOptions& a, const KinematicsOptions& b) {
  return a.solver == b.solver && a.tolerance == b.tolerance && a.max_iterations == b.max_iterations &&
         a.reuse_factorization == b.reuse_factorization && a.linear_solver == b.linear_solver;
}

/// The same model object: one owner (control block, kept by the weak_ptr: no other object can take its
/// place while the entry exists) and one address (aliasing pointers of one owner may point to several).
bool same_model(const std::weak_ptr<const RobotModel>& a, const RobotModel* a_address,
                const std::weak_ptr<const RobotModel>& b, const RobotModel* b_address) {
  return a_address == b_address && !a.owner_before(b) && !b.owner_before(a);
}

struct RegistryEntry {
  std::weak_ptr<const RobotModel> model;
  const RobotModel* model_address;  // compared only, never dereferenced
  AssemblyOptions assembly_options;
  KinematicsOptions options;  // equal_solver_options decides
  std::shared_ptr<SharedDefaultEquilibrium> equilibrium;
};

struct Registry {
  std::mutex mutex;
  std::vector<RegistryEntry> entries;  // a handful of models at a time: a linear search
};

Registry& registry() {
  static Registry r;  // thread-safe initialisation (C++11)
  return r;
}

}  // namespace

const DefaultEquilibrium& SharedDefaultEquilibrium::get(
    const RobotAssembly& assembly, const KinematicsOptions& options, bool* solved_here,
    const std::function<void(SolveSummary&)>& then_solve) {
  if (solved_here) *solved_here = false;
  std::call_once(solved_, [&] {
    if (solved_here) *solved_here = true;
    VecX x = assembly.initial_guess();
    assembly.set_inputs(x, assembly.model().default_input_values());
    value_.x = x;
    if (options.solver == SolverKind::Newton) {
      NewtonSolver newton(assembly.problem(), newton_options(options));
      value_.summary = newton.solve(x);
    } else if (!relaxed_contacts(assembly).empty()) {
      std::unique_ptr<IpoptSolver> ipopt;
      value_.summary = solve_relaxed_contact(assembly, options, ipopt, x);
    } else {
      IpoptSolver ipopt(assembly.problem(), ipopt_options(options));
      value_.summary = ipopt.solve(x);
    }
    value_.converged = value_.summary.converged() && x.allFinite();
    if (value_.converged) value_.x = std::move(x);
    if (then_solve) then_solve(value_.summary);
  });
  return value_;
}

int SharedDefaultEquilibrium::unstable_modes(const RobotAssembly& assembly) {
  std::call_once(counted_, [&] {
    if (value_.converged) unstable_modes_ = definite_unstable_modes(robot_stability(assembly, value_.x));
  });
  return unstable_modes_;
}

std::shared_ptr<SharedDefaultEquilibrium> shared_default_equilibrium(const RobotAssembly& assembly,
                                                                     const KinematicsOptions& options) {
  const std::weak_ptr<const RobotModel> model = assembly.model_ptr();
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<RegistryEntry>& entries = r.entries;
  entries.erase(std::remove_if(entries.begin(), entries.end(),
                               [](const RegistryEntry& e) { return e.model.expired(); }),
                entries.end());
  for (const RegistryEntry& e : entries)
    if (same_model(e.model, e.model_address, model, &assembly.model()) &&
        e.assembly_options == assembly.options() && equal_solver_options(e.options, options))
      return e.equilibrium;
  entries.push_back(
      {model, &assembly.model(), assembly.options(), options, std::make_shared<SharedDefaultEquilibrium>()});
  return entries.back().equilibrium;
}

}  // namespace pcr::kinematics
