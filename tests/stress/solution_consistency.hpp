#pragma once
// The global consistency of a converged robot solution, recomputed from the RobotSolution and the model
// alone (not from the solver's residuals): rod lengths against the inputs, rod ends at their attachments,
// every platform's force and moment balance, the centerline's length against the admissible arc length,
// the passive joints' balances, and finite values.
#include "pcr/robots/kinematics.hpp"

namespace pcr::test {

/// Worst violations of the global checks of one converged solution (0 = exact).
struct Consistency {
  double length = 0.0;     ///< |rod length - input| [m]
  double coupling = 0.0;   ///< |rod end position - attachment position| [m]
  double force = 0.0;      ///< |platform force balance| [N]
  double moment = 0.0;     ///< |platform moment balance| [N m]
  double stretch = 0.0;    ///< polyline length / admissible arc length - 1 (> 0 means too long)
  double magnitude = 0.0;  ///< largest sum of |force terms| on one platform [N] (round-off scale)
  double passive_moment = 0.0, passive_force = 0.0;  ///< |passive joint balance| [N m], [N]
  bool finite = true;
};

/// Recomputes, from the RobotSolution alone (and the model), what a converged result must satisfy.
/// Sign conventions (kinematics.hpp, docs/design.md §3): the rod exerts +n(0), +m(0) on its start link at
/// p(0) and -n(L), -m(L) on its end link at p(L); platform balance about the platform origin x:
///   m g + F_ext + sum_start n(0) - sum_end n(L) = 0,
///   (R c) x m g + sum (r_load x F + T) + sum_start [m(0) + (p(0) - x) x n(0)]
///                                      - sum_end [m(L) + (p(L) - x) x n(L)] = 0.
Consistency check_solution(const RobotModel& model, const RobotSolution& s);

}  // namespace pcr::test
