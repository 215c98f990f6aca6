// The verdict of an equilibrium the requested mesh cannot count, on a refined mesh (refined_verdict.hpp).
#include "refined_verdict.hpp"

#include <cstdio>
#include <memory>
#include <string>

#include "../stability/robot_stability_parts.hpp"
#include "coarse_continuation.hpp"
#include "pcr/core/error.hpp"
#include "pcr/solve/newton_solver.hpp"

namespace pcr::kinematics {

namespace {

bool unknown_by_asymmetry(const Stability& s) {
  return s.verdict == StabilityVerdict::Unknown && s.reason.rfind(stability::kAsymmetricBorder, 0) == 0;
}

/// Why the requested mesh gave no count, for the refined verdict's reason.
std::string requested_mesh_note(const Stability& s, const Stability& refined, int elements) {
  char note[200];
  if (unknown_by_asymmetry(s))
    std::snprintf(note, sizeof note,
                  "counted on %d elements per rod (asymmetry %.3g; %.3g on the requested mesh, not counted)",
                  elements, refined.asymmetry, s.asymmetry);
  else
    std::snprintf(note, sizeof note, "counted on %d elements per rod (on the requested mesh %s)", elements,
                  stability::kNoRitzEquilibrium);
  return note;
}

/// Whether `s` is unknown for a reason a finer mesh can resolve (refined_verdict.hpp).
bool unknown_on_this_mesh(const Stability& s) {
  return unknown_by_asymmetry(s) || (s.verdict == StabilityVerdict::Unknown &&
                                     s.reason.find(stability::kNoRitzEquilibrium) != std::string::npos);
}

}  // namespace

void refine_unknown_verdict(const RobotAssembly& assembly, const VecX& x, double tolerance, Stability& s) {
  if (!unknown_on_this_mesh(s)) return;
  AssemblyOptions o = assembly.options();
  o.discretization.elements *= 2;
  std::shared_ptr<const RobotAssembly> fine;
  try {
    fine = std::make_shared<const RobotAssembly>(assembly.model_ptr(), o);
  } catch (const InputError&) {
    return;
  }
  const MeshTransfer transfer(assembly, *fine);
  if (!transfer.valid()) return;
  VecX xf = transfer.apply(x.head(assembly.problem().num_variables()));
  NewtonOptions no;
  no.tolerance = tolerance;
  NewtonSolver newton(fine->problem(), no);
  if (!newton.solve(xf, 30).converged()) return;
  // The same equilibrium: every platform within 1e-3 of the length scale (the discretisation moves it by
  // micrometres; another equilibrium lies millimetres to centimetres away).
  const double near = 1e-3 * assembly.length_scale();
  for (int p = 0; p < static_cast<int>(assembly.model().platforms().size()); ++p)
    if ((fine->platform_pose(xf, p).position - assembly.platform_pose(x, p).position).norm() > near) return;
  Stability refined = robot_stability(*fine, xf);
  if (refined.verdict == StabilityVerdict::Unknown || refined.verdict == StabilityVerdict::NotChecked) return;
  const std::string note = requested_mesh_note(s, refined, o.discretization.elements);
  refined.reason = refined.reason.empty() ? note : refined.reason + "; " + note;
  s = refined;
}

}  // namespace pcr::kinematics
