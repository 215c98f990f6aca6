#pragma once
// The equilibrium at a model's default inputs (DefaultEquilibrium, kinematics.hpp), the start of cold
// forward kinematics solves (fk_strategies.cpp), shared per model and options (internal header of
// pcr::robots). Its solve is about half of the instructions of a cold stewart_gough FK object (assembly,
// default equilibrium, solve from it; callgrind): FK objects after the first over a model skip it.
//
// The registry (one per process) keys each equilibrium by the model object (its std::shared_ptr's
// control block, held as a weak_ptr: the registry never keeps a model alive, and a dead model's entry is
// dropped at the next look-up, and its address) and by the options it depends on (AssemblyOptions'
// operator==, equal_solver_options). It holds the state only, no assembly (an assembly owns its model),
// so each FK object still builds or shares its own assembly.
#include <functional>
#include <memory>
#include <mutex>

#include "pcr/robots/kinematics.hpp"

namespace pcr::kinematics {

/// One default equilibrium, solved by the first caller of get (std::call_once: callers in other threads
/// wait for it, and every caller sees the same bits); read-only after that.
class SharedDefaultEquilibrium {
 public:
  /// Solves it on `assembly` with `options` on the first call (any assembly of the model with the
  /// options of the registry's key: they are the same system); returns it on every call. *solved_here
  /// (when given) tells whether this call did the solve (its work belongs to the caller's summary).
  /// then_solve (when given) runs once right after the solve, with the summary to add its own work to
  /// (the coarse mesh's default equilibrium, coarse_continuation.hpp: solved and counted with this one).
  const DefaultEquilibrium& get(const RobotAssembly& assembly, const KinematicsOptions& options,
                                bool* solved_here = nullptr,
                                const std::function<void(SolveSummary&)>& then_solve = {});
  /// The equilibrium's unstable modes (robot_stability on `assembly`, any assembly of the model as for
  /// get; -1 where it did not converge or the verdict is not a count), counted on the first call
  /// (std::call_once, as get). Call after get.
  int unstable_modes(const RobotAssembly& assembly);

 private:
  std::once_flag solved_, counted_;
  DefaultEquilibrium value_;
  int unstable_modes_ = -1;
};

/// The shared default equilibrium of the assembly's model and of the options that shape it (the
/// assembly's own options, and those of `options` that the solve reads); a new one for a model or
/// options not seen yet. options.solver: the effective one (Ipopt where contacts are relaxed).
std::shared_ptr<SharedDefaultEquilibrium> shared_default_equilibrium(const RobotAssembly& assembly,
                                                                     const KinematicsOptions& options);

}  // namespace pcr::kinematics
